// The command-line tool, the benchmark and the experiments run the library, which imports the generated
// build/wasm/solver_schema.js: in a clone before its first build Node died on the import with an
// ERR_MODULE_NOT_FOUND stack. This module imports nothing of the library, so an entry script checks here first
// and imports the library (dynamically) only after.
import { existsSync } from 'node:fs';
import { resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const schema = 'build/wasm/solver_schema.js';

/**
 * Exits with status 1 and one line on stderr saying how to build when the wasm build is absent.
 * @param {string} tool the name that starts the line, e.g. 'deform'
 */
export function requireBuild(tool) {
  if (existsSync(fileURLToPath(new URL(`../../${schema}`, import.meta.url)))) return;
  console.error(`${tool}: not built yet (${schema} is missing): run 'npm test' (sets up, builds and tests) or ` +
    `'bash scripts/setup.sh && bash scripts/build.sh' in ${resolve(fileURLToPath(new URL('../..', import.meta.url)))}`);
  process.exit(1);
}
