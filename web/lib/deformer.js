// Validated JS layer over the Deformer session (cpp/core/solver/deformer.h via cpp/bindings/deformer_bindings.cpp):
// constrained Gauss-Newton deformation in the cage subspace (or the full space, or ARAP), one session per
// model. Arguments are checked here, before entering wasm, so mistakes surface as clear Errors naming the
// argument; failures inside the solver arrive as Errors carrying the C++ message.
//
//   const d = Deformer.create(solver, mesh, cage);      // binds W once (d.bindMs)
//   d.setHandles([[0, 1, 2], [57]]);                    // vertex groups
//   d.setTargets(targets);                              // Float64Array, 3 numbers per handle vertex
//   const { iterations, converged, stopReason } = d.step(1);   // warm-started from the last positions
//   const positions = d.positions();                    // Float64Array copy
//   d.dispose();

/** @typedef {{ positions: Float64Array, indices: Uint32Array }} MeshData */
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
/** @typedef {{ iterations: IterationStats[], converged: boolean, stopReason: string }} StepResult */

const METHODS = ['subspace', 'full', 'arap'];
const JACOBIANS = ['fast', 'exact'];
const NUMERIC_OPTIONS = ['positionWeight', 'c1', 'c2', 'maxIterations', 'stepTolerance', 'meritTolerance', 'cgTolerance', 'cgMaxIterations',
  'cgMemory', 'arapEnergyTolerance', 'arapAcceleration'];
const OPTION_KEYS = new Set(['method', 'jacobian', 'volume', ...NUMERIC_OPTIONS]);

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
      throw new TypeError('Deformer.create: solver must be the loaded wasm module (it has no DeformerSession)');
    }
    assertMeshData(mesh, 'mesh');
    if (cage !== null && cage !== undefined) assertMeshData(cage, 'cage');
    if (typeof float32 !== 'boolean') throw new TypeError('Deformer.create: float32 must be a boolean');
    if (memoryBudgetMB !== undefined && !(typeof memoryBudgetMB === 'number' && memoryBudgetMB > 0 && Number.isFinite(memoryBudgetMB))) {
      throw new TypeError('Deformer.create: memoryBudgetMB must be a positive number');
    }
    if (onProgress !== undefined && typeof onProgress !== 'function') {
      throw new TypeError('Deformer.create: onProgress must be a function');
    }
    const options = { float32 };
    if (memoryBudgetMB !== undefined) options.memoryBudgetMB = memoryBudgetMB;
    const session = new solver.DeformerSession(
      mesh.positions, mesh.indices, cage?.positions ?? null, cage?.indices ?? null, options, onProgress ?? null);
    return new Deformer(session);
  }

  /** @private use Deformer.create */
  constructor(session) {
    this._session = session;
    this._vertexCount = session.vertexCount();
    this._handleCount = 0;
  }

  /**
   * Partial updates: only the given keys change. Changing the method resets to the rest pose.
   * @param {{ method?: 'subspace'|'full'|'arap', jacobian?: 'fast'|'exact', volume?: boolean,
   *   positionWeight?: number, c1?: number, c2?: number, maxIterations?: number, stepTolerance?: number,
   *   meritTolerance?: number, cgTolerance?: number, cgMaxIterations?: number, cgMemory?: number,
   *   arapEnergyTolerance?: number, arapAcceleration?: number }} options  arapEnergyTolerance: ARAP stops when
   *   an iteration lowers its energy by less than this fraction (default 1e-5); arapAcceleration: Anderson
   *   acceleration depth of ARAP (default 5, 0 = plain local-global)
   */
  setOptions(options) {
    const s = this._live();
    if (!options || typeof options !== 'object') throw new TypeError('setOptions: options must be an object');
    for (const key of Object.keys(options)) {
      if (!OPTION_KEYS.has(key)) throw new TypeError(`setOptions: unknown option '${key}' (known: ${[...OPTION_KEYS].join(', ')})`);
    }
    if (options.method !== undefined && !METHODS.includes(options.method)) {
      throw new TypeError(`setOptions: method must be one of ${METHODS.join(', ')} (got ${JSON.stringify(options.method)})`);
    }
    if (options.jacobian !== undefined && !JACOBIANS.includes(options.jacobian)) {
      throw new TypeError(`setOptions: jacobian must be one of ${JACOBIANS.join(', ')} (got ${JSON.stringify(options.jacobian)})`);
    }
    if (options.volume !== undefined && typeof options.volume !== 'boolean') throw new TypeError('setOptions: volume must be a boolean');
    for (const key of NUMERIC_OPTIONS) {
      const value = options[key];
      if (value !== undefined && !(typeof value === 'number' && Number.isFinite(value))) {
        throw new TypeError(`setOptions: ${key} must be a finite number (got ${JSON.stringify(value)})`);
      }
    }
    for (const key of ['maxIterations', 'cgMaxIterations']) {
      if (options[key] !== undefined && !(Number.isInteger(options[key]) && options[key] >= 1)) {
        throw new RangeError(`setOptions: ${key} must be an integer >= 1`);
      }
    }
    for (const key of ['cgMemory', 'arapAcceleration']) {
      if (options[key] !== undefined && !(Number.isInteger(options[key]) && options[key] >= 0)) {
        throw new RangeError(`setOptions: ${key} must be an integer >= 0`);
      }
    }
    s.setOptions(options);
  }

  /** The current options (all keys). */
  options() {
    return this._live().options();
  }

  /**
   * Handle groups: arrays of vertex indices; not empty, no vertex twice, all in [0, vertexCount).
   * Resets the targets to the handles' current positions.
   * @param {number[][]} groups
   */
  setHandles(groups) {
    const s = this._live();
    if (!Array.isArray(groups)) throw new TypeError('setHandles: groups must be an array of arrays of vertex indices');
    const seen = new Map();
    let count = 0;
    groups.forEach((group, g) => {
      if (!Array.isArray(group) && !ArrayBuffer.isView(group)) throw new TypeError(`setHandles: group ${g} is not an array`);
      if (group.length === 0) throw new RangeError(`setHandles: group ${g} is empty`);
      for (const v of group) {
        if (!Number.isInteger(v)) throw new TypeError(`setHandles: group ${g} has a non-integer vertex index ${v}`);
        if (v < 0 || v >= this._vertexCount) {
          throw new RangeError(`setHandles: group ${g} has vertex ${v} outside [0, ${this._vertexCount})`);
        }
        if (seen.has(v)) {
          const other = seen.get(v);
          throw new RangeError(other === g
            ? `setHandles: vertex ${v} appears twice in group ${g}`
            : `setHandles: vertex ${v} is in both group ${other} and group ${g}`);
        }
        seen.set(v, g);
      }
      count += group.length;
    });
    s.setHandles(groups.map((group) => Array.from(group)));
    this._handleCount = count;
  }

  /**
   * Target positions of the handle vertices: 3 numbers per vertex, groups in order. Cheap (no refactoring).
   * @param {Float64Array} targets
   */
  setTargets(targets) {
    const s = this._live();
    if (!(targets instanceof Float64Array)) throw new TypeError('setTargets: targets must be a Float64Array');
    if (targets.length !== 3 * this._handleCount) {
      throw new RangeError(`setTargets: ${targets.length} numbers for ${this._handleCount} handle vertices (expected ${3 * this._handleCount})`);
    }
    for (let i = 0; i < targets.length; ++i) {
      if (!Number.isFinite(targets[i])) throw new RangeError(`setTargets: target ${Math.floor(i / 3)} is not finite`);
    }
    s.setTargets(targets);
  }

  /**
   * Up to k iterations, warm-started from the current positions.
   * @param {number} [k=1]
   * @returns {StepResult}
   */
  step(k = 1) {
    const s = this._live();
    if (!Number.isInteger(k) || k < 0) throw new RangeError(`step: k must be an integer >= 0 (got ${k})`);
    return s.step(k);
  }

  /** Iterates until converged or maxIterations. @returns {StepResult} */
  solve() {
    return this._live().solve();
  }

  /** Back to the rest pose (handles, targets and options are kept). */
  reset() {
    this._live().reset();
  }

  /** Current deformed mesh positions (a copy): Float64Array of 3 * vertexCount. */
  positions() {
    return this._live().positions();
  }

  /** Current cage positions (a copy): the deformed cage in the subspace method, else the rest cage. */
  cagePositions() {
    return this._live().cagePositions();
  }

  get restVolume() { return this._live().restVolume(); }
  get bindMs() { return this._live().bindMs(); }
  get precomputeMs() { return this._live().precomputeMs(); }
  get vertexCount() { return this._vertexCount; }
  get handleCount() { return this._handleCount; }
  /** Vertices whose Laplacian coordinates needed the fallback (docs/method.md section 4). */
  get fallbackCount() { return this._live().fallbackCount(); }
  get disposed() { return this._session === null; }

  /** Frees the wasm memory of the session. Safe to call twice. */
  dispose() {
    if (this._session) {
      this._session.delete();
      this._session = null;
    }
  }

  _live() {
    if (!this._session) throw new Error('Deformer: this session was disposed');
    return this._session;
  }
}

function assertMeshData(mesh, role) {
  if (!mesh || typeof mesh !== 'object') throw new TypeError(`Deformer.create: ${role} must be { positions, indices }`);
  if (!(mesh.positions instanceof Float64Array)) throw new TypeError(`Deformer.create: ${role}.positions must be a Float64Array`);
  if (!(mesh.indices instanceof Uint32Array)) throw new TypeError(`Deformer.create: ${role}.indices must be a Uint32Array`);
  if (mesh.positions.length % 3 !== 0) throw new RangeError(`Deformer.create: ${role}.positions length ${mesh.positions.length} is not a multiple of 3`);
  if (mesh.indices.length % 3 !== 0) throw new RangeError(`Deformer.create: ${role}.indices length ${mesh.indices.length} is not a multiple of 3`);
  const n = mesh.positions.length / 3;
  for (let i = 0; i < mesh.indices.length; ++i) {
    if (mesh.indices[i] >= n) {
      throw new RangeError(`Deformer.create: ${role} face ${Math.floor(i / 3)} uses vertex ${mesh.indices[i]}, but there are only ${n} vertices`);
    }
  }
}
