// @ts-check
// Validated JS layer over automatic cage generation (cpp/bindings/cage_bindings.cpp): a
// voxel-dilated surface around the mesh, decimated by progressive hulls (Sander et al. 2000) to about K
// vertices, and checked (closed, manifold, outward, no self-intersection, every mesh vertex inside) before
// it is returned. See docs/cage.md.
import { CAGE_LIMITS as SCHEMA_CAGE_LIMITS } from '../../build/wasm/solver_schema.js';
import { InputError, callWasmWithCallback } from './errors.js';
import { assertMesh } from './mesh.js';

/**
 * @typedef {object} CageResult
 * @property {Float64Array} positions   cage vertices, xyz interleaved
 * @property {Uint32Array} indices      cage triangles, counter-clockwise seen from outside
 * @property {number} offset            clearance the successful attempt aimed for (mesh units)
 * @property {number} voxelSize         voxel size of that attempt
 * @property {number} attempts          1 when the first attempt succeeded (each retry grows the offset)
 * @property {number} startVertices     vertices of the voxel surface before decimation
 * @property {number} volumeRatio       cage volume / mesh volume
 * @property {number} startVolumeRatio  voxel surface volume / mesh volume
 * @property {number} minClearance      smallest distance from a mesh vertex to the cage
 * @property {number} ms                time of the call
 */

/**
 * The fixed limits of generateCage's options (the CLI's flags use the same): the core's
 * (cpp/core/cage/cage_generation.h), through the generated schema.
 */
export const CAGE_LIMITS = Object.freeze({
  vertices: Object.freeze({ ...SCHEMA_CAGE_LIMITS.vertices }),
  resolution: Object.freeze({ ...SCHEMA_CAGE_LIMITS.resolution }),
});

/** @typedef {import('./solver_module.js').SolverModule} SolverModule */

/**
 * Generates a cage with `vertices` vertices (at most 20% more when the decimation runs out of valid
 * collapses) around a closed triangle mesh. Throws an InputError for bad arguments, a MeshError when the
 * mesh is not closed and valid, a CancelledError when onProgress returns false, and a SolverError (code
 * 'cage_failed') when no valid cage could be made. An exception onProgress throws reaches the caller unchanged.
 * @param {SolverModule} solver module from loadSolver() / loadNodeSolver()
 * @param {{positions: Float64Array, indices: Uint32Array}} mesh closed triangle mesh
 * @param {{vertices?: number, offset?: number, resolution?: number,
 *          onProgress?: (fraction: number) => (boolean|void)}} [options]
 *   vertices: target K (an integer within CAGE_LIMITS.vertices, default 100; 20..1000 is the tested range);
 *   offset: clearance in mesh units (default 0.5% of the bounding-box diagonal);
 *   resolution: voxels along the longest side, within CAGE_LIMITS.resolution (default from K);
 *   onProgress: called with the fraction done; return false to cancel.
 * @returns {CageResult}
 */
export function generateCage(solver, mesh, options = {}) {
  assertMesh(mesh, 'mesh', 'generateCage');
  if (mesh.positions.length < 12 || mesh.indices.length < 12) {
    throw new InputError('generateCage: the mesh needs at least 4 vertices and 4 triangles');
  }
  if (options === null || typeof options !== 'object') throw new InputError('generateCage: options must be an object');
  const { vertices = 100, offset, resolution, onProgress } = options;
  const { vertices: V, resolution: R } = CAGE_LIMITS;
  if (!Number.isInteger(vertices) || vertices < V.min || vertices > V.max) {
    throw new InputError(`generateCage: options.vertices must be an integer from ${V.min} to ${V.max} (got ${vertices})`);
  }
  if (offset !== undefined && !(Number.isFinite(offset) && offset > 0)) {
    throw new InputError(`generateCage: options.offset must be a positive number (got ${offset})`);
  }
  if (resolution !== undefined && !(Number.isInteger(resolution) && resolution >= R.min && resolution <= R.max)) {
    throw new InputError(`generateCage: options.resolution must be an integer from ${R.min} to ${R.max} (got ${resolution})`);
  }
  if (onProgress !== undefined && typeof onProgress !== 'function') {
    throw new InputError('generateCage: options.onProgress must be a function');
  }
  /** @type {{ vertices: number, offset?: number, resolution?: number }} */
  const raw = { vertices };
  if (offset !== undefined) raw.offset = offset;
  if (resolution !== undefined) raw.resolution = resolution;
  return callWasmWithCallback(onProgress, (callback) => solver.generateCage(mesh.positions, mesh.indices, raw, callback));
}

/**
 * MeshData from nested arrays, e.g. the npm package `bunny` ({positions: [[x,y,z]...], cells: [[a,b,c]...]}).
 * @param {{positions: number[][], cells: number[][]}} model
 * @returns {{positions: Float64Array, indices: Uint32Array}}
 */
export function meshFromCells(model) {
  if (!model || !Array.isArray(model.positions) || !Array.isArray(model.cells)) {
    throw new InputError('meshFromCells: expected {positions: [[x, y, z]...], cells: [[a, b, c]...]}');
  }
  const positions = new Float64Array(model.positions.length * 3);
  model.positions.forEach((p, i) => positions.set(p, 3 * i));
  const indices = new Uint32Array(model.cells.length * 3);
  model.cells.forEach((c, i) => {
    if (c.length !== 3) throw new InputError(`meshFromCells: cell ${i} has ${c.length} corners (triangles only)`);
    indices.set(c, 3 * i);
  });
  return { positions, indices };
}
