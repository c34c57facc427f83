// A small canvas plot of merit against iteration (log scale), redrawn when new iterations arrive. It draws
// one series: the current method's since the last load, method switch or re-solve (merits of different
// methods are different functions), titled with the method. `shown` says what it drew (for tests).
export class ConvergencePlot {
  constructor({ width = 220, height = 90, color = '#f08a24' } = {}) {
    this.canvas = document.createElement('canvas');
    this.canvas.className = 'sd-plot';
    this.canvas.width = width * (globalThis.devicePixelRatio > 1 ? 2 : 1);
    this.canvas.height = height * (globalThis.devicePixelRatio > 1 ? 2 : 1);
    this.canvas.style.width = `${width}px`;
    this.canvas.style.height = `${height}px`;
    this.color = color;
    this.maxPoints = 400;
    /** @type {{ label: string, points: number, first: number, last: number }|null} */
    this.shown = null;
  }

  /**
   * @param {{ iteration: number, merit: number }[]} history one series
   * @param {{ label?: string, color?: string }} [series] its method's name and colour
   */
  draw(history, { label: title = '', color = this.color } = {}) {
    this.color = color;
    const ctx = this.canvas.getContext('2d');
    const w = this.canvas.width;
    const h = this.canvas.height;
    const s = w / parseFloat(this.canvas.style.width);
    ctx.clearRect(0, 0, w, h);
    ctx.fillStyle = 'rgba(255,255,255,0.85)';
    ctx.fillRect(0, 0, w, h);
    ctx.font = `${10 * s}px system-ui, sans-serif`;
    ctx.fillStyle = '#445';
    const points = history.slice(-this.maxPoints).filter((p) => Number.isFinite(p.merit) && p.merit > 0);
    const heading = `${title ? `${title}: ` : ''}merit (log) vs iteration`;
    ctx.fillText(heading, 6 * s, 11 * s);
    this.shown = { label: title, points: points.length, first: points[0]?.iteration ?? 0, last: points.at(-1)?.iteration ?? 0 };
    if (points.length < 1) return;
    let lo = Infinity;
    let hi = -Infinity;
    for (const p of points) {
      const l = Math.log10(p.merit);
      lo = Math.min(lo, l);
      hi = Math.max(hi, l);
    }
    // A solve starting from an exact minimizer has merits near 1e-30: show the last 10 decades only.
    lo = Math.max(lo, hi - 10);
    if (hi - lo < 1e-6) {
      hi += 0.5;
      lo -= 0.5;
    }
    const left = 44 * s;
    const top = 18 * s;
    const bottom = h - 14 * s;
    const right = w - 6 * s;
    const first = points[0].iteration;
    const last = Math.max(points[points.length - 1].iteration, first + 1);
    const x = (it) => left + ((it - first) / (last - first)) * (right - left);
    const y = (m) => bottom - ((Math.max(Math.log10(m), lo) - lo) / (hi - lo)) * (bottom - top);
    ctx.strokeStyle = '#ccd';
    ctx.lineWidth = 1 * s;
    ctx.beginPath();
    for (let d = Math.ceil(lo); d <= Math.floor(hi); ++d) {
      ctx.moveTo(left, y(10 ** d));
      ctx.lineTo(right, y(10 ** d));
    }
    ctx.stroke();
    const label = (e) => (hi - lo >= 2 ? `1e${Math.round(e)}` : (10 ** e).toExponential(1).replace('e+', 'e'));
    ctx.fillText(label(hi), 2 * s, top + 8 * s);
    ctx.fillText(label(lo), 2 * s, bottom);
    ctx.fillText(`iter ${first}`, left, h - 3 * s);
    const lastLabel = `${last}`;
    ctx.fillText(lastLabel, right - ctx.measureText(lastLabel).width, h - 3 * s);
    ctx.strokeStyle = this.color;
    ctx.lineWidth = 1.5 * s;
    ctx.beginPath();
    points.forEach((p, i) => (i ? ctx.lineTo(x(p.iteration), y(p.merit)) : ctx.moveTo(x(p.iteration), y(p.merit))));
    ctx.stroke();
    if (points.length === 1) {
      ctx.fillStyle = this.color;
      ctx.fillRect(x(points[0].iteration) - 2 * s, y(points[0].merit) - 2 * s, 4 * s, 4 * s);
    }
  }
}
