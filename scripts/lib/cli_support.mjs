// Small pieces every CLI command shares: argument parsing (flags with the library's limits: a value out of
// range is bad usage, exit 2, whichever flag it is), the outputs checked before any work, reading models, and
// the mapping from thrown errors to exit statuses and messages. Files are read and written by the library's one
// bounded, typed reader (web/lib/node_files.js).
import { existsSync, statSync } from 'node:fs';
import { basename, dirname, extname, resolve } from 'node:path';
import {
  InputError, MeshError, OUTPUT_EXTENSIONS, checkFileSize, checkWritable, containedUri, isGltfFile, loadSolver,
  parseThreads, readFileBytes, readModel, typedError,
} from 'subspace-deform';
import { CommandLineError, numberValue, parseCommandLine } from './command_line.mjs';

/** Bad command-line usage: exit status 2 with the message. */
export class UsageError extends InputError {
  constructor(message) {
    super(message);
    this.name = 'UsageError';
  }
}

/**
 * Parses argv into positionals and --flags (lib/command_line.mjs: Node's util.parseArgs). `spec` maps flag names
 * to 'string' | 'boolean'. Unknown flags, missing values and empty positionals are UsageErrors.
 * @param {string[]} argv
 * @param {Record<string, 'string'|'boolean'>} spec
 */
export function parseArgs(argv, spec) {
  const options = Object.fromEntries(Object.entries(spec).map(([name, type]) => [name, { type }]));
  let parsed;
  try {
    parsed = parseCommandLine(argv, options);
  } catch (error) {
    if (error instanceof CommandLineError) throw new UsageError(error.message);
    throw error;
  }
  // Every command's positionals are file paths: an empty one ("$MESH" unset) is the command line's fault, not the
  // file reader's (which said "error (invalid_argument): readFileBytes: path must be a non-empty string", exit 1).
  const empty = parsed.positionals.indexOf('');
  if (empty >= 0) throw new UsageError(`argument ${empty + 1} is empty: a file path must not be empty`);
  return parsed;
}

/**
 * Reads an input file (a mesh, a cage, a scene): regular files only, at most the library's limit
 * (node_files.js); an InputError with code 'unreadable_file' or 'file_too_large' names it otherwise.
 */
export function readInputFile(path) {
  return readFileBytes(path);
}

/**
 * Reads a model file (OBJ, OFF, PLY, STL, .glb, .gltf) with readModel. A .gltf's separate buffers and images
 * are read from beside it (a missing one is named by readModel).
 * @returns {Promise<import('subspace-deform').Model>}
 */
export async function readModelFile(solver, path) {
  const bytes = readInputFile(path);
  const name = basename(path);
  const resources = isGltfFile(name, bytes) ? gltfResources(bytes, name, dirname(path)) : undefined;
  return readModel(solver, bytes, name, { resources });
}

// The files a .gltf names by relative URI (buffers, images) that exist beside it, by that URI. One that would
// lie outside the .gltf's folder is refused before anything is read (containedUri: a converter must not embed
// its own files in what it writes), and the files together stay within the one file limit, checked by their
// sizes before they are read.
function gltfResources(bytes, name, folder) {
  let json;
  try {
    json = JSON.parse(new TextDecoder().decode(bytes));
  } catch {
    return undefined;  // a .glb, or malformed JSON that readModel names
  }
  const resources = {};
  let total = bytes.byteLength;
  const items = [...listOf(json?.buffers).map((item, i) => [item, `buffer ${i}`]), ...listOf(json?.images).map((item, i) => [item, `image ${i}`])];
  for (const [item, what] of items) {
    const uri = item?.uri;
    if (typeof uri !== 'string' || /^data:/i.test(uri)) continue;
    const path = resolve(folder, containedUri(uri, `${name}: ${what}`));
    if (!existsSync(path)) continue;  // readModel names the file it misses
    total += statSync(path).size;
    checkFileSize(total, `${name} with its resources up to ${what} ("${uri}")`);
    resources[uri] = readInputFile(path);
  }
  return resources;
}

function listOf(value) {
  return Array.isArray(value) ? value : [];
}

/**
 * Checks, before a command computes anything, that each output flag given names a file that can be written
 * (an InputError with code 'unwritable_file' naming the flag), so no result is computed and then lost.
 * @param {Record<string, string|boolean>} flags
 * @param {string[]} names the output flags, e.g. ['out', 'report']
 */
export function checkOutputs(flags, names) {
  for (const name of names) if (typeof flags[name] === 'string') checkWritable(flags[name], `--${name}`);
}

/**
 * The format a model output flag's file name asks for ('obj' or 'glb', as writeModel writes them), else a
 * UsageError naming the flag and the extension: checked before any work, so no other format is written under a
 * name that promises it (a .gltf would need its buffers beside it).
 * @param {string} path
 * @param {string} name e.g. '--out'
 */
export function outputFormat(path, name) {
  const ext = extname(path).slice(1).toLowerCase();
  if (!OUTPUT_EXTENSIONS.includes(ext)) {
    throw new UsageError(`${name} must name a .obj or .glb file (got '${path}': ${ext ? `.${ext}` : 'no extension'} cannot be written)`);
  }
  return ext;
}

/**
 * A numeric flag's value, else a UsageError naming the flag and the range.
 * @param {string} text
 * @param {string} name e.g. '--vertices'
 * @param {{ min?: number, max?: number, integer?: boolean, minOpen?: boolean }} range minOpen: min itself excluded
 */
export function numberFlag(text, name, range = {}) {
  try {
    return numberValue(text, name, range);
  } catch (error) {
    if (error instanceof CommandLineError) throw new UsageError(error.message);
    throw error;
  }
}

/**
 * The --memory-budget flag in MB (undefined when not given), else a UsageError. At least 0.01 MB (10 kB): a
 * smaller budget refuses every W all the same, and its messages (two decimals) would say "over 0.00 MB".
 * @param {Record<string, string|boolean>} flags
 * @returns {number|undefined}
 */
export function memoryBudgetFlag(flags) {
  const text = flags['memory-budget'];
  return typeof text === 'string' ? numberFlag(text, '--memory-budget', { min: 0.01 }) : undefined;
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
  const text = typed instanceof MeshError ? checkReportText(typed.message) : typed.message;
  return { status: 1, message: `error (${typed.code}): ${text}` };
}

// A mesh check's failure carries the core's report text, one "error: ..." (or "warning: ...") line per finding and
// a newline after the last: after "error (code): " the first word would repeat and an empty line follow. The first
// finding loses its "error: ", the others stay indented under it.
function checkReportText(message) {
  const lines = message.trimEnd().split('\n');
  lines[0] = lines[0].replace(/^error: /, '');
  return lines.join('\n  ');
}
