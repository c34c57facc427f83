// @ts-check
// When a subspace basis is stored in single precision: half the memory and half the bytes each pass over it
// streams, for rows that sum to 1 within 1e-7 (docs/mvc.md); the positions stay exact at rest
// (X = X0 + W (P - P0)). Below FLOAT32_ABOVE_BYTES in double, double precision costs little. The solver worker
// chooses by this rule, and the benchmarks measure what it chooses.

/** The size in double precision above which a basis is stored in single precision. */
export const FLOAT32_ABOVE_BYTES = 128e6;

/** Whether a basis of `rows` (mesh vertices) x `columns` (cage vertices or spectral columns) is stored in float32. */
/** @param {number} rows @param {number} columns @returns {boolean} */
export function singlePrecisionPays(rows, columns) {
  return 8 * rows * columns > FLOAT32_ABOVE_BYTES;
}
