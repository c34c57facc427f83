// A small SVG line-plot writer for the experiment figures (no browser, no dependencies): linear or
// log-scale axes with ticks, a legend, solid or dashed polylines, optional markers.
//
//   writeFileSync('fig.svg', linePlot({ title, xLabel, yLabel, logY: true,
//     series: [{ name: 'subspace', x: [1, 2, 3], y: [1, 0.1, 0.01] }] }));

const PALETTE = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#17becf', '#7f7f7f'];

const escape = (s) => String(s).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');

function niceLinearTicks(lo, hi, count = 8) {
  if (!(hi > lo)) return [lo];
  const raw = (hi - lo) / count;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((k) => k * mag).find((s) => s >= raw) ?? 10 * mag;
  const ticks = [];
  for (let t = Math.ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) ticks.push(+t.toPrecision(12));
  return ticks;
}

function logTicks(lo, hi) {
  const ticks = [];
  for (let e = Math.floor(Math.log10(lo)); e <= Math.ceil(Math.log10(hi)); ++e) {
    const t = 10 ** e;
    if (t >= lo * (1 - 1e-9) && t <= hi * (1 + 1e-9)) ticks.push(t);
  }
  return ticks;
}

function label(t) {
  if (t === 0) return '0';
  const a = Math.abs(t);
  if (a >= 1e4 || a < 1e-3) {
    const e = Math.floor(Math.log10(a));
    const m = t / 10 ** e;
    return Math.abs(m - 1) < 1e-9 ? `1e${e}` : `${+m.toFixed(1)}e${e}`;
  }
  return String(+t.toPrecision(4));
}

/**
 * @param {{ title?: string, xLabel?: string, yLabel?: string, logX?: boolean, logY?: boolean,
 *   width?: number, height?: number,
 *   series: { name: string, x: number[], y: number[], color?: string, dash?: boolean, markers?: boolean }[] }} spec
 * @returns {string} SVG document
 */
export function linePlot(spec) {
  const width = spec.width ?? 640, height = spec.height ?? 400;
  const m = { left: 72, right: 16, top: spec.title ? 34 : 14, bottom: 48 };
  const pw = width - m.left - m.right, ph = height - m.top - m.bottom;
  const valid = (v, log) => Number.isFinite(v) && (!log || v > 0);
  const xs = [], ys = [];
  for (const s of spec.series) {
    s.x.forEach((x, i) => {
      if (valid(x, spec.logX) && valid(s.y[i], spec.logY)) { xs.push(x); ys.push(s.y[i]); }
    });
  }
  if (xs.length === 0) { xs.push(spec.logX ? 1 : 0, spec.logX ? 10 : 1); ys.push(spec.logY ? 1 : 0, spec.logY ? 10 : 1); }
  let [x0, x1] = [Math.min(...xs), Math.max(...xs)];
  let [y0, y1] = [Math.min(...ys), Math.max(...ys)];
  if (spec.logY) { y0 = 10 ** Math.floor(Math.log10(y0)); y1 = 10 ** Math.ceil(Math.log10(y1)); if (y1 === y0) y1 *= 10; }
  else { if (y1 === y0) y1 = y0 + 1; const pad = 0.05 * (y1 - y0); y0 -= pad; y1 += pad; }
  if (spec.logX) { x0 = 10 ** Math.floor(Math.log10(x0)); x1 = 10 ** Math.ceil(Math.log10(x1)); if (x1 === x0) x1 *= 10; }
  else if (x1 === x0) x1 = x0 + 1;
  const tx = (x) => m.left + pw * (spec.logX ? Math.log10(x / x0) / Math.log10(x1 / x0) : (x - x0) / (x1 - x0));
  const ty = (y) => m.top + ph * (1 - (spec.logY ? Math.log10(y / y0) / Math.log10(y1 / y0) : (y - y0) / (y1 - y0)));
  const f = (v) => v.toFixed(1);
  const out = [];
  out.push(`<svg xmlns="http://www.w3.org/2000/svg" width="${width}" height="${height}" viewBox="0 0 ${width} ${height}" font-family="Helvetica, Arial, sans-serif" font-size="12">`);
  out.push(`<rect width="${width}" height="${height}" fill="white"/>`);
  if (spec.title) {
    // Shrink long titles to fit the width (about 0.55 em per character in Helvetica bold).
    const size = Math.min(14, (width - 8) / (0.6 * spec.title.length)).toFixed(1);
    out.push(`<text x="${width / 2}" y="20" text-anchor="middle" font-size="${size}" font-weight="bold">${escape(spec.title)}</text>`);
  }
  // Grid and ticks.
  const xt = spec.logX ? logTicks(x0, x1) : niceLinearTicks(x0, x1);
  const yt = spec.logY ? logTicks(y0, y1) : niceLinearTicks(y0, y1);
  for (const t of xt) {
    out.push(`<line x1="${f(tx(t))}" y1="${m.top}" x2="${f(tx(t))}" y2="${m.top + ph}" stroke="#e6e6e6"/>`);
    out.push(`<text x="${f(tx(t))}" y="${m.top + ph + 16}" text-anchor="middle">${label(t)}</text>`);
  }
  for (const t of yt) {
    out.push(`<line x1="${m.left}" y1="${f(ty(t))}" x2="${m.left + pw}" y2="${f(ty(t))}" stroke="#e6e6e6"/>`);
    out.push(`<text x="${m.left - 6}" y="${f(ty(t) + 4)}" text-anchor="end">${label(t)}</text>`);
  }
  out.push(`<rect x="${m.left}" y="${m.top}" width="${pw}" height="${ph}" fill="none" stroke="#333"/>`);
  if (spec.xLabel) out.push(`<text x="${m.left + pw / 2}" y="${height - 10}" text-anchor="middle">${escape(spec.xLabel)}</text>`);
  if (spec.yLabel) {
    out.push(`<text transform="translate(16 ${m.top + ph / 2}) rotate(-90)" text-anchor="middle">${escape(spec.yLabel)}</text>`);
  }
  // Series, clipped to the plot area.
  out.push(`<clipPath id="plot"><rect x="${m.left}" y="${m.top}" width="${pw}" height="${ph}"/></clipPath>`);
  out.push('<g clip-path="url(#plot)">');
  spec.series.forEach((s, k) => {
    const color = s.color ?? PALETTE[k % PALETTE.length];
    const pts = s.x.map((x, i) => [x, s.y[i]]).filter(([x, y]) => valid(x, spec.logX) && valid(y, spec.logY));
    if (pts.length === 0) return;
    const d = pts.map(([x, y]) => `${f(tx(x))},${f(ty(y))}`).join(' ');
    out.push(`<polyline points="${d}" fill="none" stroke="${color}" stroke-width="2"${s.dash ? ' stroke-dasharray="6 4"' : ''}/>`);
    if (s.markers ?? pts.length <= 40) {
      for (const [x, y] of pts) out.push(`<circle cx="${f(tx(x))}" cy="${f(ty(y))}" r="2.5" fill="${color}"/>`);
    }
  });
  out.push('</g>');
  // Legend (top right, inside the plot).
  const lw = 12 + 7 * Math.max(...spec.series.map((s) => s.name.length), 4) + 30;
  const lx = m.left + pw - lw - 8, ly = m.top + 8;
  out.push(`<rect x="${lx}" y="${ly}" width="${lw}" height="${8 + 18 * spec.series.length}" fill="white" fill-opacity="0.9" stroke="#999"/>`);
  spec.series.forEach((s, k) => {
    const color = s.color ?? PALETTE[k % PALETTE.length];
    const y = ly + 16 + 18 * k;
    out.push(`<line x1="${lx + 8}" y1="${y - 4}" x2="${lx + 32}" y2="${y - 4}" stroke="${color}" stroke-width="2"${s.dash ? ' stroke-dasharray="6 4"' : ''}/>`);
    out.push(`<text x="${lx + 38}" y="${y}">${escape(s.name)}</text>`);
  });
  out.push('</svg>');
  return out.join('\n') + '\n';
}
