// The integration table of scripts/bench.mjs (docs/benchmarks.md, "Cost of an iteration against n"): what a
// drag iteration costs as the mesh grows with the subspace fixed (m = 100), with the Laplacian term summed over
// every vertex ('full') and over the reduced integration's samples ('reduced'), in wasm (binding
// benchIntegration) and natively (cpp/tools/bench_integration.cpp), both running cpp/tools/bench_integration.h.
// W is stored in single precision above 128 MB in double, as the app's worker does. Beside each iteration: one
// pass over W at the machine's streaming read bandwidth, the floor a frame cannot go below (X = W P is drawn).
import { execFileSync } from 'node:child_process';
import { singlePrecisionPays } from 'subspace-deform';
import { linePlot } from '../experiments/svg_plot.mjs';

export const DEFAULT_SIZES = [5000, 20000, 51000, 100000, 280000, 1000000];
export const QUICK_SIZES = [5000, 51000, 280000];
const SEGMENTS = 24; // m = 4 (24 + 1) = 100 cage vertices
const SOLVE_MAX_N = 300000; // converged solves (the shape difference) up to here; beyond, the drag only

function caseFor(n) {
  const float32 = singlePrecisionPays(n, 4 * (SEGMENTS + 1)); // as the worker chooses
  return { n, segments: SEGMENTS, frames: 9, float32, solve: n <= SOLVE_MAX_N };
}

function runNativeCase(bin, c, env) {
  const args = ['--frames', c.frames, ...(c.float32 ? ['--float32'] : []), ...(c.solve ? [] : ['--no-solve']),
    `${c.n}:${c.segments}`].map(String);
  const text = execFileSync(bin, args, { encoding: 'utf8', maxBuffer: 1 << 24, env });
  return JSON.parse(text.trim().split('\n').pop());
}

/**
 * Runs every size in wasm (`solver` with the bench bindings) and, when `nativeBin` is given, natively.
 * @returns {{ n: number, wasm: object, native: object|null }[]}
 */
export function runIntegration({ solver, nativeBin, nativeEnv, sizes, log }) {
  return sizes.map((n) => {
    const c = caseFor(n);
    const wasm = solver.benchIntegration(c);
    const native = nativeBin ? runNativeCase(nativeBin, c, nativeEnv) : null;
    log(`integration n=${wasm.n}: full ${wasm.fullIterationMs.toFixed(1)} ms, reduced ${wasm.reducedIterationMs.toFixed(1)} ms per ` +
      `iteration (wasm)${native ? `; ${native.fullIterationMs.toFixed(1)} / ${native.reducedIterationMs.toFixed(1)} ms native` : ''}`);
    return { n: wasm.n, wasm, native };
  });
}

const fixed = (v, digits) => (Number.isFinite(v) ? v.toFixed(digits) : '-');
const exp = (v) => (Number.isFinite(v) ? v.toExponential(1) : '-');

/** Markdown table: one row per size, wasm and native side by side, the W pass floor from `readGBs`. */
export function formatIntegration(rows, { readGBsWasm, readGBsNative }) {
  const lines = [
    '| n | W MB | W pass floor ms (wasm / native) | full ms/it wasm | reduced ms/it wasm | reduced / full | full ms/it native | reduced ms/it native | reduced / full | samples | fit ms (wasm) | reduced vs full shape (of the diagonal) | volume error full / reduced |',
    '|---|---|---|---|---|---|---|---|---|---|---|---|---|',
  ];
  for (const { wasm: w, native: nat } of rows) {
    const mb = w.wBytes / 1e6;
    const floor = (gbs) => (gbs ? fixed(mb / gbs, 1) : '-');
    lines.push(`| ${w.n} | ${fixed(mb, 0)}${w.float32 ? ' (float32)' : ''} | ${floor(readGBsWasm)} / ${floor(readGBsNative)} ` +
      `| ${fixed(w.fullIterationMs, 1)} | ${fixed(w.reducedIterationMs, 1)} | ${fixed(w.reducedIterationMs / w.fullIterationMs, 2)} ` +
      `| ${fixed(nat?.fullIterationMs, 1)} | ${fixed(nat?.reducedIterationMs, 1)} | ${fixed(nat?.reducedIterationMs / nat?.fullIterationMs, 2)} ` +
      `| ${w.dragSamples} | ${fixed(w.fitMs, 0)} | ${exp(w.shapeDifference)} | ${exp(w.fullVolumeRelError)} / ${exp(w.reducedVolumeRelError)} |`);
  }
  return lines.join('\n');
}

/** The goals of the integration (docs/benchmarks.md): met, missed or n/a, per build. */
export function integrationGoals(rows) {
  const goals = [];
  for (const build of ['wasm', 'native']) {
    const at = (n) => rows.find((r) => Math.abs(r.n - n) / n < 0.1)?.[build];
    const mid = at(51000), big = at(280000);
    goals.push({
      goal: `${build}: a reduced iteration at 51k <= 0.25 of a full one`,
      met: mid ? mid.reducedIterationMs <= 0.25 * mid.fullIterationMs : null,
      detail: mid ? `${fixed(mid.reducedIterationMs, 1)} / ${fixed(mid.fullIterationMs, 1)} ms` : 'no 51k case',
    });
    goals.push({
      goal: `${build}: a reduced iteration at 280k <= 0.5 of a full one at 51k`,
      met: mid && big ? big.reducedIterationMs <= 0.5 * mid.fullIterationMs : null,
      detail: mid && big ? `${fixed(big.reducedIterationMs, 1)} / ${fixed(mid.fullIterationMs, 1)} ms` : 'no 51k or 280k case',
    });
    const solved = rows.map((r) => r[build]).filter((r) => r && Number.isFinite(r.shapeDifference));
    goals.push({
      goal: `${build}: the converged reduced shape within 5e-3 of the diagonal of the full one; volume error <= 1e-9 in both`,
      met: solved.length ? solved.every((r) => r.shapeDifference <= 5e-3 && Math.abs(r.fullVolumeRelError) <= 1e-9
        && Math.abs(r.reducedVolumeRelError) <= 1e-9) : null,
      detail: solved.map((r) => `${r.n}: ${exp(r.shapeDifference)}`).join(', '),
    });
  }
  return goals;
}

/** Log-log plot of ms per iteration against n: full and reduced, wasm and native, and the W pass floor. */
export function integrationPlot(rows, { readGBsWasm }) {
  const n = rows.map((r) => r.n);
  const series = [
    { name: 'full, wasm', x: n, y: rows.map((r) => r.wasm.fullIterationMs), color: '#d62728', markers: true },
    { name: 'reduced, wasm', x: n, y: rows.map((r) => r.wasm.reducedIterationMs), color: '#1f77b4', markers: true },
  ];
  if (rows.every((r) => r.native)) {
    series.push({ name: 'full, native', x: n, y: rows.map((r) => r.native.fullIterationMs), color: '#d62728', dash: true, markers: true });
    series.push({ name: 'reduced, native', x: n, y: rows.map((r) => r.native.reducedIterationMs), color: '#1f77b4', dash: true, markers: true });
  }
  if (readGBsWasm) {
    series.push({ name: 'one pass over W (wasm read bandwidth)', x: n, y: rows.map((r) => r.wasm.wBytes / 1e6 / readGBsWasm), color: '#7f7f7f', dash: true });
  }
  return linePlot({ title: 'ms per drag iteration against mesh size (m = 100)', xLabel: 'mesh vertices n', yLabel: 'ms per iteration',
    logX: true, logY: true, series });
}
