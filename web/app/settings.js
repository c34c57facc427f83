// The app's settings: solver options, display and interaction, with their defaults. One object shared by the
// views (solver options per method), the scene files (their "solver" part) and the panel (through the app's
// 'options' event). update() merges a partial change and dispatches 'change'.
import { EventDispatcher } from 'three';

export const DEFAULT_SETTINGS = {
  method: 'subspace',
  jacobian: 'fast',
  volume: true,
  positionWeight: 1,
  c1: 1e-4,
  c2: 0.5,
  maxIterations: 100, // Gauss-Newton (subspace, full): iterations after the last change before "stopped"
  // ARAP's local-global iterations converge linearly: from rest to a large pull they need 70-180+ (bar, sphere;
  // docs/app.md), far more than Gauss-Newton, while each is cheap. Its own cap, so 100 does not stop it early.
  arapMaxIterations: 1000,
  iterationsPerFrame: 'auto',
  showCage: true,
  showHandles: true,
  wireframe: false,
  flatShading: false,
  gizmoMode: 'translate',
  brushRadius: 0.04, // fraction of the bounding-box diagonal
  cageVertices: 120, // target size K of "Generate cage" (docs/cage.md: 20-1000 tested)
};

/** Solver options the panel always sends, in scene order (maxIterations is per method: maxIterationsFor). */
const PANEL_SOLVER_KEYS = ['jacobian', 'volume', 'maxIterations', 'positionWeight', 'c1', 'c2'];

/** Solver options a scene may set beyond the panel's (tolerances; sent to the worker only when set). */
const EXTRA_SOLVER_KEYS = ['stepTolerance', 'meritTolerance', 'cgTolerance', 'cgMaxIterations', 'cgMemory', 'arapEnergyTolerance',
  'arapAcceleration'];

/** Range of the "Generate cage" size control. */
export const CAGE_VERTICES_RANGE = { min: 20, max: 1000 };

/** Throws a RangeError unless `vertices` is a cage size "Generate cage" accepts. */
export function checkCageSize(vertices) {
  const { min, max } = CAGE_VERTICES_RANGE;
  if (!Number.isInteger(vertices) || vertices < min || vertices > max) {
    throw new RangeError(`generateCage: vertices must be an integer from ${min} to ${max} (got ${vertices})`);
  }
}

/** Settings that change only what is drawn or how the mouse edits: the solvers need not hear of them. */
const VIEW_KEYS = new Set(['showCage', 'showHandles', 'wireframe', 'flatShading', 'gizmoMode', 'brushRadius', 'cageVertices']);

/** True when a change of these settings concerns the solvers (options, method, caps, request size). */
export function touchesSolver(changed) {
  return Object.keys(changed).some((key) => !VIEW_KEYS.has(key));
}

export class AppSettings extends EventDispatcher {
  /** @param {object} [initial] values that replace the defaults */
  constructor(initial = {}) {
    super();
    this.values = { ...DEFAULT_SETTINGS, ...initial };
  }

  /** Merges `partial` and dispatches { type: 'change', changed: partial }. */
  update(partial) {
    Object.assign(this.values, partial);
    this.dispatchEvent({ type: 'change', changed: partial });
  }

  /** A copy of every value (what scripts and the panel see). */
  snapshot() {
    return { ...this.values };
  }

  /** The iteration cap of a method (ARAP has its own, see DEFAULT_SETTINGS). */
  maxIterationsFor(method) {
    return method === 'arap' ? this.values.arapMaxIterations : this.values.maxIterations;
  }

  /** The Deformer options of a method: the panel's, the method's cap, and any extra option a scene set. */
  solverOptions(method) {
    const options = {};
    for (const key of PANEL_SOLVER_KEYS) options[key] = key === 'maxIterations' ? this.maxIterationsFor(method) : this.values[key];
    for (const key of EXTRA_SOLVER_KEYS) if (this.values[key] !== undefined) options[key] = this.values[key];
    return options;
  }

  /** A scene's "solver" (the same options plus the method). */
  toScene(method) {
    return { method, ...this.solverOptions(method) };
  }

  /**
   * Settings from a parsed scene's "solver": its maxIterations is the cap of the scene's method (or, without
   * one, of `currentMethod`).
   */
  static fromScene(solver, currentMethod) {
    const { maxIterations, ...rest } = solver;
    const method = solver.method ?? currentMethod;
    if (maxIterations !== undefined) rest[method === 'arap' ? 'arapMaxIterations' : 'maxIterations'] = maxIterations;
    return rest;
  }
}
