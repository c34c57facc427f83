// Solver benchmark against the memory-bandwidth floor and the speed goals (docs/benchmarks.md).
//
//   npm run bench -- [--quick] [--json FILE] [--no-native] [--native-bin PATH] [--cases 5000:24,50000:74:f32]
//                    [--scaling n:segments | --no-scaling] [--threads 1,2,4]
//                    [--integration 5000,51000,... | --no-integration] [--plot FILE.svg]
//
// Each case is a capsule bar of about n vertices in a bar cage of m = 4 (segments + 1) vertices, bent at one
// end (cpp/tools/bench_case.h). The same C++ case runner is timed inside wasm (binding benchCase, from
// cpp/tools/wasm/bench_bindings.cpp) and natively (cpp/tools/bench_native_cases), so the wasm/native ratio
// compares identical code. Medians of several runs; the machine may be shared, so the load average is
// recorded with the numbers. A case "n:segments:f32" stores W in float32 (half the bytes per pass).
//   --quick       under 4 minutes: n = 5k and 50k, fewer repeats, one round
//   --rounds K    run the whole case list K times (default 3, --quick 1) and keep each field's median over
//                 the rounds: load on a shared machine drifts over minutes, and rounds interleave with it
//   --json FILE   writes { machine, options, cases: [{ n, m, bindMs, productMs, stepMs, solveMs, products,
//                 passMs, ..., native: {...}, ratios: {...} }], goals: [...] }
//   --scaling     the case of the thread-scaling table (default 50000:74, n = 50k and m = 300): W passes,
//                 product, step, solve, bind, ARAP and full-space iterations with 1, 2, 4, 8, 16 threads
//                 where the machine has them (--threads overrides the list), wasm and native
//                 (scripts/bench/scaling.mjs). The main table runs with every core.
//   --integration the cost of a drag iteration against n (default 5k, 20k, 51k, 100k, 280k, 1M; --quick 5k,
//                 51k, 280k) at m = 100 with full and reduced integration, wasm and native
//                 (scripts/bench/integration.mjs); --plot FILE writes its log-log plot as SVG
//   --models      the real models of ../shared/data in their own cages (default: every one present; a list of
//                 names picks some; --no-models skips them): a converged drag solve with full and reduced integration,
//                 wasm (the command-line tool) and native (cpp/tools/bench_models) (scripts/bench/models.mjs)
//   SD_WASM_DIR   another wasm build (default build/wasm; the threaded Node build in its node-threads/)
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { CommandLineError, parseCommandLine } from './lib/command_line.mjs';
import { requireBuild } from './lib/require_build.mjs';
import { namesOption } from './lib/script_options.mjs';

// The library needs the wasm build: without one, one line says how to make it (lib/require_build.mjs).
requireBuild('bench');
const { loadSolver, wasmDir } = await import('subspace-deform');
const { evaluateGoals, formatTable } = await import('./bench/report.mjs');
const { DEFAULT_SIZES, QUICK_SIZES, formatIntegration, integrationGoals, integrationPlot, runIntegration } = await import('./bench/integration.mjs');
const { MODELS, formatModels, runModels } = await import('./bench/models.mjs');
const { defaultThreadCounts, formatScaling, runScaling } = await import('./bench/scaling.mjs');
const { Timer } = await import('./lib/timer.mjs'); // with the app's time format, which imports the library

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');

const HELP = `usage: node scripts/bench.mjs [--quick] [--json FILE] [--no-native] [--native-bin PATH] [--cases n:segments,...]
                              [--scaling n:segments | --no-scaling] [--threads 1,2,4,...]
                              [--integration n,n,... | --no-integration] [--plot FILE.svg] [--models name,... | --no-models]
  cases: capsule of ~n vertices in a bar cage of 4 (segments + 1) vertices, ":f32" for a float32 W
  (default 5000:24,20000:49,50000:74,50000:74:f32,100000:74; --quick: 5000:24,50000:74)
  scaling: the thread-scaling case (default 50000:74) timed with each thread count (default 1, 2, 4, 8, 16
  up to the cores)
  integration: ms per drag iteration with full and reduced integration at each n (m = 100; default
  5000,20000,51000,100000,280000,1000000, --quick 5000,51000,280000); --plot writes it as an SVG plot
  models: the models of ../shared/data in their own cages, dragged to convergence (default: every one present:
  ${MODELS.join(', ')})`;

const FLAGS = {
  quick: { type: 'boolean' }, json: { type: 'string' }, 'no-native': { type: 'boolean' }, 'native-bin': { type: 'string' },
  cases: { type: 'string' }, rounds: { type: 'string' }, scaling: { type: 'string' }, 'no-scaling': { type: 'boolean' },
  threads: { type: 'string' }, integration: { type: 'string' }, 'no-integration': { type: 'boolean' }, plot: { type: 'string' },
  models: { type: 'string' }, 'no-models': { type: 'boolean' },
  help: { type: 'boolean', short: 'h' },
};

function usage(message) {
  console.error(`bench: ${message}`);
  process.exit(2);
}

function parseArgs(argv) {
  let parsed;
  try {
    parsed = parseCommandLine(argv, FLAGS);
  } catch (error) {
    if (!(error instanceof CommandLineError)) throw error;
    usage(error.kind === 'unknown' ? `unknown argument '${error.flag}'\n${HELP}` : `${error.message}\n${HELP}`);
  }
  const { positionals, flags } = parsed;
  if (flags.help) {
    console.log(HELP);
    process.exit(0);
  }
  if (positionals.length) usage(`unknown argument '${positionals[0]}'\n${HELP}`);
  const a = {
    quick: !!flags.quick, json: flags.json ?? null, native: !flags['no-native'], nativeBin: flags['native-bin'] ?? null,
    cases: flags.cases ?? null, rounds: flags.rounds === undefined ? null : Number(flags.rounds),
    scaling: flags['no-scaling'] ? null : flags.scaling ?? '50000:74', threads: flags.threads ?? null,
    // A misspelt name used to measure nothing and say the models were absent (exit 0).
    models: flags['no-models'] ? null : flags.models === undefined ? MODELS : namesOption('bench', flags.models, '--models', MODELS),
    integration: flags['no-integration'] ? null : flags.integration?.split(',').map(Number) ?? (flags.quick ? QUICK_SIZES : DEFAULT_SIZES),
    plot: flags.plot ?? null,
  };
  if (a.integration && !a.integration.every((n) => Number.isInteger(n) && n >= 100)) usage('--integration needs whole vertex counts >= 100, e.g. 5000,51000');
  if (a.rounds !== null && !(Number.isInteger(a.rounds) && a.rounds >= 1)) usage('--rounds needs an integer >= 1');
  if (a.threads !== null) {
    a.threads = a.threads.split(',').map(Number);
    if (!a.threads.every((t) => Number.isInteger(t) && t >= 1)) usage('--threads needs a list of whole numbers >= 1, e.g. 1,2,4');
  }
  return a;
}

// Repeats per case: medians need several runs, but a bind at n = 100k costs seconds, so big cases repeat less.
function caseOptions(n, segments, float32, quick) {
  const big = n >= 80000, mid = n >= 30000;
  return {
    n, segments,
    repeats: quick ? 5 : big ? 5 : 9,
    bindRepeats: quick ? 1 : big ? 1 : mid ? 2 : 3,
    solveRepeats: quick || mid ? 1 : 3,
    frames: quick ? 5 : 9,
    exactMaxN: 6000,
    fullMaxN: quick ? 6000 : 60000,
    arap: true,
    float32,
  };
}

export function machineInfo() {
  let cpu = 'unknown';
  try {
    const line = readFileSync('/proc/cpuinfo', 'utf8').split('\n').find((l) => l.startsWith('model name'));
    if (line) cpu = line.split(':')[1].trim();
  } catch { /* not Linux */ }
  return {
    nproc: os.availableParallelism?.() ?? os.cpus().length,
    cpu,
    memoryGB: +(os.totalmem() / 1e9).toFixed(1),
    node: process.version,
    platform: `${os.type()} ${os.release()}`,
  };
}

function findNative(explicit, tool = 'bench_native_cases') {
  if (explicit) return existsSync(explicit) ? explicit : null;
  for (const dir of ['build/native', 'build/bench']) {
    const path = resolve(root, dir, tool);
    if (existsSync(path)) return path;
  }
  return null;
}

// glibc returns large blocks (the n x k temporaries of every product) to the OS on free and page-faults them
// back on the next allocation, which triples native step times at n = 50k; wasm's heap never shrinks. Native
// runs therefore raise glibc's mmap and trim thresholds so both sides reuse memory alike (set
// SD_BENCH_GLIBC_DEFAULT=1 to measure glibc's default behaviour).
const NATIVE_ENV = process.env.SD_BENCH_GLIBC_DEFAULT
  ? process.env
  : { ...process.env, GLIBC_TUNABLES: 'glibc.malloc.mmap_threshold=4294967295:glibc.malloc.trim_threshold=4294967295' };

function runNative(bin, opts, threads = 0) {
  const args = ['--threads', threads, '--repeats', opts.repeats, '--bind-repeats', opts.bindRepeats, '--solve-repeats', opts.solveRepeats,
    '--frames', opts.frames, '--exact-max-n', opts.exactMaxN, '--full-max-n', opts.fullMaxN,
    ...(opts.arap ? [] : ['--no-arap']), ...(opts.float32 ? ['--float32'] : []), `${opts.n}:${opts.segments}`].map(String);
  const text = execFileSync(bin, args, { encoding: 'utf8', maxBuffer: 1 << 24, env: NATIVE_ENV });
  return JSON.parse(text.trim().split('\n').pop());
}

// Older builds of the native tool lack --bandwidth: then the bandwidth is simply not reported.
function nativeBandwidth(bin) {
  try {
    return JSON.parse(execFileSync(bin, ['--bandwidth'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }).trim()).readGBs;
  } catch {
    console.warn(`bench: ${bin} does not know --bandwidth (rebuild it with "bash scripts/build.sh --native")`);
    return null;
  }
}

const load = () => os.loadavg().map((x) => +x.toFixed(2));

async function main() {
  const args = parseArgs(process.argv.slice(2));
  const list = args.cases ?? (args.quick ? '5000:24,50000:74' : '5000:24,20000:49,50000:74,50000:74:f32,100000:74');
  const cases = list.split(',').map(parseCase);
  const scalingCase = args.scaling ? parseCase(args.scaling) : null;

  // The pool must hold the largest thread count of the scaling table (default: every core).
  const solver = await loadSolver({ bench: true, ...(args.threads ? { threads: Math.max(...args.threads) } : {}) });
  solver.setThreads(0);
  if (typeof solver.benchCase !== 'function') {
    console.error(`bench: ${wasmDir()} has no benchCase binding (cpp/tools/wasm/bench_bindings.cpp): rebuild with "bash scripts/build.sh --wasm"`);
    process.exit(1);
  }
  const nativeBin = args.native ? findNative(args.nativeBin) : null;
  if (args.native && !nativeBin) {
    console.warn('bench: no native bench_native_cases found (build it with "bash scripts/build.sh --native"); wasm only');
  }

  const machine = machineInfo();
  machine.wasmBuild = solver.build;
  machine.threads = { wasm: solver.threads(), native: machine.nproc };
  const started = new Timer();
  const loadBefore = load();
  // Streaming read bandwidth of one thread: the ideal floor of a W pass is W's bytes / this.
  machine.readGBsWasm = typeof solver.benchReadBandwidth === 'function' ? solver.benchReadBandwidth(240) : null;
  machine.readGBsNative = nativeBin ? nativeBandwidth(nativeBin) : null;
  console.log(`machine: ${machine.nproc} cores, ${machine.cpu}, ${machine.memoryGB} GB; node ${machine.node}; load ${loadBefore.join(' ')}; ` +
    `read bandwidth ${machine.readGBsWasm?.toFixed(1) ?? '-'} GB/s wasm, ${machine.readGBsNative?.toFixed(1) ?? '-'} GB/s native`);
  // Warm-up: V8 compiles wasm in tiers, so the first calls of a fresh module run slower code.
  solver.benchCase({ n: 2000, segments: 6, repeats: 1, frames: 1, exactMaxN: 0, fullMaxN: 0, arap: true });
  const rounds = args.rounds ?? (args.quick ? 1 : 3);
  const perRound = cases.map(() => []);
  for (let round = 1; round <= rounds; ++round) cases.forEach(({ n, segments, float32 }, index) => {
    const opts = caseOptions(n, segments, float32, args.quick);
    const wasmTimer = new Timer();
    const wasm = solver.benchCase(opts);
    if (float32 && wasm.float32 !== 1) {
      throw new Error(`${wasmDir()} is older than the float32 benchmark option: rebuild with "bash scripts/build.sh --wasm"`);
    }
    const wasmS = wasmTimer.seconds();
    let native = null;
    let nativeS = 0;
    if (nativeBin) {
      const nativeTimer = new Timer();
      native = runNative(nativeBin, opts);
      nativeS = nativeTimer.seconds();
    }
    perRound[index].push({ wasm, native, load: load()[0], seconds: { wasm: wasmS, native: nativeS } });
    console.log(`round ${round}/${rounds} n=${wasm.n} m=${wasm.m}${float32 ? ' float32' : ''}: wasm ${wasmS.toFixed(0)} s, ` +
      `native ${nativeS.toFixed(0)} s, load ${load()[0]}`);
  });
  let scaling = null;
  if (scalingCase) {
    const threads = args.threads ?? defaultThreadCounts(machine.nproc);
    // The full-space iteration belongs in the table even at n = 50k (the quick main table skips it there).
    const opts = { ...caseOptions(scalingCase.n, scalingCase.segments, scalingCase.float32, args.quick), fullMaxN: 60000 };
    scaling = runScaling({
      solver, opts, threads, rounds, medianFields, log: console.log,
      runNative: (o, t) => (nativeBin ? runNative(nativeBin, o, t) : null),
    });
    scaling.loadAfter = load();
  }
  const integration = args.integration ? runIntegration({
    solver, nativeBin: nativeBin ? findNative(null, 'bench_integration') : null, nativeEnv: NATIVE_ENV, sizes: args.integration, log: console.log,
  }) : null;
  const sharedData = resolve(root, '..', 'shared', 'data');
  const models = args.models ? await runModels({
    solver, nativeBin: nativeBin ? findNative(null, 'bench_models') : null, dataDir: sharedData, names: args.models, log: console.log,
  }) : null;
  if (args.models && !models.length) console.log(`bench: no models of ${sharedData} are present; the real-model table is skipped`);
  const results = perRound.map((runs) => {
    const wasm = medianFields(runs.map((r) => r.wasm));
    const native = runs[0].native ? medianFields(runs.map((r) => r.native)) : null;
    const c = { ...wasm, native, rounds: runs.length, loads: runs.map((r) => r.load), seconds: runs.map((r) => r.seconds) };
    if (machine.readGBsWasm) c.idealPassMs = c.wBytes / 1e6 / machine.readGBsWasm;
    c.ratios = ratios(c, native);
    return c;
  });
  const report = {
    machine,
    date: new Date().toISOString(),
    wasm: wasmDir(),
    nativeBin,
    nativeGlibcTunables: NATIVE_ENV.GLIBC_TUNABLES ?? null,
    quick: args.quick,
    loadBefore,
    loadAfter: load(),
    seconds: started.seconds(),
    cases: results,
    scaling,
    integration,
    models,
  };
  report.goals = [...evaluateGoals(results), ...(integration ? integrationGoals(integration) : [])];
  console.log('\n' + formatTable(results));
  console.log('\ngoals:');
  for (const g of report.goals) console.log(`  ${g.met === null ? '  n/a' : g.met ? '  met' : 'MISSED'}  ${g.goal}: ${g.detail}`);
  if (scaling) {
    console.log(`\nthread scaling at n = ${scaling.wasm[0].n}, m = ${scaling.wasm[0].m} (${machine.nproc} cores; load after ${scaling.loadAfter.join(' ')}):`);
    console.log(formatScaling(scaling));
  }
  if (models?.length) console.log(`\nreal models in their own cages (a drag solved to convergence):\n${formatModels(models)}`);
  if (integration) {
    console.log(`\nms per drag iteration against n (m = 100):\n${formatIntegration(integration, machine)}`);
    if (args.plot) {
      writeFileSync(args.plot, integrationPlot(integration, machine));
      console.log(`wrote ${args.plot}`);
    }
  }
  console.log(`\ntotal ${report.seconds.toFixed(0)} s; load before ${loadBefore.join(' ')}, after ${report.loadAfter.join(' ')}`);
  if (args.json) {
    writeFileSync(args.json, JSON.stringify(report, null, 2) + '\n');
    console.log(`wrote ${args.json}`);
  }
}

function parseCase(c) {
  const [n, segments, kind] = c.split(':');
  if (!(+n > 0 && +segments > 0) || (kind !== undefined && kind !== 'f32')) {
    console.error(`bench: bad case '${c}' (expected n:segments or n:segments:f32)`);
    process.exit(2);
  }
  return { n: +n, segments: +segments, float32: kind === 'f32' };
}

// Each numeric field's median over the rounds (the lower middle for an even count).
function medianFields(list) {
  const out = {};
  for (const key of Object.keys(list[0])) {
    const values = list.map((x) => x[key]).filter((v) => typeof v === 'number' && Number.isFinite(v)).sort((a, b) => a - b);
    out[key] = values.length ? values[Math.floor((values.length - 1) / 2)] : list[0][key];
  }
  return out;
}

function ratios(w, nat) {
  const r = {
    productOverFloor: w.productMs / (2 * w.passMs),
    productOverPasses: w.productMs / (w.passMs + w.transposePassMs),
    productOverIdealFloor: w.idealPassMs ? w.productMs / (2 * w.idealPassMs) : NaN,
  };
  if (nat) {
    for (const key of ['bindMs', 'passMs', 'productMs', 'stepMs', 'solveMs', 'arapIterationMs', 'fullIterationMs', 'exactIterationMs']) {
      if (Number.isFinite(w[key]) && Number.isFinite(nat[key])) r[`wasmOverNative_${key}`] = w[key] / nat[key];
    }
  }
  return r;
}

main().catch((error) => {
  console.error(`bench: ${error.message}`);
  process.exit(1);
});
