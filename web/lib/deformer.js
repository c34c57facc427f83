// Validated JS layer over the Deformer session (cpp/core/solver/deformer.h via cpp/bindings/deformer_bindings.cpp):
// constrained Gauss-Newton deformation in the cage subspace (or the full space, or ARAP), one session per
// model. Arguments are checked here, before entering wasm, so mistakes surface as InputErrors naming the
// argument; failures inside the solver arrive as typed errors (errors.js) carrying the C++ code and message.
//
//   const d = Deformer.create(solver, mesh, cage);      // binds W once (d.bindMs)
//   d.setHandles([[0, 1, 2], [57]]);                    // vertex groups
//   d.setTargets(targets);                              // Float64Array, 3 numbers per handle vertex
//   const { iterations, converged, stop } = d.step(1);  // warm-started; stop: why it returned (STOP_CODES)
//   const positions = d.positions();                    // Float64Array copy
//   d.dispose();

import { STOP_CODES } from '../../build/wasm/solver_schema.js';
import { InputError, callWasm } from './errors.js';
import { assertMesh } from './mesh.js';
import { checkSolverOptions } from './options.js';

/** @typedef {import('./mesh.js').MeshData} MeshData */
/** @typedef {import('./options.js').SolverOptions} SolverOptions */
/**
 * @typedef {object} IterationStats
 * @property {number} iteration counted from the last reset
 * @property {number} merit 1/2 |f|^2 + lambda g
 * @property {number} energy 1/2 |f|^2
 * @property {number} laplacianEnergy
 * @property {number} positionEnergy
 * @property {number} volume
 * @property {number} volumeRelError (volume - rest volume) / rest volume
 * @property {number} lambda volume multiplier
 * @property {number} step largest vertex displacement of the iteration
 * @property {number} lineSearchTrials
 * @property {number} innerIterations CG iterations (fast mode)
 * @property {number} products matrix-free products W^T J^T J W v (fast subspace)
 * @property {number} passes streams over W
 * @property {number} ms
 */
/**
 * Why a step() or solve() call returned (cpp/core/solver/solver_types.h, generated with the schema).
 * @typedef {import('../../build/wasm/solver_schema.js').StopCode} StopCode
 */
/**
 * @typedef {object} StepResult
 * @property {IterationStats[]} iterations
 * @property {boolean} converged
 * @property {StopCode} stop why the call returned: decide from this
 * @property {string} stopReason the same for people (may say more, e.g. what was not finite)
 */
/**
 * How well the cage controls the mesh, read from W (cpp/core/weights/cage_quality.h, docs/cage.md).
 * @typedef {object} CageQuality
 * @property {number} cageVertices
 * @property {number} weakVertices cage vertices with no weight above 1e-3 on any mesh vertex
 * @property {number} minColumnMax the smallest of the cage vertices' largest weights
 * @property {number} volumeRatio cage volume / mesh volume
 * @property {number} influenceRatio smallest / largest eigenvalue of W^T W over sampled rows (NaN: not
 *   computed, cages over 400 vertices): tiny when cage motions exist that barely move the mesh
 * @property {number} weakMotions eigenvalues below 1e-6 of the largest
 * @property {number} sampledRows rows of W in that W^T W
 * @property {number} ms time taken
 * @property {string[]} warnings one sentence per exceeded threshold
 * @property {boolean} poor true when there is a warning
 */

/** Every stop code with whether it means "converged" and its standard text, from the C++ enum. */
export { STOP_CODES };

// Iteration counts cross into C++ as int.
const MAX_INT = 2147483647;

export class Deformer {
  /**
   * Validates the mesh (and cage) and binds the mean value coordinates W once.
   * @param {object} solver the module from loadSolver() / loadNodeSolver()
   * @param {MeshData} mesh closed, manifold, outward mesh
   * @param {MeshData|null} cage closed cage strictly around the mesh; null: no cage (full space and ARAP only)
   * @param {{ float32?: boolean, memoryBudgetMB?: number, onProgress?: (fraction: number) => (boolean|void) }} [options]
   *   float32 stores W in single precision (half the memory and bandwidth); onProgress returning false cancels.
   * @returns {Deformer}
   */
  static create(solver, mesh, cage, { float32 = false, memoryBudgetMB, onProgress } = {}) {
    if (!solver || typeof solver.DeformerSession !== 'function') {
      throw new InputError('Deformer.create: solver must be the loaded wasm module (it has no DeformerSession)');
    }
    assertMesh(mesh, 'mesh', 'Deformer.create');
    if (cage !== null && cage !== undefined) assertMesh(cage, 'cage', 'Deformer.create');
    if (typeof float32 !== 'boolean') throw new InputError('Deformer.create: float32 must be a boolean');
    if (memoryBudgetMB !== undefined && !(typeof memoryBudgetMB === 'number' && memoryBudgetMB > 0 && Number.isFinite(memoryBudgetMB))) {
      throw new InputError('Deformer.create: memoryBudgetMB must be a positive number');
    }
    if (onProgress !== undefined && typeof onProgress !== 'function') {
      throw new InputError('Deformer.create: onProgress must be a function');
    }
    const options = { float32 };
    if (memoryBudgetMB !== undefined) options.memoryBudgetMB = memoryBudgetMB;
    const session = callWasm(() => new solver.DeformerSession(
      mesh.positions, mesh.indices, cage?.positions ?? null, cage?.indices ?? null, options, onProgress ?? null));
    return new Deformer(session);
  }

  /** @private use Deformer.create */
  constructor(session) {
    /** @private the embind DeformerSession; null once disposed */
    this._session = session;
    /** @private */
    this._vertexCount = /** @type {number} */ (session.vertexCount());
    /** @private */
    this._handleCount = 0;
  }

  /**
   * Partial updates: only the given keys change (undefined or null values are skipped). Changing the
   * method resets to the rest pose. Every option, its limits and its default: OPTIONS in options.js.
   * @param {SolverOptions} options
   */
  setOptions(options) {
    const s = this._live();
    const checked = checkSolverOptions(options, 'setOptions');
    callWasm(() => s.setOptions(checked));
  }

  /** The current options (all keys). @returns {Required<SolverOptions>} */
  options() {
    const s = this._live();
    return callWasm(() => s.options());
  }

  /**
   * Handle groups: arrays of vertex indices; not empty, no vertex twice, all in [0, vertexCount).
   * Resets the targets to the handles' current positions.
   * @param {number[][]} groups
   */
  setHandles(groups) {
    const s = this._live();
    if (!Array.isArray(groups)) throw new InputError('setHandles: groups must be an array of arrays of vertex indices');
    const seen = new Map();
    let count = 0;
    groups.forEach((group, g) => {
      if (!Array.isArray(group) && !ArrayBuffer.isView(group)) throw new InputError(`setHandles: group ${g} is not an array`);
      if (group.length === 0) throw new InputError(`setHandles: group ${g} is empty`);
      for (const v of group) {
        if (!Number.isInteger(v)) throw new InputError(`setHandles: group ${g} has a non-integer vertex index ${v}`);
        if (v < 0 || v >= this._vertexCount) {
          throw new InputError(`setHandles: group ${g} has vertex ${v} outside [0, ${this._vertexCount})`);
        }
        if (seen.has(v)) {
          const other = seen.get(v);
          throw new InputError(other === g
            ? `setHandles: vertex ${v} appears twice in group ${g}`
            : `setHandles: vertex ${v} is in both group ${other} and group ${g}`);
        }
        seen.set(v, g);
      }
      count += group.length;
    });
    callWasm(() => s.setHandles(groups.map((group) => Array.from(group))));
    this._handleCount = count;
  }

  /**
   * Target positions of the handle vertices: 3 numbers per vertex, groups in order. Cheap (no refactoring).
   * @param {Float64Array} targets
   */
  setTargets(targets) {
    const s = this._live();
    if (!(targets instanceof Float64Array)) throw new InputError('setTargets: targets must be a Float64Array');
    if (targets.length !== 3 * this._handleCount) {
      throw new InputError(`setTargets: ${targets.length} numbers for ${this._handleCount} handle vertices (expected ${3 * this._handleCount})`);
    }
    for (let i = 0; i < targets.length; ++i) {
      if (!Number.isFinite(targets[i])) throw new InputError(`setTargets: target ${Math.floor(i / 3)} is not finite`);
    }
    callWasm(() => s.setTargets(targets));
  }

  /**
   * Up to k iterations, warm-started from the current positions.
   * @param {number} [k=1]
   * @returns {StepResult}
   */
  step(k = 1) {
    const s = this._live();
    if (!(Number.isInteger(k) && k >= 0 && k <= MAX_INT)) {
      throw new InputError(`step: k must be an integer from 0 to ${MAX_INT} (got ${k})`);
    }
    return callWasm(() => s.step(k));
  }

  /** Iterates until converged or maxIterations. @returns {StepResult} */
  solve() {
    const s = this._live();
    return callWasm(() => s.solve());
  }

  /** Back to the rest pose (handles, targets and options are kept). */
  reset() {
    const s = this._live();
    callWasm(() => s.reset());
  }

  /** Current deformed mesh positions (a copy): Float64Array of 3 * vertexCount. @returns {Float64Array} */
  positions() {
    const s = this._live();
    return callWasm(() => s.positions());
  }

  /**
   * Current cage positions (a copy): the deformed cage in the subspace method, else the rest cage.
   * @returns {Float64Array}
   */
  cagePositions() {
    const s = this._live();
    return callWasm(() => s.cagePositions());
  }

  /**
   * The cage's quality (computed on each call: O(rows m^2) with at most ~8192 sampled rows, then an m x m
   * eigen-solve). A session without a cage throws an InputError with code 'no_cage'.
   * @returns {CageQuality}
   */
  cageQuality() {
    const s = this._live();
    return callWasm(() => s.cageQuality());
  }

  /** Enclosed volume of the rest mesh. @returns {number} */
  get restVolume() { return this._live().restVolume(); }
  /** Time the binding of W took. @returns {number} */
  get bindMs() { return this._live().bindMs(); }
  /** Time of the one-off subspace precomputation (0 without a cage). @returns {number} */
  get precomputeMs() { return this._live().precomputeMs(); }
  /** @returns {number} */
  get vertexCount() { return this._vertexCount; }
  /** Vertices in all handle groups. @returns {number} */
  get handleCount() { return this._handleCount; }
  /** Vertices whose Laplacian coordinates needed the fallback (docs/method.md section 4). @returns {number} */
  get fallbackCount() { return this._live().fallbackCount(); }
  /** @returns {boolean} */
  get disposed() { return this._session === null; }

  /** Frees the wasm memory of the session. Safe to call twice. */
  dispose() {
    if (this._session) {
      this._session.delete();
      this._session = null;
    }
  }

  /** @private */
  _live() {
    if (!this._session) throw new InputError('Deformer: this session was disposed');
    return this._session;
  }
}
