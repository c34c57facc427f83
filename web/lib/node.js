// loadSolver() for Node (CLI, Vitest, benchmarks): reads the .wasm bytes and hands them to the loader,
// because the Emscripten 3.1.6 loader cannot fetch file paths under Node 20 (docs/building.md).
// SD_WASM_DIR overrides the folder holding the built modules (default: build/wasm).
//   loadNodeSolver()                   subspace_deform.{js,wasm}: what the app and the CLI use
//   loadNodeSolver({ bench: true })    subspace_deform_bench.{js,wasm}: the same plus the benchmark and
//                                      experiment bindings (benchCase, benchEvaluateEnergy, ...)
import { existsSync, readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { InputError } from './errors.js';

const repoRoot = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const modulePromises = new Map();

export function wasmDir() {
  return resolve(process.env.SD_WASM_DIR ?? resolve(repoRoot, 'build/wasm'));
}

/** @param {{ bench?: boolean }} [options] */
export function loadNodeSolver({ bench = false } = {}) {
  const name = bench ? 'subspace_deform_bench' : 'subspace_deform';
  if (!modulePromises.has(name)) modulePromises.set(name, load(name));
  return modulePromises.get(name);
}

async function load(name) {
  const dir = wasmDir();
  const wasmPath = resolve(dir, `${name}.wasm`);
  if (!existsSync(wasmPath)) {
    throw new InputError(`${wasmPath} is missing: build it with "bash scripts/build.sh" (or npm test / npm start)`,
      { code: 'unreadable_file' });
  }
  const { default: createSubspaceDeform } = await import(pathToFileURL(resolve(dir, `${name}.js`)).href);
  return createSubspaceDeform({ wasmBinary: readFileSync(wasmPath) });
}

// This file is also the package's Node entry (package.json "exports", condition "node"): the library
// plus the loader above, exported as loadSolver too, so the same code runs in Node and in a browser:
//   import { loadSolver, Deformer, readMesh } from 'subspace-deform';
//   const solver = await loadSolver();               // or loadSolver({ bench: true }) for benchmarks
export * from './library.js';
export { loadNodeSolver as loadSolver };
