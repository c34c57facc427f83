// @ts-check
// Validated JS layer over the cage coordinates binding (cpp/bindings/weights_bindings.cpp): mean value (the
// default), positive mean value or harmonic coordinates. W is n x m (mesh vertices x cage vertices), row-major,
// rows sum to 1; with mean value coordinates W * cagePositions = mesh positions (linear precision).
import { checkCoordinates } from './coordinates.js';
import { InputError, callWasmWithCallback } from './errors.js';
import { assertMesh, assertPositions } from './mesh.js';
import { checkWeightsAllocation } from './wasm_allocation.js';

/** @typedef {import('./solver_module.js').SolverModule} SolverModule */
/**
 * @typedef {object} WeightsResult
 * @property {Float64Array|Float32Array} weights  n * m entries, row-major (Float32Array when float32)
 * @property {number} rows        n, mesh vertices
 * @property {number} cols        m, cage vertices
 * @property {number} bytes       storage size of W
 * @property {import('./coordinates.js').CoordinateType} coordinates which coordinates W holds
 * @property {number} minWeight   smallest entry (mean value coordinates: negative inside concave cages)
 * @property {number} minWeightRow
 * @property {number} minWeightCol
 * @property {number} onVertex    mesh vertices lying on a cage vertex
 * @property {number} onFace      mesh vertices lying on a cage triangle or edge
 * @property {number} evaluations point-triangle evaluations (n x cage triangles; harmonic: unknowns x m)
 * @property {number} [rays]      pmvc: rays cast into the hidden parts
 * @property {number} [hiddenFaces] pmvc: back-facing triangles corrected, over all points
 * @property {number} [clamped]   pmvc: weights below 0 after the sampled correction, set to 0
 * @property {number} [resolution] harmonic: grid cells along the cage box's longest side
 * @property {number[]} [grid]    harmonic: grid nodes per axis
 * @property {number} [spacing]   harmonic: the grid spacing
 * @property {number} [unknowns]  harmonic: grid nodes inside the cage
 * @property {number} [factorNonzeros] harmonic: entries of the LDL^T factor below its diagonal
 * @property {number} [gridBytes] harmonic: memory of the grid, factor and solve besides W
 * @property {number} [boundaryCells] harmonic: mesh vertices in grid cells with a corner outside the cage
 * @property {number} [unresolved] harmonic: of those, vertices whose cell has no corner inside
 * @property {number} [factorMs]  harmonic: time of the factorization
 * @property {number} [solveMs]   harmonic: time of the right-hand sides' solves and interpolation
 * @property {number} bindMs      time of the binding itself
 * @property {number} ms          total time of the call, including the copies in and out
 */

/**
 * Cage coordinates of the mesh's vertices with respect to the cage: mean value coordinates (Ju, Schaefer,
 * Warren 2005; the default), or with options.coordinates 'pmvc' positive mean value coordinates (Lipman et al.
 * 2007) or 'harmonic' harmonic coordinates (Joshi et al. 2007), docs/method.md sections 2, 18 and 19.
 * Throws a MeshError (code 'mesh_outside_cage') naming the vertices outside the cage, a SolverError (code
 * 'memory_budget') when W would exceed the memory budget, or (code 'out_of_memory') exceed the 2 GiB one
 * allocation in the wasm heap can have (wasm_allocation.js), a CancelledError when `options.progress`
 * returns false, and an InputError for bad arguments; an exception `options.progress` throws reaches the caller
 * unchanged.
 * @param {SolverModule} solver module from loadSolver() / loadNodeSolver()
 * @param {{positions: Float64Array, indices?: Uint32Array}} mesh only the positions are used
 * @param {{positions: Float64Array, indices: Uint32Array}} cage closed, outward triangle cage
 * @param {{float32?: boolean, memoryBudgetMB?: number, progress?: (fraction: number) => (boolean|void)}
 *   & import('./coordinates.js').CoordinatesChoice} [options]
 *   float32: store W in single precision (half the memory); memoryBudgetMB: refuse beyond this (default 1073.7,
 *   i.e. 1 GiB; harmonic coordinates count their grid and factor too); progress: called with the fraction done
 *   every few hundred rows; return false to cancel; coordinates, pmvcResolution, harmonicResolution:
 *   coordinates.js.
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
  const { float32 = false, memoryBudgetMB, progress, coordinates, pmvcResolution, harmonicResolution } = options;
  if (typeof float32 !== 'boolean') throw new InputError('computeWeights: options.float32 must be a boolean');
  if (memoryBudgetMB !== undefined && !(Number.isFinite(memoryBudgetMB) && memoryBudgetMB > 0)) {
    throw new InputError('computeWeights: options.memoryBudgetMB must be a positive number');
  }
  if (progress !== undefined && typeof progress !== 'function') throw new InputError('computeWeights: options.progress must be a function');
  /** @type {Record<string, unknown>} what the binding reads */
  const raw = { float32, ...checkCoordinates({ coordinates, pmvcResolution, harmonicResolution }, 'computeWeights') };
  if (memoryBudgetMB !== undefined) raw.memoryBudgetMB = memoryBudgetMB;
  checkWeightsAllocation(mesh.positions.length / 3, cage.positions.length / 3, float32, 'computeWeights');
  return callWasmWithCallback(progress, (callback) => solver.computeWeights(mesh.positions, cage.positions, cage.indices, raw, callback));
}
