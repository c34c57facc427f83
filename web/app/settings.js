// The app's settings as data: every solver option of the library (web/lib/options.js, written from the C++
// table, so an option added there reaches the app by itself) and the app's own settings (display,
// interaction, the next binding, threads), each with its kind, limits, default and one line of doc. The one
// check of a settings object, checkSettings, is driven by this table; setOptions, the constructor, scenes,
// URL parameters and embed attributes (page_options.js) all go through it, so a value is refused the same
// way wherever it comes from: an InputError naming the setting and what it expects, and nothing changes.
// AppSettings holds the values and dispatches 'change'.
import { EventDispatcher } from 'three';
import { COORDINATES } from '../lib/coordinates.js';
import { InputError } from '../lib/errors.js';
import { DEFAULT_OPTIONS, OPTIONS, describeValue, optionAllows } from '../lib/options.js';
import { BASES } from '../lib/subspace.js';

/**
 * A menu's labelled counts ({ '1 iteration': 1, '2 iterations': 2 }): labels that are no integers keep their order
 * after a default put first (an object's integer keys enumerate before every other key).
 */
export function countChoices(counts, noun) {
  return Object.fromEntries(counts.map((n) => [`${n} ${noun}${n === 1 ? '' : 's'}`, n]));
}

/**
 * The panel's Solver folder, in its order: the solver options it shows and the app's settings of the solve. A row
 * names the setting, its label and, for a number, the slider's range (narrower than the setting's limits: finer
 * values are for scenes and the CLI); a choice or a boolean takes its values from the setting's schema (`choices`:
 * labelled ones instead). A solver option added to the C++ table reaches setOptions, scenes and every check by
 * itself; a row here gives it a control, a default in the app and a place in every saved scene.
 * @type {readonly { key: string, label: string, min?: number, max?: number, choices?: Record<string, unknown> }[]}
 */
export const SOLVER_CONTROLS = Object.freeze([
  { key: 'method', label: 'method' },
  { key: 'jacobian', label: 'Jacobian' },
  { key: 'volume', label: 'volume constraint' },
  { key: 'weighting', label: 'energy weighting' },
  { key: 'dragIntegration', label: 'integration while dragging' },
  { key: 'positionWeight', label: 'position weight', min: 0.01, max: 100 },
  { key: 'straightnessWeight', label: 'bone straightness', min: 0, max: 30 },
  { key: 'c1', label: 'Armijo c1', min: 1e-6, max: 0.5 },
  { key: 'c2', label: 'backtrack c2', min: 0.1, max: 0.9 },
  { key: 'maxIterations', label: 'max iterations', min: 1, max: 1000 },
  { key: 'arapMaxIterations', label: 'ARAP max iterations', min: 1, max: 5000 },
  { key: 'iterationsPerFrame', label: 'iterations / request', choices: { 'auto (frame budget)': 'auto', ...countChoices([1, 2, 3, 5, 10, 20], 'iteration') } },
]);

/** Solver options the panel shows and every saved scene lists, in the library's order (maxIterations: per method). */
const PANEL_SOLVER_KEYS = OPTIONS.map((o) => o.name).filter((name) => name !== 'method' && SOLVER_CONTROLS.some((c) => c.key === name));

/** The library's other options (tolerances, ...): a scene may set them; sent to the worker only once set. */
const EXTRA_SOLVER_KEYS = OPTIONS.map((o) => o.name).filter((name) => name !== 'method' && !PANEL_SOLVER_KEYS.includes(name));

const MAX_INT = 2147483647;

/** Values of settings.dragIntegration. */
export const DRAG_INTEGRATIONS = ['auto', 'full', 'reduced'];

/** The tools of a one-finger press (settings.tool). */
export const TOOLS = ['orbit', 'pick', 'brush', 'lasso', 'bone'];

/** Range of the spectral basis' modes in the app (the library takes any k up to the vertex count - 5). */
export const SPECTRAL_MODES_RANGE = { min: 1, max: 300 };
/** Range of "auto parts". */
export const AUTO_PARTS_RANGE = { min: 2, max: 16 };
/** Range of the "Generate cage" size control. */
export const CAGE_VERTICES_RANGE = { min: 20, max: 1000 };

/**
 * One app setting, in the shape of the library's OptionSchema (options.js) plus `also`: words accepted beside
 * the kind's values ('auto').
 * @typedef {import('../lib/options.js').OptionSchema & { also: string[], solver: boolean }} SettingSchema
 */

// An app setting's schema from a short description; `expects` is what messages say, as the library's do.
function setting(name, kind, doc, fallback, { min = null, max = null, minOpen = false, choices = [], also = [] } = {}) {
  const range = min === null ? '' : minOpen ? ` above ${min} and up to ${max}` : ` from ${min} to ${max}`;
  const base = kind === 'boolean' ? 'true or false' : kind === 'choice' ? choices.map((c) => `'${c}'`).join(', ')
    : `${kind === 'integer' ? 'an integer' : 'a number'}${range}`;
  const expects = also.length ? `${also.map((a) => `'${a}'`).join(' or ')} or ${base}` : kind === 'choice' ? `one of ${base}` : base;
  return Object.freeze({ name, kind, doc, default: fallback, min, max, minOpen, maxOpen: false, choices: Object.freeze([...choices]),
    also: Object.freeze(also), expects, solver: false });
}

// ARAP's local-global iterations converge linearly: from rest to a large pull they need 70-180+ (bar, sphere;
// docs/app.md), far more than Gauss-Newton, while each is cheap. Its own cap, so 100 does not stop it early.
const APP_SETTINGS = [
  setting('arapMaxIterations', 'integer', "ARAP's iteration cap (the solver option maxIterations is Gauss-Newton's)", 1000,
    { min: 1, max: MAX_INT }),
  setting('iterationsPerFrame', 'integer', "iterations per request to a view's worker ('auto': fitted to a 25 ms budget)",
    'auto', { min: 1, max: 1000, also: ['auto'] }),
  // The subspace's integration while the handles move (integration_policy.js); the settled shape always uses the
  // solver option integration (full by default).
  setting('dragIntegration', 'choice', "the subspace's integration while the handles move ('auto': reduced on models " +
    'of 20k vertices and more)', 'auto', { choices: DRAG_INTEGRATIONS }),
  setting('showCage', 'boolean', 'draw the cage', true),
  setting('showHandles', 'boolean', 'draw the handle groups and their targets', true),
  setting('wireframe', 'boolean', 'draw the mesh as a wireframe', false),
  setting('flatShading', 'boolean', 'flat shading', false),
  setting('gizmoMode', 'choice', 'what the gizmo on the moving group does', 'translate', { choices: ['translate', 'rotate'] }),
  // What a one-finger (or left-button) press in a view does (tool strip, docs/app.md): 'orbit' (turn the camera,
  // taps do nothing), 'pick' (tap a vertex, drag orbits), 'brush' or 'lasso' (drag selects), 'bone' (taps place
  // joints and bones: skeleton/bone_tool.js); erase: those remove
  // from the selection instead (what Ctrl does with a mouse). Two fingers always zoom and pan.
  setting('tool', 'choice', 'what a one-finger (or left-button) press in a view does', 'pick', { choices: TOOLS }),
  setting('erase', 'boolean', 'the brush, lasso and taps remove from the selection instead', false),
  setting('brushRadius', 'number', 'the brush radius, as a fraction of the bounding-box diagonal', 0.04,
    { min: 0, max: 0.5, minOpen: true }),
  setting('cageVertices', 'integer', 'target size K of "Generate cage" (docs/cage.md: 20-1000 tested)', 120, CAGE_VERTICES_RANGE),
  // The subspace basis a model is bound with (the next binding; DeformerApp.setBasis rebinds the current one):
  // the cage's, or the mesh's spectral basis with spectralModes eigenvectors (docs/method.md section 15).
  setting('basis', 'choice', 'the subspace basis of the next binding', 'cage', { choices: BASES }),
  setting('spectralModes', 'integer', "the spectral basis' eigenvectors", 40, SPECTRAL_MODES_RANGE),
  // The cage basis' coordinates of the next binding (DeformerApp.setCoordinates rebinds the current model), each
  // type's resolution, and the second view of "compare coordinates" (docs/method.md sections 2, 18, 19).
  setting('coordinates', 'choice', "the cage's coordinates of the next binding", COORDINATES.types[0], { choices: COORDINATES.types }),
  setting('pmvcResolution', 'integer', "positive mean value coordinates' sampling: a cube map with this many pixels per side",
    COORDINATES.pmvcResolution.default, COORDINATES.pmvcResolution),
  setting('harmonicResolution', 'integer', "harmonic coordinates' grid cells along the cage box's longest side (0: chosen from the cage)",
    COORDINATES.harmonicResolution.default, { min: 0, max: COORDINATES.harmonicResolution.max }),
  setting('compareCoordinates', 'choice', 'the coordinates of the second view of "compare coordinates"', 'harmonic',
    { choices: COORDINATES.types }),
  setting('autoParts', 'integer', 'K of "auto parts" (docs/method.md section 16)', 6, AUTO_PARTS_RANGE),
  // The threads the views' workers share (docs/threads.md): 'auto' = every core of the page. A setting of the
  // page, not of the solve: it changes no result, so it is neither a solver option nor saved in scenes.
  setting('threads', 'integer', "the threads the views' workers share ('auto': every core of the page)", 'auto',
    { min: 1, max: 1024, also: ['auto'] }),
];

/** Every setting, the solver options first (their own schema, marked `solver`), by name. */
const SETTINGS = new Map([
  ...OPTIONS.map((o) => [o.name, Object.freeze({ ...o, also: Object.freeze([]), solver: true })]),
  ...APP_SETTINGS.map((s) => [s.name, s]),
]);

/** @type {readonly string[]} every setting's name */
export const SETTING_NAMES = Object.freeze([...SETTINGS.keys()]);

/** The schema of a setting (undefined for an unknown name). @returns {SettingSchema|undefined} */
export function settingSchema(name) {
  return SETTINGS.get(name);
}

/** The settings a new app starts with: the method and the panel's solver options, and every app setting. */
export const DEFAULT_SETTINGS = Object.freeze({
  method: DEFAULT_OPTIONS.method,
  ...Object.fromEntries(PANEL_SOLVER_KEYS.map((key) => [key, DEFAULT_OPTIONS[key]])),
  ...Object.fromEntries(APP_SETTINGS.map((s) => [s.name, s.default])),
});

/** Whether `value` is valid for the setting. */
export function settingAllows(schema, value) {
  return schema.also.includes(/** @type {string} */ (value)) || optionAllows(schema, value);
}

/** The message for a bad value, e.g. "setOptions: gizmoMode must be one of 'translate', 'rotate' (got "fly")". */
export function settingError(schema, value, where) {
  return new InputError(`${where}: ${schema.name} must be ${schema.expects} (got ${describeValue(value)})`);
}

/**
 * The one check of a settings object: every key a known setting, every value allowed (undefined values are
 * skipped). Throws an InputError naming the first unknown key or bad value; returns a copy without the
 * skipped keys.
 * @param {unknown} settings
 * @param {string} where prefix of the messages, e.g. 'setOptions'
 * @returns {Record<string, unknown>}
 */
export function checkSettings(settings, where) {
  if (!settings || typeof settings !== 'object' || Array.isArray(settings)) throw new InputError(`${where}: settings must be an object`);
  const out = {};
  for (const [key, value] of Object.entries(settings)) {
    const schema = SETTINGS.get(key);
    if (!schema) throw new InputError(`${where}: unknown setting '${key}' (known: ${SETTING_NAMES.join(', ')})`);
    if (value === undefined) continue;
    if (!settingAllows(schema, value)) throw settingError(schema, value, where);
    out[key] = value;
  }
  return out;
}

/** Throws an InputError unless `vertices` is a cage size "Generate cage" accepts. */
export function checkCageSize(vertices) {
  const schema = SETTINGS.get('cageVertices');
  if (!settingAllows(schema, vertices)) throw new InputError(`generateCage: vertices must be ${schema.expects} (got ${describeValue(vertices)})`);
}

/** Settings that change only what is drawn, how the mouse edits, the next binding or how fast the workers run:
 *  the solvers need not hear of them. */
const VIEW_KEYS = new Set(['showCage', 'showHandles', 'wireframe', 'flatShading', 'gizmoMode', 'tool', 'erase', 'brushRadius', 'cageVertices',
  'basis', 'spectralModes', 'coordinates', 'pmvcResolution', 'harmonicResolution', 'compareCoordinates', 'autoParts', 'threads']);

/** True when a change of these settings concerns the solvers (options, method, caps, request size). */
export function touchesSolver(changed) {
  return Object.keys(changed).some((key) => !VIEW_KEYS.has(key));
}

export class AppSettings extends EventDispatcher {
  #first; // the values the app started with (the defaults and the page's own): what a lesson starts from

  /** @param {object} [initial] values that replace the defaults (checked as update() checks them) */
  constructor(initial = {}) {
    super();
    this.values = { ...DEFAULT_SETTINGS, ...checkSettings(initial, 'settings') };
    this.#first = Object.freeze({ ...this.values });
  }

  /**
   * Merges `partial` and dispatches { type: 'change', changed }. Everything is checked first: an InputError
   * names an unknown setting or a bad value, and nothing changes.
   */
  update(partial) {
    const changed = checkSettings(partial, 'setOptions');
    Object.assign(this.values, changed);
    this.dispatchEvent({ type: 'change', changed });
  }

  /** A copy of every value (what scripts and the panel see). */
  snapshot() {
    return { ...this.values };
  }

  /** The iteration cap of a method (ARAP has its own, see APP_SETTINGS). */
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
   * The settings a lesson's scene sets: every solver setting (the Solver folder's, and any other solver option an
   * earlier scene set) back to what the app started with, then the scene's "solver". A choice made before (the
   * volume constraint unticked, a cap of 200 from another lesson) must not carry into a lesson whose caption
   * describes the solve with its own settings; display and page settings (threads, the tools) stay.
   */
  lessonStart(solver) {
    const start = {};
    for (const { key } of SOLVER_CONTROLS) start[key] = this.#first[key];
    for (const key of EXTRA_SOLVER_KEYS) if (this.values[key] !== undefined) start[key] = this.#first[key] ?? DEFAULT_OPTIONS[key];
    return { ...start, ...AppSettings.fromScene(solver, solver.method ?? this.#first.method) };
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
