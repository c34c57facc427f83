// @ts-check
// One asynchronous loader for the wasm solver in browsers (the app, its Web Workers, the embed). The module
// is created once per JS realm and cached. Node callers use web/lib/node.js instead (it reads the bytes:
// Node 20's fetch cannot load file paths with Emscripten 3.1.6: docs/building.md).
//
// Two builds (docs/threads.md):
//   threads  build/wasm/threads/subspace_deform.js, served as-is beside the site (web/vite.config.js puts it
//            in threads/ at the site root): the core's thread pool on Web Workers. It needs SharedArrayBuffer,
//            which browsers give only to cross-origin isolated pages (COOP + COEP headers, or the
//            coi-serviceworker shim on static hosts).
//   single   build/wasm/subspace_deform.js, bundled by Vite: runs on any page.
// build 'auto' (the default) takes the threaded build when the page is isolated and falls back to the
// single-threaded one otherwise, or when the threaded one fails to load (module.buildNote says why).
import createSubspaceDeform from '../../build/wasm/subspace_deform.js';
import { SolverError } from './errors.js';
import { typedSetThreads } from './solver_module.js';
import { bootstrapUrl } from './worker/worker_start.js';

// Relative to this file in development (web/lib/ -> web/threads/, served by the dev server) and to the
// bundled chunk in a build (assets/ -> threads/): both are one folder below the site root. A variable, so
// that Vite leaves the URL to run time instead of trying to bundle the file.
const THREADED_MODULE = '../threads/subspace_deform.js';
// The pool is started with the module; more threads than this gain little for the solver's memory-bound
// passes and cost a Web Worker each.
const MAX_THREADS = 16;
// Emscripten 3.1.6 waits for every pthread worker of the pool before the module resolves, with no error when
// one cannot start: past this the page gives up on threads and runs the single-threaded build, saying why.
const THREADED_START_MS = 30000;

/** @typedef {import('./solver_module.js').SolverModule} SolverModule */

/** @type {Promise<SolverModule>|null} */
let modulePromise = null;

/** Whether this realm can run the threaded build: a cross-origin isolated page (or worker of one). */
export function threadsAvailable() {
  return globalThis.crossOriginIsolated === true && typeof SharedArrayBuffer === 'function';
}

/** The cores a page may use: navigator.hardwareConcurrency, at most MAX_THREADS. */
export function pageCores() {
  return Math.max(1, Math.min(MAX_THREADS, globalThis.navigator?.hardwareConcurrency || 1));
}

/**
 * @param {{ build?: 'auto'|'threads'|'single', threads?: number, wasmBinary?: Uint8Array }} [options]
 *   threads: how many threads to use now (0 or absent: pageCores()); the pool always holds pageCores(), so
 *   setThreads can move the count within it later. wasmBinary: the .wasm bytes (single build, tests).
 * @returns {Promise<SolverModule>} the embind module (readMesh, checkMesh, Deformer, setThreads, ...) with
 *   module.build = 'threads' | 'single' and, after a fallback, module.buildNote.
 */
export function loadSolver(options = {}) {
  if (!modulePromise) {
    modulePromise = load(options).then(typedSetThreads, (error) => {
      modulePromise = null; // allow a retry after a failed load
      throw new SolverError(`could not load the solver (build/wasm/subspace_deform.wasm): ${error.message ?? error}`, { cause: error });
    });
  }
  return modulePromise;
}

/**
 * @param {{ build?: 'auto'|'threads'|'single', threads?: number, wasmBinary?: Uint8Array }} options
 * @returns {Promise<SolverModule>}
 */
async function load({ build = 'auto', threads = 0, wasmBinary }) {
  let note;
  if (build === 'threads' || (build === 'auto' && threadsAvailable())) {
    try {
      return await loadThreaded(threads);
    } catch (error) {
      if (build === 'threads') throw error;
      note = `the threaded build did not load (${/** @type {Error} */ (error)?.message ?? error}); running single-threaded`;
    }
  } else if (build === 'auto') {
    note = 'the page is not cross-origin isolated, so it runs single-threaded';
  }
  const module = await createSubspaceDeform(wasmBinary ? { wasmBinary } : {});
  module.build = 'single';
  if (note) module.buildNote = note;
  return module;
}

/**
 * @param {number} threads
 * @returns {Promise<SolverModule>}
 */
async function loadThreaded(threads) {
  const url = new URL(THREADED_MODULE, import.meta.url).href;
  const { default: createThreaded } = await import(/* @vite-ignore */ url);
  const cores = pageCores();
  // At least one worker: Emscripten 3.1.6 waits for the pool to load, and an empty pool never does.
  /** @type {ReturnType<typeof setTimeout>|undefined} */
  let timer;
  const late = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`its thread pool did not start within ${THREADED_START_MS / 1000} s`)), THREADED_START_MS);
  });
  const module = await Promise.race([late, createThreaded({
    pthreadPoolSize: Math.max(1, cores - 1),
    // The pthread workers start from bootstrap blobs (worker_start.js): a script of the build's folder would be
    // refused on an isolated page whose service worker does not cover that folder, and the pool would wait for
    // it forever. They then import the module by its real URL.
    mainScriptUrlOrBlob: url,
    locateFile: (/** @type {string} */ path) => {
      const file = new URL(path, url).href;
      return path.endsWith('.worker.js') ? bootstrapUrl(file, { module: false }) : file;
    },
  })]).finally(() => clearTimeout(timer));
  module.setThreads(threads > 0 ? Math.min(threads, cores) : cores);
  module.build = 'threads';
  return module;
}
