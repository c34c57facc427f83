// loadSolver() for Node (CLI, Vitest, benchmarks): reads the .wasm bytes and hands them to the loader,
// because the Emscripten 3.1.6 loader cannot fetch file paths under Node 20 (toolchain.md trap 3).
// SD_WASM_DIR overrides the folder holding subspace_deform.{js,wasm} (default: build/wasm).
import { existsSync, readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const repoRoot = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
let modulePromise = null;

export function wasmDir() {
  return resolve(process.env.SD_WASM_DIR ?? resolve(repoRoot, 'build/wasm'));
}

export function loadNodeSolver() {
  if (!modulePromise) modulePromise = load();
  return modulePromise;
}

async function load() {
  const dir = wasmDir();
  const wasmPath = resolve(dir, 'subspace_deform.wasm');
  if (!existsSync(wasmPath)) {
    throw new Error(`${wasmPath} is missing: build it with "bash scripts/build.sh" (or npm test / npm start)`);
  }
  const { default: createSubspaceDeform } = await import(pathToFileURL(resolve(dir, 'subspace_deform.js')).href);
  return createSubspaceDeform({ wasmBinary: readFileSync(wasmPath) });
}
