// Validated JS layer over the mean value coordinates binding (cpp/bindings/weights_bindings.cpp).
// W is n x m (mesh vertices x cage vertices), row-major, rows sum to 1 and W * cagePositions = mesh positions.
import { InputError, callWasmWithCallback } from './errors.js';
import { assertMesh, assertPositions } from './mesh.js';

/**
 * @typedef {object} WeightsResult
 * @property {Float64Array|Float32Array} weights  n * m entries, row-major (Float32Array when float32)
 * @property {number} rows        n, mesh vertices
 * @property {number} cols        m, cage vertices
 * @property {number} bytes       storage size of W
 * @property {number} minWeight   smallest entry (negative inside concave cages)
 * @property {number} minWeightRow
 * @property {number} minWeightCol
 * @property {number} onVertex    mesh vertices lying on a cage vertex
 * @property {number} onFace      mesh vertices lying on a cage triangle or edge
 * @property {number} evaluations point-triangle evaluations (n x cage triangles)
 * @property {number} bindMs      time of the binding itself
 * @property {number} ms          total time of the call, including the copies in and out
 */

/**
 * Mean value coordinates of the mesh's vertices with respect to the cage (Ju, Schaefer, Warren 2005).
 * Throws a MeshError (code 'mesh_outside_cage') naming the vertices outside the cage, a SolverError (code
 * 'memory_budget') when W would exceed the memory budget, a CancelledError when `options.progress`
 * returns false, and an InputError for bad arguments; an exception `options.progress` throws reaches the caller
 * unchanged.
 * @param {object} solver module from loadSolver() / loadNodeSolver()
 * @param {{positions: Float64Array, indices?: Uint32Array}} mesh only the positions are used
 * @param {{positions: Float64Array, indices: Uint32Array}} cage closed, outward triangle cage
 * @param {{float32?: boolean, memoryBudgetMB?: number, progress?: (fraction: number) => (boolean|void)}} [options]
 *   float32: store W in single precision (half the memory); memoryBudgetMB: refuse beyond this (default 1073.7,
 *   i.e. 1 GiB); progress: called with the fraction done every few hundred rows; return false to cancel.
 * @returns {WeightsResult}
 */
export function computeWeights(solver, mesh, cage, options = {}) {
  if (!mesh || typeof mesh !== 'object') throw new InputError('computeWeights: mesh must be { positions: Float64Array }');
  assertPositions(mesh.positions, 'computeWeights: mesh.positions');
  assertMesh(cage, 'cage', 'computeWeights');
  if (cage.positions.length < 12 || cage.indices.length < 12) {
    throw new InputError('computeWeights: the cage needs at least 4 vertices and 4 triangles');
  }
  if (options === null || typeof options !== 'object') throw new InputError('computeWeights: options must be an object');
  const { float32 = false, memoryBudgetMB, progress } = options;
  if (typeof float32 !== 'boolean') throw new InputError('computeWeights: options.float32 must be a boolean');
  if (memoryBudgetMB !== undefined && !(Number.isFinite(memoryBudgetMB) && memoryBudgetMB > 0)) {
    throw new InputError('computeWeights: options.memoryBudgetMB must be a positive number');
  }
  if (progress !== undefined && typeof progress !== 'function') throw new InputError('computeWeights: options.progress must be a function');
  const raw = { float32 };
  if (memoryBudgetMB !== undefined) raw.memoryBudgetMB = memoryBudgetMB;
  return callWasmWithCallback(progress, (callback) => solver.computeWeights(mesh.positions, cage.positions, cage.indices, raw, callback));
}
