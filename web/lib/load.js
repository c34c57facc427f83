// One asynchronous loader for the wasm solver, shared by the app, its Web Workers, the Node CLI and the
// tests. The module is created once per JS realm and cached.
//
// In the browser the Emscripten loader finds subspace_deform.wasm next to itself (Vite copies and hashes it).
// Node 20's fetch cannot load file paths with Emscripten 3.1.6 (docs/building.md), so Node callers pass
// the bytes: see web/lib/node.js.
import createSubspaceDeform from '../../build/wasm/subspace_deform.js';
import { SolverError } from './errors.js';

let modulePromise = null;

/**
 * @param {{ wasmBinary?: Uint8Array }} [options] wasmBinary: the .wasm bytes (Node); omit in browsers.
 * @returns {Promise<object>} the embind module (readMesh, checkMesh, Deformer, ...).
 */
export function loadSolver(options = {}) {
  if (!modulePromise) {
    modulePromise = createSubspaceDeform({ ...options }).catch((error) => {
      modulePromise = null; // allow a retry after a failed load
      throw new SolverError(`could not load the solver (build/wasm/subspace_deform.wasm): ${error.message ?? error}`, { cause: error });
    });
  }
  return modulePromise;
}
