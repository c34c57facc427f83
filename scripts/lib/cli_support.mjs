// Small pieces every CLI command shares: argument parsing, file reading with readable errors, and the
// mapping from thrown errors to exit statuses and messages.
import { existsSync, readFileSync } from 'node:fs';
import { basename, dirname, resolve } from 'node:path';
import { InputError, isGltfFile, loadSolver, parseThreads, readModel, typedError } from 'subspace-deform';

/** Bad command-line usage: exit status 2 with the message. */
export class UsageError extends InputError {
  constructor(message) {
    super(message);
    this.name = 'UsageError';
  }
}

/**
 * Parses argv into positionals and --flags. `spec` maps flag names to 'string' | 'boolean'.
 * Unknown flags and missing values are UsageErrors.
 */
export function parseArgs(argv, spec) {
  const positionals = [];
  const flags = {};
  for (let i = 0; i < argv.length; ++i) {
    const arg = argv[i];
    if (!arg.startsWith('--')) {
      positionals.push(arg);
      continue;
    }
    const [key, inlineValue] = arg.slice(2).split(/=(.*)/s, 2);
    const kind = spec[key];
    if (!kind) throw new UsageError(`unknown option --${key}`);
    if (kind === 'boolean') {
      flags[key] = true;
    } else {
      const value = inlineValue ?? argv[++i];
      if (value === undefined || value.startsWith('--')) throw new UsageError(`--${key} needs a value`);
      flags[key] = value;
    }
  }
  return { positionals, flags };
}

/** Reads a file, turning ENOENT and friends into one readable line. */
export function readInputFile(path) {
  try {
    return new Uint8Array(readFileSync(path));
  } catch (error) {
    throw new InputError(`cannot read ${path}: ${error.code === 'ENOENT' ? 'no such file' : error.message}`,
      { code: 'unreadable_file', cause: error });
  }
}

/**
 * Reads a model file (OBJ, OFF, PLY, STL, .glb, .gltf) with readModel. A .gltf's separate buffers and images
 * are read from beside it (a missing one is named by readModel).
 * @returns {Promise<import('subspace-deform').Model>}
 */
export async function readModelFile(solver, path) {
  const bytes = readInputFile(path);
  const name = basename(path);
  const resources = isGltfFile(name, bytes) ? gltfResources(bytes, dirname(path)) : undefined;
  return readModel(solver, bytes, name, { resources });
}

// The files a .gltf names by relative URI (buffers, images) that exist beside it, by that URI.
function gltfResources(bytes, folder) {
  let json;
  try {
    json = JSON.parse(new TextDecoder().decode(bytes));
  } catch {
    return undefined;  // a .glb, or malformed JSON that readModel names
  }
  const resources = {};
  for (const item of [...(json?.buffers ?? []), ...(json?.images ?? [])]) {
    const uri = item?.uri;
    if (typeof uri !== 'string' || /^[a-z][a-z0-9+.-]*:/i.test(uri)) continue;  // data:, http:, ...
    const path = resolve(folder, decodeURIComponent(uri));
    if (existsSync(path)) resources[uri] = readInputFile(path);
  }
  return resources;
}

/** Runs a command body; returns its exit status (a number, or 0 when it returns nothing). */
export async function runCommand(body) {
  const status = await body();
  return typeof status === 'number' ? status : 0;
}

/** The solver module for a command, with the thread count of its --threads flag (a UsageError if bad). */
export function loadCommandSolver(flags) {
  if (flags.threads === undefined) return loadSolver();
  let threads;
  try {
    threads = parseThreads(flags.threads, '--threads');
  } catch (error) {
    throw new UsageError(error.message);
  }
  return loadSolver({ threads });
}

/**
 * The exit status and the stderr line for an error a command threw: 2 and "usage error: ..." for bad
 * usage; 1 and "error (code): ..." for everything else, with the library's error code (errors.js).
 * @param {unknown} error
 * @returns {{ status: number, message: string }}
 */
export function failure(error) {
  if (error instanceof UsageError) return { status: 2, message: `usage error: ${error.message}` };
  const typed = typedError(error);
  return { status: 1, message: `error (${typed.code}): ${typed.message}` };
}
