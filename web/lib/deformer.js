// @ts-check
// Validated JS layer over the Deformer session (cpp/core/solver/deformer.h via cpp/bindings/deformer_bindings.cpp):
// constrained Gauss-Newton deformation in the cage subspace, or the cage-free spectral subspace (basis: 'spectral'), or
// the full space, or ARAP, one session per model; the volume kept globally or per part. The JS types of the arguments
// are checked here, before entering wasm, so mistakes surface as InputErrors naming the argument; the rules on handles
// and targets (no empty group, indices of the mesh, no vertex twice, finite targets, 3 per handle vertex) are the C++
// session's alone; its failures arrive as typed errors (errors.js) carrying the C++ code and message.
//
//   const d = Deformer.create(solver, mesh, cage);      // binds W once (d.bindMs)
//   (or Deformer.create(solver, mesh, cage, { coordinates: 'harmonic' }): another cage basis W;
//    or Deformer.create(solver, mesh, null, { basis: 'spectral', modes: 40 }): no cage needed)
//   d.setVolumeParts(parts);                            // optional: one part index per triangle (parts.js)
//   d.setHandles([[0, 1, 2], [57]]);                    // vertex groups
//   d.setTargets(targets);                              // Float64Array, 3 numbers per handle vertex
//   d.setHandleLines([null, { along: [0, 0, -1] }]);    // optional: group 1 held only across the view
//   d.setSkeleton({ joints: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]] });  // optional: rigid limbs
//   const { iterations, converged, stop } = d.step(1);  // warm-started; stop: why it returned (STOP_CODES)
//   const positions = d.positions();                    // Float64Array copy
//   d.dispose();

import { STOP_CODES } from '../../build/wasm/solver_schema.js';
import { InputError, callWasm, callWasmWithCallback } from './errors.js';
import { checkHandleLine, packHandleLines } from './handle_lines.js';
import { SPECTRAL_MIN_VERTICES, assertMesh, assertMinVertices, assertTargetsNear } from './mesh.js';
import { checkNormalGroups } from './normals.js';
import { assertAttached } from './typed_arrays.js';
import { checkSolverOptions } from './options.js';
import { checkSkeleton, packSkeleton } from './skeleton.js';
import { BASES, isSpectral, parseSubspace } from './subspace.js';
import { weightsOutOfMemory } from './wasm_allocation.js';

/** @typedef {import('./mesh.js').MeshData} MeshData */
/** @typedef {import('./options.js').SolverOptions} SolverOptions */
/** @typedef {import('./deformer_types.js').IterationStats} IterationStats */
/** @typedef {import('./deformer_types.js').ReducedIntegrationInfo} ReducedIntegrationInfo */
/** @typedef {import('./deformer_types.js').LineSearchTrial} LineSearchTrial */
/** @typedef {import('./deformer_types.js').ArapHalfStep} ArapHalfStep */
/** @typedef {import('./deformer_types.js').StopCode} StopCode */
/** @typedef {import('./deformer_types.js').StepResult} StepResult */
/** @typedef {import('./deformer_types.js').CageQuality} CageQuality */
/** @typedef {import('./coordinates.js').CoordinatesReport} CoordinatesReport */

/** Every stop code with whether it means "converged" and its standard text, from the C++ enum. */
export { STOP_CODES };

// Iteration counts cross into C++ as int.
const MAX_INT = 2147483647;

/** The subspace bases: the cage's coordinates, or the mesh's low Laplacian modes (no cage); subspace.js. */
export { BASES };

export class Deformer {
  /**
   * Validates the mesh (and cage) and binds the subspace basis once: the cage's mean value coordinates W, or
   * with basis 'spectral' the mesh's k = modes lowest Laplace-Beltrami modes (docs/method.md section 15).
   * @param {import('./solver_module.js').SolverModule} solver the module from loadSolver() / loadNodeSolver()
   * @param {MeshData} mesh the model as read (its own vertex layout: seams, unreferenced vertices, open or
   *   several components are fine; checkMesh says how it is taken); every per-vertex and per-triangle input and
   *   output of the session is in its numbering
   * @param {MeshData|null} cage closed cage strictly around the mesh; null: no cage (full space and ARAP only,
   *   unless the basis is 'spectral'); ignored by the spectral basis
   * @param {{ float32?: boolean, memoryBudgetMB?: number, onProgress?: (fraction: number) => (boolean|void),
   *   weldTolerance?: number } & import('./subspace.js').SubspaceFields} [options]
   *   float32 stores the basis in single precision (half the memory and bandwidth); onProgress returning false
   *   cancels (a CancelledError), an exception it throws reaches the caller unchanged; modes: the spectral basis'
   *   number of eigenvectors (required with basis 'spectral'); weldTolerance: split vertices within this times
   *   the bounding-box diagonal are one point for the solver (default 1e-6; 0: only equal positions;
   *   docs/library.md, "Vertex layout"); coordinates ('mvc', the default, 'pmvc' or 'harmonic') and its
   *   resolution: which coordinates the cage basis binds (coordinates.js; not with the spectral basis). The
   *   subspace's fields (basis, modes, coordinates and resolutions) follow subspace.js' rules.
   * @returns {Deformer}
   */
  static create(solver, mesh, cage, {
    float32 = false, memoryBudgetMB, onProgress, basis, modes, weldTolerance, coordinates, pmvcResolution,
    harmonicResolution,
  } = {}) {
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
    const subspace = parseSubspace({ basis, modes, coordinates, pmvcResolution, harmonicResolution });
    if (isSpectral(subspace)) assertMinVertices(mesh, SPECTRAL_MIN_VERTICES, 'Deformer.create: the spectral basis');
    if (weldTolerance !== undefined && !(typeof weldTolerance === 'number' && weldTolerance >= 0 && weldTolerance <= 0.01)) {
      throw new InputError(`Deformer.create: weldTolerance must be a number from 0 to 0.01 (got ${JSON.stringify(weldTolerance)})`);
    }
    const options = /** @type {Record<string, unknown>} */ ({ float32, weldTolerance, ...subspace });
    if (memoryBudgetMB !== undefined) options.memoryBudgetMB = memoryBudgetMB;
    // An exception of onProgress reaches the caller as it was thrown (the binding frees the half-built session).
    try {
      const session = callWasmWithCallback(onProgress, (progress) => new solver.DeformerSession(
        mesh.positions, mesh.indices, cage?.positions ?? null, cage?.indices ?? null, options, progress ?? null));
      return new Deformer(session);
    } catch (error) {
      throw cage && !isSpectral(subspace) ? weightsOutOfMemory(error, mesh, cage, float32) : error;
    }
  }

  /** @private use Deformer.create @param {any} session the embind DeformerSession */
  constructor(session) {
    this._normalGroups = /** @type {Int32Array|null|undefined} */ (undefined); // what renderBuffers last gave the session
    this._restNormals = /** @type {Float32Array|null|undefined} */ (undefined); // (undefined: nothing yet)
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
   * Handle groups: arrays of vertex indices; not empty, no vertex twice, all in [0, vertexCount) (checked by the
   * C++ session, whose InputError names the group and the vertex). Resets the targets to the handles' current
   * positions.
   * @param {ArrayLike<number>[]} groups arrays or typed arrays
   */
  setHandles(groups) {
    const s = this._live();
    callWasm(() => s.setHandles(Array.isArray(groups) ? groups.map((group, g) => assertAttached(group, `setHandles: group ${g}`)) : groups));
    this._handleCount = groups.reduce((count, group) => count + group.length, 0);
  }

  /**
   * Target positions of the handle vertices: 3 finite numbers per vertex, groups in order (the C++ session checks
   * the count and the values), none beyond MAX_MESH_COORDINATE as in a scene (else the solve overflows and
   * ends in numerical_failure). Cheap (no refactoring).
   * @param {Float64Array} targets
   */
  setTargets(targets) {
    const s = this._live();
    if (!(targets instanceof Float64Array)) throw new InputError('setTargets: targets must be a Float64Array');
    assertTargetsNear(assertAttached(targets, 'setTargets: targets'), 'setTargets');
    callWasm(() => s.setTargets(targets));
  }

  /**
   * The projection constraint (handle_lines.js): per handle group { along: [dx, dy, dz] }, { from: [x, y, z] } or
   * null (a point target); null or []: all point targets. Cheap; setHandles clears them; ARAP ignores them.
   * @param {import('./handle_lines.js').HandleLine[]|null} lines
   */
  setHandleLines(lines) {
    const s = this._live();
    if (lines !== null && lines !== undefined && !Array.isArray(lines)) throw new InputError('setHandleLines: lines must be an array (one per handle group) or null');
    const checked = (lines ?? []).map((line, g) => checkHandleLine(line, `setHandleLines: lines[${g}]`));
    callWasm(() => s.setHandleLines(packHandleLines(checked)));
  }

  /** Per handle group, the farthest of its vertices from its line (or its target). @returns {Float64Array} */
  handleDistances() { return callWasm(() => this._live().handleDistances()); }

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
  solve() { return callWasm(() => this._live().solve()); }

  /**
   * ARAP step-through (method 'arap', with handles): one half of the next local-global iteration from the
   * current positions, without acceleration: 'local' (the best rotation of every vertex; positions unchanged)
   * or 'global' (the positions for those rotations). Energies are ARAP's with the rotations before and after.
   * @param {'local'|'global'} phase
   * @returns {ArapHalfStep}
   */
  arapHalfStep(phase) {
    const s = this._live();
    if (phase !== 'local' && phase !== 'global') throw new InputError(`arapHalfStep: phase must be 'local' or 'global' (got ${phase})`);
    return callWasm(() => s.arapHalfStep(phase));
  }

  /**
   * The reduced integration's fit (option integration: 'reduced', docs/method.md section 17): made on the first
   * reduced solve or by prepareReduced(), kept until the weighting changes.
   * @returns {ReducedIntegrationInfo}
   */
  reducedIntegration() { return callWasm(() => this._live().reducedIntegration()); }

  /** Makes the reduced integration's fit now (a second or so on large meshes) rather than on the first reduced solve. */
  prepareReduced() { callWasm(() => this._live().prepareReduced()); }

  /** Makes the factor preconditioner's pose-free parts now, not in the first solve that buys it (method.md 11.1; 0.2-0.5 s
   *  on large models); nothing unless method 'subspace' and preconditioner 'gauss-newton'; kept until the weighting changes. */
  prepareFactor() { callWasm(() => this._live().prepareFactor()); }

  /**
   * The energy 1/2 |f|^2 summed over every vertex at the current positions, plus the cage regularisation: what a
   * reduced solve reached, measured without sampling. @returns {number}
   */
  fullEnergy() { return callWasm(() => this._live().fullEnergy()); }

  /** Back to the rest pose (handles, targets and options are kept). */
  reset() { callWasm(() => this._live().reset()); }

  /** Current deformed mesh positions (a copy): Float64Array of 3 * vertexCount. @returns {Float64Array} */
  positions() { return callWasm(() => this._live().positions()); }

  /**
   * What a renderer draws of the current positions: Float32 positions and unit vertex normals (area-weighted,
   * as three.js computes them; shared within `groups`, the file's `restNormals` where a sum vanishes), computed
   * in wasm on the thread pool. `groups` (normals.js normalGroups: one id in [0, vertexCount) per vertex, else an
   * InputError) and `restNormals` are kept until others are given.
   * @param {{ groups?: Int32Array|null, restNormals?: Float32Array|null }} [layout] @returns {{ positions: Float32Array, normals: Float32Array }}
   */
  renderBuffers({ groups = null, restNormals = null } = {}) {
    const s = this._live();
    if (groups !== this._normalGroups || restNormals !== this._restNormals) {
      callWasm(() => s.setNormalGroups(checkNormalGroups(groups, this._vertexCount, 'renderBuffers: groups'), assertAttached(restNormals, 'renderBuffers: restNormals')));
      this._normalGroups = groups;
      this._restNormals = restNormals;
    }
    return callWasm(() => s.renderBuffers());
  }

  /**
   * Current cage positions (a copy): the deformed cage in the subspace method, else the rest cage.
   * @returns {Float64Array}
   */
  cagePositions() { return callWasm(() => this._live().cagePositions()); }

  /**
   * The cage's quality (computed on each call: O(rows m^2) with at most ~8192 sampled rows, then an m x m
   * eigen-solve). A session without a cage, or with the spectral basis, throws an InputError with code 'no_cage'.
   * @returns {CageQuality}
   */
  cageQuality() { return callWasm(() => this._live().cageQuality()); }

  /**
   * The vertex layout's counts (LayoutStats; docs/library.md, "Vertex layout") and solverOfFile: each vertex's
   * welded point, -1 for one carried along. @returns {import('./mesh.js').LayoutStats & { solverOfFile: Int32Array }}
   */
  layout() { return callWasm(() => this._live().layout()); }

  /**
   * The current result's warnings (deformation_check.h): folded_triangles, cage_self_intersecting. Costs a pass
   * over the triangles and the cage's intersection test: once a solve settles. @returns {import('./errors.js').Finding[]}
   */
  resultWarnings() { return callWasm(() => this._live().resultWarnings()); }

  /**
   * The skeleton (skeleton.js; docs/method.md section 5.4): joints inside the mesh and bones between them, whose
   * lengths and straightness every Gauss-Newton solve then keeps (ARAP ignores it); null: none. Positions are kept;
   * the next step restores the bones. Throws an InputError (code 'invalid_skeleton', skeleton unchanged) for a
   * joint outside the mesh, a bone that leaves the mesh between its joints, a zero-length bone, an open mesh, or bones
   * whose lengths the method's space cannot keep.
   * @param {import('./skeleton.js').Skeleton|null} skeleton
   */
  setSkeleton(skeleton) {
    const s = this._live();
    const checked = checkSkeleton(skeleton, 'setSkeleton: skeleton');
    const packed = checked ? packSkeleton(checked) : null;
    callWasm(() => s.setSkeleton(packed?.joints ?? null, packed?.bones ?? null));
  }

  /** The deformed joints and each bone's errors and multiplier; null without a skeleton. @returns {import('./skeleton.js').SkeletonReport|null} */
  skeletonReport() { return callWasm(() => this._live().skeletonReport()); }

  /**
   * Keeps the volume per part (docs/method.md section 16) instead of globally: one part index per triangle,
   * parts 0 .. K-1 each used (parts.js makes them from lists or automatically); null or empty: the default
   * parts again (one per connected component: a single closed mesh keeps one global volume). Positions are
   * kept; the next step restores the parts' rest volumes.
   * @param {Int32Array|Uint32Array|number[]|null} parts @returns {void}
   */
  setVolumeParts(parts) {
    const s = this._live();
    if (parts === null || parts === undefined) return callWasm(() => s.setVolumeParts(null));
    if (!Array.isArray(parts) && !(parts instanceof Int32Array) && !(parts instanceof Uint32Array)) {
      throw new InputError('setVolumeParts: parts must be an Int32Array or an array of part indices, one per triangle');
    }
    return callWasm(() => s.setVolumeParts(assertAttached(parts, 'setVolumeParts: parts')));
  }

  /**
   * The volume parts, one per triangle: those set, or the default ones of an open mesh or of several components;
   * empty: the one global volume. @returns {Int32Array}
   */
  volumeParts() {
    const s = this._live();
    return callWasm(() => s.volumeParts());
  }

  /** Rest volume of each part (the whole rest volume alone without parts). @returns {Float64Array} */
  restPartVolumes() {
    const s = this._live();
    return callWasm(() => s.restPartVolumes());
  }

  /** Volume of each part at the current positions (the whole volume without parts). @returns {Float64Array} */
  partVolumes() {
    const s = this._live();
    return callWasm(() => s.partVolumes());
  }

  /**
   * The subspace coefficients (3 numbers per basis column, row-major): the cage vertices P with the cage
   * basis, the coefficients C of the spectral one.
   * @returns {Float64Array}
   */
  subspaceCoefficients() {
    const s = this._live();
    return callWasm(() => s.subspaceCoefficients());
  }

  /** The spectral basis' eigenvalues lambda_0 (~0) .. lambda_k (empty for the cage). @returns {Float64Array} */
  basisEigenvalues() {
    const s = this._live();
    return callWasm(() => s.basisEigenvalues());
  }

  /** 'cage' or 'spectral'. @returns {'cage'|'spectral'} */
  get basis() { return /** @type {'cage'|'spectral'} */ (this._live().basis()); }

  /** What binding the cage's W found (coordinates.js); null with the spectral basis or without a cage. @returns {CoordinatesReport|null} */
  coordinatesReport() {
    const s = this._live();
    return callWasm(() => s.coordinatesReport());
  }

  /** The cage coordinates W holds ('mvc', 'pmvc', 'harmonic'); null with the spectral basis or without a cage. */
  get coordinates() { return this.coordinatesReport()?.coordinates ?? null; }

  /**
   * Column j (0 .. basisSize - 1) of the basis at every vertex of the file (as positions()), a copy: cage vertex j's weight (or the
   * spectral column j); an InputError 'no_cage' without a basis. @param {number} j @returns {Float32Array}
   */
  basisColumn(j) {
    const s = this._live();
    if (this.basisSize === 0) throw new InputError('basisColumn: this session has no subspace basis (no cage)', { code: 'no_cage' });
    if (!Number.isInteger(j) || j < 0 || j >= this.basisSize) {
      throw new InputError(`basisColumn: j must be an integer from 0 to ${this.basisSize - 1} (got ${JSON.stringify(j)})`);
    }
    return callWasm(() => s.basisColumn(j));
  }
  /** Columns of the subspace basis (cage vertices m, or k + 4; 0 without a basis). @returns {number} */
  get basisSize() { return this._live().basisSize(); }
  /** Enclosed volume of the rest mesh. @returns {number} */
  get restVolume() { return this._live().restVolume(); }
  /** Time binding the basis took (W, or the spectral basis' eigen-decomposition). @returns {number} */
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
