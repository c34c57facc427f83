// The thread-scaling table of scripts/bench.mjs: one case (default n = 50k, m = 300) timed with 1, 2, 4, 8
// and 16 threads where the machine has the cores, in wasm (the threaded Node build, setThreads) and natively
// (bench_native_cases --threads). Speed-ups are against 1 thread of the same build; "CPU / wall" is the
// process's CPU time over the wall time of the wasm case (about the number of threads kept busy: evidence
// that the worker_threads really run at once, whatever the load does to the wall time).
import { Timer } from '../lib/timer.mjs';

const METRICS = [
  ['passMs', 'W pass y = W p (3 columns)'],
  ['transposePassMs', 'W pass W^T r (3 columns)'],
  ['transposePass6Ms', 'W pass W^T r (6 columns)'],
  ['productMs', 'product W^T J^T J W V'],
  ['stepMs', 'interactive step'],
  ['solveMs', 'converged solve'],
  ['bindMs', 'bind (mean value coordinates)'],
  ['arapIterationMs', 'ARAP iteration'],
  ['fullIterationMs', 'full-space iteration (fast)'],
];

/** Thread counts to measure: 1, 2, 4, 8, 16 up to the cores (and the core count itself). */
export function defaultThreadCounts(cores) {
  const counts = [1, 2, 4, 8, 16].filter((t) => t <= cores);
  if (cores <= 16 && !counts.includes(cores)) counts.push(cores);
  return counts;
}

/**
 * @param {{ solver, runNative: (opts, threads) => object|null, opts: object, threads: number[], rounds: number,
 *   medianFields: (list) => object, log: (line: string) => void }} p
 * @returns {{ threads: number[], wasm: object[], native: (object|null)[], cpuOverWall: number[] }}
 */
export function runScaling({ solver, runNative, opts, threads, rounds, medianFields, log }) {
  const perThreads = threads.map(() => ({ wasm: [], native: [], cpuOverWall: [] }));
  for (let round = 1; round <= rounds; ++round) {
    threads.forEach((t, index) => {
      const got = solver.setThreads(t);
      if (got !== t) throw new Error(`the wasm build runs ${got} threads, not ${t} (its pool is smaller)`);
      const cpu0 = process.cpuUsage();
      const timer = new Timer();
      perThreads[index].wasm.push(solver.benchCase(opts));
      const wall = timer.ms();
      const cpu = process.cpuUsage(cpu0);
      perThreads[index].cpuOverWall.push((cpu.user + cpu.system) / 1e3 / wall);
      const native = runNative(opts, t);
      if (native) perThreads[index].native.push(native);
      log(`scaling round ${round}/${rounds}, ${t} thread${t > 1 ? 's' : ''}: wasm ${(wall / 1e3).toFixed(0)} s`);
    });
  }
  solver.setThreads(0);
  const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor((xs.length - 1) / 2)];
  return {
    threads,
    wasm: perThreads.map((r) => medianFields(r.wasm)),
    native: perThreads.map((r) => (r.native.length ? medianFields(r.native) : null)),
    cpuOverWall: perThreads.map((r) => median(r.cpuOverWall)),
  };
}

const fmt = (x, digits) => (Number.isFinite(x) ? x.toFixed(digits) : '-');
const digitsFor = (ms) => (ms >= 100 ? 0 : ms >= 10 ? 1 : 2);

/** Markdown: one row per operation, per thread count "wasm ms (xS) / native ms (xS)". */
export function formatScaling(s) {
  const head = ['operation', ...s.threads.map((t) => `${t} thread${t > 1 ? 's' : ''}: wasm / native ms (speed-up)`)];
  const cell = (run, base, key) => {
    if (!run || !Number.isFinite(run[key])) return '-';
    const speedup = base && Number.isFinite(base[key]) ? ` (${(base[key] / run[key]).toFixed(2)}x)` : '';
    return `${fmt(run[key], digitsFor(run[key]))}${speedup}`;
  };
  const rows = METRICS.filter(([key]) => s.wasm.some((w) => Number.isFinite(w[key]))).map(([key, label]) => [
    label,
    ...s.threads.map((_, i) => `${cell(s.wasm[i], s.wasm[0], key)} / ${cell(s.native[i], s.native[0], key)}`),
  ]);
  rows.push(['CPU / wall (wasm case)', ...s.cpuOverWall.map((x) => fmt(x, 2))]);
  return [head, head.map(() => '---'), ...rows].map((r) => `| ${r.join(' | ')} |`).join('\n');
}
