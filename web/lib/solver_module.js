// @ts-check
// The type of what loadSolver() resolves to (load.js in browsers, node.js in Node): the Emscripten/embind
// module of the C++ core. Every library function that needs the module takes it as its first argument
// (`solver`); callers only pass it on, so only what the library adds to it is spelt out here, and its
// embind bindings (cpp/bindings/: readMesh, DeformerSession, ...) are left untyped: the library's functions
// are their typed, checked interface.

/**
 * @typedef {{
 *   build: 'threads'|'single',
 *   buildNote?: string,
 *   threads(): number,
 *   setThreads(count: number): number,
 *   [binding: string]: any,
 * }} SolverModule
 *   build: which wasm build runs; buildNote: why the threaded build was not taken (browsers, build 'auto');
 *   threads() and setThreads(count): the threads the core's passes use now (at most the pool's size).
 */

import { callWasm } from './errors.js';

/**
 * The module's setThreads with the library's typed errors: the raw binding throws a plain Error for a count that
 * is not a whole number from 0 to 1024 (setThreads(-1), setThreads('3')); every other entry throws an InputError.
 * Both loaders (load.js, node.js) apply it. @template {SolverModule} M @param {M} module @returns {M}
 */
export function typedSetThreads(module) {
  const raw = module.setThreads;
  module.setThreads = (/** @type {number} */ count) => callWasm(() => raw.call(module, count));
  return module;
}
