// The app's settings: solver options, display and interaction, with their defaults. One object shared by the
// views (solver options per method), the scene files (their "solver" part) and the panel (through the app's
// 'options' event). The solver options, their defaults and their checks are the library's (web/lib/options.js,
// written from the C++ table), so an option added there reaches scenes and the app by itself; the app adds a
// second iteration cap for ARAP. update() checks and merges a partial change and dispatches 'change'.
import { EventDispatcher } from 'three';
import { COORDINATES } from '../lib/coordinates.js';
import { InputError } from '../lib/errors.js';
import { DEFAULT_OPTIONS, OPTION_NAMES, checkSolverOptions, describeValue, optionAllows, optionSchema } from '../lib/options.js';

/** Solver options the panel shows and every saved scene lists, in scene order (maxIterations: per method). */
const PANEL_SOLVER_KEYS = ['jacobian', 'volume', 'weighting', 'maxIterations', 'positionWeight', 'c1', 'c2'];

/** The library's other options (tolerances, ...): a scene may set them; sent to the worker only once set. */
const EXTRA_SOLVER_KEYS = OPTION_NAMES.filter((name) => name !== 'method' && !PANEL_SOLVER_KEYS.includes(name));

export const DEFAULT_SETTINGS = {
  method: DEFAULT_OPTIONS.method,
  ...Object.fromEntries(PANEL_SOLVER_KEYS.map((key) => [key, DEFAULT_OPTIONS[key]])),
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
  // The subspace basis a model is bound with (the next binding; DeformerApp.setBasis rebinds the current one):
  // the cage's, or the mesh's spectral basis with spectralModes eigenvectors (docs/method.md section 15).
  basis: 'cage',
  spectralModes: 40,
  // The cage basis' coordinates (the next binding; DeformerApp.setCoordinates rebinds the current model): 'mvc',
  // 'pmvc' or 'harmonic' (docs/method.md sections 2, 17, 18), and each type's resolution (harmonic 0: chosen from
  // the cage). compareCoordinates: the second view of "compare coordinates", the same solve beside the first.
  coordinates: COORDINATES.types[0],
  pmvcResolution: COORDINATES.pmvcResolution.default,
  harmonicResolution: COORDINATES.harmonicResolution.default,
  compareCoordinates: 'harmonic',
  autoParts: 6, // K of "auto parts" (docs/method.md section 16)
  // The threads the views' workers share (docs/threads.md): 'auto' = every core of the page. A setting of the
  // page, not of the solve: it changes no result, so it is neither a solver option nor saved in scenes.
  threads: 'auto',
};

/** Range of the spectral basis' modes in the app (the library takes any k up to the vertex count - 5). */
export const SPECTRAL_MODES_RANGE = { min: 1, max: 300 };
/** Range of "auto parts". */
export const AUTO_PARTS_RANGE = { min: 2, max: 16 };

/** Range of the "Generate cage" size control. */
export const CAGE_VERTICES_RANGE = { min: 20, max: 1000 };

/** Throws an InputError unless `vertices` is a cage size "Generate cage" accepts. */
export function checkCageSize(vertices) {
  const { min, max } = CAGE_VERTICES_RANGE;
  if (!Number.isInteger(vertices) || vertices < min || vertices > max) {
    throw new InputError(`generateCage: vertices must be an integer from ${min} to ${max} (got ${describeValue(vertices)})`);
  }
}

/** Settings that change only what is drawn, how the mouse edits, the next binding or how fast the workers run:
 *  the solvers need not hear of them. */
const VIEW_KEYS = new Set(['showCage', 'showHandles', 'wireframe', 'flatShading', 'gizmoMode', 'brushRadius', 'cageVertices',
  'basis', 'spectralModes', 'coordinates', 'pmvcResolution', 'harmonicResolution', 'compareCoordinates', 'autoParts', 'threads']);

/** True when a change of these settings concerns the solvers (options, method, caps, request size). */
export function touchesSolver(changed) {
  return Object.keys(changed).some((key) => !VIEW_KEYS.has(key));
}

/** Throws an InputError unless `value` is an integer in `range`, naming `key`. */
function checkInteger(value, range, key, where) {
  if (value !== undefined && !(Number.isInteger(value) && value >= range.min && value <= range.max)) {
    throw new InputError(`${where}: ${key} must be an integer from ${range.min} to ${range.max} (got ${describeValue(value)})`);
  }
}

/** Checks the coordinates settings: the types, and each resolution within its type's limits. */
function checkCoordinatesSettings({ coordinates, compareCoordinates, pmvcResolution, harmonicResolution }, where) {
  for (const [key, value] of [['coordinates', coordinates], ['compareCoordinates', compareCoordinates]]) {
    if (value !== undefined && !COORDINATES.types.includes(value)) {
      throw new InputError(`${where}: ${key} must be one of ${COORDINATES.types.join(', ')} (got ${describeValue(value)})`);
    }
  }
  checkInteger(pmvcResolution, COORDINATES.pmvcResolution, 'pmvcResolution', where);
  if (harmonicResolution !== 0) checkInteger(harmonicResolution, COORDINATES.harmonicResolution, 'harmonicResolution', where);
}

/** Checks the solver options among `settings` (the library's check), the ARAP cap (as maxIterations), the basis and the coordinates. */
function check(settings, where) {
  const { arapMaxIterations, basis, spectralModes, autoParts, threads, coordinates, compareCoordinates, pmvcResolution,
    harmonicResolution, ...rest } = settings;
  if (basis !== undefined && basis !== 'cage' && basis !== 'spectral') {
    throw new InputError(`${where}: basis must be 'cage' or 'spectral' (got ${describeValue(basis)})`);
  }
  checkCoordinatesSettings({ coordinates, compareCoordinates, pmvcResolution, harmonicResolution }, where);
  checkInteger(spectralModes, SPECTRAL_MODES_RANGE, 'spectralModes', where);
  checkInteger(autoParts, AUTO_PARTS_RANGE, 'autoParts', where);
  if (threads !== undefined && threads !== 'auto' && !(Number.isInteger(threads) && threads >= 1 && threads <= 1024)) {
    throw new InputError(`${where}: threads must be 'auto' or an integer from 1 to 1024 (got ${describeValue(threads)})`);
  }
  checkSolverOptions(Object.fromEntries(Object.entries(rest).filter(([key]) => OPTION_NAMES.includes(key))), where);
  const cap = optionSchema('maxIterations');
  if (arapMaxIterations !== undefined && !optionAllows(cap, arapMaxIterations)) {
    throw new InputError(`${where}: arapMaxIterations must be ${cap.expects} (got ${describeValue(arapMaxIterations)})`);
  }
}

export class AppSettings extends EventDispatcher {
  /** @param {object} [initial] values that replace the defaults (checked as update() checks them) */
  constructor(initial = {}) {
    super();
    check(initial, 'settings');
    this.values = { ...DEFAULT_SETTINGS, ...initial };
  }

  /**
   * Merges `partial` and dispatches { type: 'change', changed: partial }. Solver options (and the ARAP cap)
   * are checked first: an InputError names a bad one and nothing changes.
   */
  update(partial) {
    check(partial, 'setOptions');
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
