// @ts-check
// The largest single allocation the solver's wasm heap can make: about 2 GiB, not the 4 GB the heap may grow
// to (CMakeLists.txt: -sMAXIMUM_MEMORY=4GB). Emscripten's allocator (dlmalloc) grows the heap through sbrk,
// whose increment is a signed 32-bit number in wasm32, so it asks for less than 2^31 bytes at a time
// (HALF_MAX_SIZE_T in system/lib/dlmalloc.c): a W of 2.18 GB failed at once with out_of_memory while one of
// 2.10 GB was bound. W (n x m, dense) is one such allocation; asking for it is refused here, with the true
// limit, before the module is called.
import { SolverError } from './errors.js';

/** Bytes one allocation in the wasm heap may have (2^31, less 1 MiB for the allocator's own padding). */
export const MAX_WASM_ALLOCATION_BYTES = 2 ** 31 - 2 ** 20;

/**
 * Throws an out_of_memory SolverError when W (rows x cols) would not fit one wasm allocation.
 * @param {number} rows
 * @param {number} cols
 * @param {boolean} float32
 * @param {string} what e.g. 'computeWeights'
 */
export function checkWeightsAllocation(rows, cols, float32, what) {
  const bytes = rows * cols * (float32 ? 4 : 8);
  if (bytes <= MAX_WASM_ALLOCATION_BYTES) return;
  throw new SolverError(`${what}: ${weightsTooLarge(rows, cols, float32)}`, { code: 'out_of_memory' });
}

/**
 * Why W of that size cannot be made, and what helps (no memory budget does).
 * @param {number} rows
 * @param {number} cols
 * @param {boolean} float32
 * @param {boolean} [bound] rows is an upper bound (the file's vertices, before welding)
 * @returns {string}
 */
export function weightsTooLarge(rows, cols, float32, bound = false) {
  const megabytes = (/** @type {number} */ bytes) => `${(bytes / 1e6).toFixed(0)} MB`;
  const bytes = rows * cols * (float32 ? 4 : 8);
  return `W (${bound ? 'up to ' : ''}${rows} x ${cols} ${float32 ? 'float32' : 'float64'}) would need ${megabytes(bytes)}, more than the ` +
    `${megabytes(MAX_WASM_ALLOCATION_BYTES)} one allocation in the solver's wasm heap can have (the heap grows to 4 GB, ` +
    `but its allocator takes less than 2 GiB at a time; no memory budget changes that); use a coarser cage (fewer ` +
    `vertices)${float32 ? '' : ' or float32 storage (half the size)'}`;
}

/**
 * The binding's out_of_memory (the wasm heap is full) said truly when W itself is what cannot be
 * allocated: W has a row per welded vertex, so it is known only inside the module; the file's vertex count bounds
 * it. Any other error is returned as it is.
 * @param {unknown} error what Deformer.create's binding threw
 * @param {{ positions: Float64Array }} mesh
 * @param {{ positions: Float64Array }} cage
 * @param {boolean} float32
 * @returns {unknown}
 */
export function weightsOutOfMemory(error, mesh, cage, float32) {
  const rows = mesh.positions.length / 3, cols = cage.positions.length / 3;
  if (!(error instanceof SolverError) || error.code !== 'out_of_memory' || rows * cols * (float32 ? 4 : 8) <= MAX_WASM_ALLOCATION_BYTES) return error;
  return new SolverError(`Deformer.create: out of memory: ${weightsTooLarge(rows, cols, float32, true)}`, { code: 'out_of_memory', cause: error });
}
