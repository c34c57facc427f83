// @ts-check
/// <reference types="node" />
// loadSolver() for Node (CLI, Vitest, benchmarks): reads the .wasm bytes and hands them to the loader,
// because the Emscripten 3.1.6 loader cannot fetch file paths under Node 20 (docs/building.md).
//
// Two builds (docs/threads.md):
//   threads (default)  build/wasm/node-threads/: CommonJS, the core's thread pool on worker_threads. The ES6
//                      build that pages load cannot start its threads under Node, so Node has its own.
//   single             build/wasm/: the single-threaded ES module the pages load without isolation.
// SD_WASM_BUILD=single|threads picks the default, SD_THREADS=N the default thread count (0 or unset: every
// core; at most maxThreads(): 4 per core, at least 16), SD_WASM_DIR the folder holding the builds (default: build/wasm).
//   loadNodeSolver()                   subspace_deform: what the app and the CLI use
//   loadNodeSolver({ bench: true })    subspace_deform_bench: the same plus the benchmark and experiment
//                                      bindings (benchCase, benchEvaluateEnergy, ...)
//   loadNodeSolver({ threads: 2 })     at most 2 threads (the pool is sized when the module loads; setThreads
//                                      can lower the count later, not raise it past that)
//   loadNodeSolver({ build: 'single' })
// The module gets two properties: build ('threads' | 'single') and, like every build, threads() and
// setThreads(n) (cpp/bindings/parallel_bindings.cpp).
import { existsSync, readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { availableParallelism } from 'node:os';
import { dirname, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { InputError } from './errors.js';
import { typedSetThreads } from './solver_module.js';

/** @typedef {import('./solver_module.js').SolverModule} SolverModule */

const repoRoot = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const require = createRequire(import.meta.url);
const modulePromises = new Map();

/** The folder holding the wasm builds: SD_WASM_DIR, else the package's build/wasm. @returns {string} */
export function wasmDir() {
  return resolve(process.env.SD_WASM_DIR ?? resolve(repoRoot, 'build/wasm'));
}

/** The build loadNodeSolver uses when none is named: SD_WASM_BUILD, else 'threads'. */
function defaultBuild() {
  return parseBuild(process.env.SD_WASM_BUILD || 'threads', 'SD_WASM_BUILD');
}

/** The thread count loadNodeSolver uses when none is given: SD_THREADS, else every core (0). */
function defaultThreads() {
  return parseThreads(process.env.SD_THREADS || '0', 'SD_THREADS');
}

/**
 * @param {string} value
 * @param {string} what where the value came from, for the error message
 * @returns {'threads'|'single'}
 */
function parseBuild(value, what) {
  if (value !== 'threads' && value !== 'single') {
    throw new InputError(`${what} must be "threads" or "single", not "${value}"`);
  }
  return value;
}

/**
 * The most threads loadNodeSolver starts: 4 per core, at least 16 (the counts the thread tests and benchmarks
 * compare for identical bits), at most 1024. The pool starts every thread with the module, and threads beyond
 * the cores only cost start-up time and memory: 64 on a 2-core machine took 13.5 s and 654 MB, 160 took 1.46 GB.
 * @param {number} [cores] @returns {number}
 */
export function maxThreads(cores = availableParallelism()) {
  return Math.min(1024, Math.max(16, 4 * cores));
}

/**
 * A thread count as loadSolver takes it, from a number or decimal digits (SD_THREADS, the CLI's --threads N):
 * an InputError (code 'invalid_argument') naming `what` unless it is a whole number from 0 to maxThreads().
 * Nothing else converts: not true, null, [2], "0x2" or "1e0".
 * @param {string|number} value
 * @param {string} what where the value came from, for the error message
 * @returns {number} 0 (every core) or a positive whole number
 */
export function parseThreads(value, what = 'threads') {
  const n = typeof value === 'number' ? value : typeof value === 'string' && /^[0-9]+$/.test(value) ? Number(value) : NaN;
  const most = maxThreads();
  if (!Number.isInteger(n) || n < 0 || n > most) {
    throw new InputError(`${what} must be a whole number from 0 (every core) to ${most} (4 per core, at least 16: more ` +
      `threads than cores only cost start-up time and memory), not ${JSON.stringify(value) ?? String(value)}`);
  }
  return n;
}

/**
 * The wasm module for Node, created once per build, kind and thread count.
 * @param {{ bench?: boolean, build?: 'threads'|'single', threads?: number }} [options]
 * @returns {Promise<SolverModule>} the embind module, with module.build
 */
export function loadNodeSolver({ bench = false, build = defaultBuild(), threads = defaultThreads() } = {}) {
  const name = bench ? 'subspace_deform_bench' : 'subspace_deform';
  const which = parseBuild(build, 'build');
  const count = parseThreads(threads);
  const key = `${which}/${name}/${count}`;
  if (!modulePromises.has(key)) modulePromises.set(key, load(name, which, count));
  return modulePromises.get(key);
}

/**
 * @param {string} name the module's file name without extension
 * @param {'threads'|'single'} build
 * @param {number} threads 0: every core
 * @returns {Promise<SolverModule>}
 */
async function load(name, build, threads) {
  const dir = build === 'threads' ? resolve(wasmDir(), 'node-threads') : wasmDir();
  const wasmPath = wasmFile(dir, name, build);
  if (!existsSync(wasmPath)) {
    throw new InputError(`${wasmPath} is missing: build it with "bash scripts/build.sh" (or npm test / npm start)`,
      { code: 'unreadable_file' });
  }
  const wasmBinary = readFileSync(wasmPath);
  let module;
  if (build === 'threads') {
    const count = threads > 0 ? threads : availableParallelism();
    // One pthread worker per thread besides this one, started with the module (CMakeLists.txt). At least
    // one: Emscripten 3.1.6 waits for the pool's workers to load, and with none it never finishes.
    const createSubspaceDeform = require(resolve(dir, `${name}.js`));
    module = await createSubspaceDeform({ wasmBinary, pthreadPoolSize: Math.max(1, count - 1) });
    unrefWorkers(module);
    module.setThreads(count);
  } else {
    const { default: createSubspaceDeform } = await import(pathToFileURL(resolve(dir, `${name}.js`)).href);
    module = await createSubspaceDeform({ wasmBinary });
  }
  module.build = build;
  return typedSetThreads(module);
}

/**
 * The .wasm of a build. The threaded Node build's is the same bytes as the browsers' threaded one (only the JS glue
 * differs: tests/js/package.test.js compares them), so the package ships it once, in threads/, and Node reads it
 * there when node-threads/ has none of its own.
 * @param {string} dir @param {string} name @param {'threads'|'single'} build @returns {string}
 */
function wasmFile(dir, name, build) {
  const own = resolve(dir, `${name}.wasm`);
  if (build !== 'threads' || existsSync(own)) return own;
  const shared = resolve(wasmDir(), 'threads', `${name}.wasm`);
  return existsSync(shared) ? shared : own;
}

// Emscripten 3.1.6 keeps its worker_threads referenced, so a CLI run would never exit: the pool's threads
// only ever run while this thread waits for them inside a solver call, so they need not keep Node alive.
/** @param {SolverModule} module */
function unrefWorkers(module) {
  const { unusedWorkers = [], runningWorkers = [] } = module.PThread ?? {};
  for (const worker of [...unusedWorkers, ...runningWorkers]) worker.unref?.();
}

// This file is also the package's Node entry (package.json "exports", condition "node"): the library
// plus the loader above, exported as loadSolver too, so the same code runs in Node and in a browser:
//   import { loadSolver, Deformer, readMesh } from 'subspace-deform';
//   const solver = await loadSolver();               // or loadSolver({ bench: true }) for benchmarks
// and Node's one way to read and write files (node_files.js): bounded, regular files only, typed errors.
export * from './library.js';
export { checkWritable, readFileBytes, writeFileBytes } from './node_files.js';
export { loadNodeSolver as loadSolver };
