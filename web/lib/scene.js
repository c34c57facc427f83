// @ts-check
// Scene files (docs/scene-format.md): a mesh, an optional cage, handle groups with their motion, and solver
// options, for reproducible experiments and shareable states. Shared by the CLI (`deform`) and the app.
//
// {
//   "mesh": "bar.obj", "cage": "bar_cage.obj",            // paths relative to the scene file; cage optional
//   (or "example": "bunny" instead of "mesh", for a built-in example with its own cage;
//    or "generateCage": { "vertices": 120 } instead of "cage", for a cage made on load)
//   "handles": [
//     { "vertices": [0, 1, 2] },                           // fixed: targets = rest positions
//     { "vertices": [57], "translate": [0, -0.4, 0.2],     // moving: rest positions rotated, then translated
//       "rotate": { "axis": [0, 0, 1], "angle": 0.5, "center": [1, 0, 0] },
//       "along": [0, 0, -1] }                              // optional: held only across the view's lines
//   ],                                                     // ("along" a direction, or "from" an eye)
//   "solver": { "method": "subspace", "jacobian": "fast", "volume": true, "maxIterations": 100,
//               "positionWeight": 1.0, "c1": 1e-4, "c2": 0.5 },
//   "subspace": { "basis": "spectral", "modes": 40 },       // optional; default { "basis": "cage" }
//   (or { "basis": "cage", "coordinates": "pmvc" }: the cage's coordinates, "mvc" (default) | "pmvc" | "harmonic",
//    with "pmvcResolution" or "harmonicResolution" for that type)
//   "volumeParts": { "auto": 6 },                           // optional: the volume kept per part (parts.js)
//   "skeleton": { "joints": [[-2, 0, 0], [0, 0, 0], [2, 0, 0]],  // optional: rigid limbs (skeleton.js): joints
//                 "bones": [[0, 1], [1, 2]] }                  // inside the mesh, bones between them
// }
// The spectral basis needs no cage (and ignores one).
// Rotation: `angle` in radians, or `degrees` instead; `center` defaults to the group's rest centroid; the
// axis need not be unit length. Target of vertex x: center + R (x - center) + translate (the app's
// HandleSet uses the same convention). "solver" takes the options of the Deformer with the same limits
// (options.js, from the C++ table). Every problem is an InputError naming the field.
import { CAGE_LIMITS } from './cage.js';
import { containedPath } from './contained_path.js';
import { InputError } from './errors.js';
import { checkHandleLine } from './handle_lines.js';
import { MAX_MESH_COORDINATE, beyondMeshCoordinates } from './mesh.js';
import { METHODS, OPTION_NAMES, describeValue, optionAllows, optionSchema } from './options.js';
import { checkVolumePartsSpec } from './parts.js';
import { checkSkeleton } from './skeleton.js';
import { WORDINGS, parseSubspace } from './subspace.js';
import { assertAttached } from './typed_arrays.js';

/** @param {unknown} v @returns {v is number} */
function isNumber(v) {
  return typeof v === 'number' && Number.isFinite(v);
}

/** @param {string} message @returns {never} */
function fail(message) {
  throw new InputError(`scene: ${message}`);
}

/** @param {unknown} value @param {string} where @returns {number[]} */
function vector3(value, where) {
  if (!Array.isArray(value) || value.length !== 3 || !value.every(isNumber)) fail(`${where} must be an array of 3 finite numbers`);
  return value.slice();
}

/**
 * @typedef {{ axis: number[], angle: number, center: number[]|null }} Rotation  angle in radians
 * @typedef {{ vertices: number[], translate: number[], rotate: Rotation|null, moving: boolean,
 *             line: import('./handle_lines.js').HandleLine }} SceneHandle  line: null for a point target
 * @typedef {import('./subspace.js').Subspace} SceneSubspace  subspace.js: the value every layer shares
 * @typedef {{ mesh: string|null, cage: string|null, example: string|null,
 *             generateCage: { vertices: number }|null, handles: SceneHandle[], solver: object,
 *             subspace: SceneSubspace, volumeParts: import('./parts.js').VolumePartsSpec|null, view: SceneView|null,
 *             skeleton: import('./skeleton.js').Skeleton|null }} Scene
 * @typedef {{ compare: string[]|null, direction: number[]|null, paused: boolean }} SceneView  what the app shows
 */

/**
 * Parses and validates a scene (JSON text or an already parsed object). Errors name the field.
 * Vertex indices are checked against the mesh later, by handleTargets.
 * @param {string|object} input
 * @param {{ modelOptional?: boolean }} [options] modelOptional: a scene without "mesh" and "example" is
 *   accepted (mesh, cage and example are then null): the app applies such a scene to the model it shows
 * @returns {Scene}
 */
export function parseScene(input, { modelOptional = false } = {}) {
  /** @type {any} what the file says, checked field by field below */
  let scene = input;
  if (typeof input === 'string') {
    try {
      scene = JSON.parse(input);
    } catch (error) {
      fail(`not valid JSON (${/** @type {Error} */ (error).message})`);
    }
  }
  if (!scene || typeof scene !== 'object' || Array.isArray(scene)) fail('the top level must be an object');
  const known = new Set(['mesh', 'cage', 'example', 'generateCage', 'handles', 'solver', 'subspace', 'volumeParts',
    'skeleton', 'view', 'description', 'name']);
  for (const key of Object.keys(scene)) if (!known.has(key)) fail(`unknown field "${key}" (known: ${[...known].join(', ')})`);
  const model = parseModelSource(scene, modelOptional);
  const handles = parseSceneHandles(scene.handles);
  const solver = scene.solver ?? {};
  if (typeof solver !== 'object' || Array.isArray(solver)) fail('"solver" must be an object');
  for (const [key, value] of Object.entries(solver)) {
    const option = optionSchema(key);
    if (!option) fail(`solver has unknown field "${key}" (known: ${OPTION_NAMES.join(', ')})`);
    if (!optionAllows(option, value)) fail(`solver.${key} must be ${option.expects} (got ${describeValue(value)})`);
  }
  const subspace = parseSubspace(scene.subspace, WORDINGS.scene);
  const volumeParts = scene.volumeParts === undefined || scene.volumeParts === null ? null
    : checkVolumePartsSpec(scene.volumeParts, 'scene: "volumeParts"');
  const skeleton = checkSkeleton(scene.skeleton, 'scene: "skeleton"');
  return { ...model, handles, solver: { ...solver }, subspace, volumeParts, skeleton, view: parseView(scene.view) };
}

// "view": what the app shows (the command-line tool ignores it): the methods side by side, the direction the
// camera looks along, and whether the solver starts paused (step-through). All optional.
/** @param {any} value @returns {SceneView|null} */
function parseView(value) {
  if (value === undefined || value === null) return null;
  if (typeof value !== 'object' || Array.isArray(value)) fail('"view" must be { "compare"?: [methods], "direction"?: [x, y, z], "paused"?: boolean }');
  for (const key of Object.keys(value)) {
    if (!['compare', 'direction', 'paused'].includes(key)) fail(`view has unknown field "${key}" (known: compare, direction, paused)`);
  }
  const { compare = null, direction = null, paused = false } = value;
  if (compare !== null) {
    const ok = Array.isArray(compare) && compare.length > 0 && compare.every((m) => METHODS.includes(m)) && new Set(compare).size === compare.length;
    if (!ok) fail(`view.compare must be a list of distinct methods (${METHODS.join(', ')}) (got ${describeValue(compare)})`);
  }
  if (direction !== null && !(Array.isArray(direction) && direction.length === 3 && direction.every(Number.isFinite) && direction.some((x) => x !== 0))) {
    fail(`view.direction must be [x, y, z], finite and not zero (got ${describeValue(direction)})`);
  }
  if (typeof paused !== 'boolean') fail(`view.paused must be true or false (got ${describeValue(paused)})`);
  return { compare: compare && [...compare], direction: direction && [...direction], paused };
}

/**
 * Validates a scene's "handles" list alone (also what the app keeps across a new cage for the same mesh).
 * @param {unknown} list
 * @returns {SceneHandle[]}
 */
export function parseSceneHandles(list) {
  if (!Array.isArray(list)) fail('"handles" must be an array of { vertices, translate?, rotate? }');
  checkHandleCount(list);
  const seen = new Map();
  return Array.from(list, (h, i) => {
    const where = `handles[${i}]`;
    if (!h || typeof h !== 'object' || Array.isArray(h)) fail(`${where} must be an object`);
    for (const key of Object.keys(h)) {
      if (!['vertices', 'translate', 'rotate', 'along', 'from'].includes(key)) fail(`${where} has unknown field "${key}"`);
    }
    if (!Array.isArray(h.vertices) || h.vertices.length === 0) fail(`${where}.vertices must be a non-empty array of vertex indices`);
    for (let k = 0; k < h.vertices.length; ++k) {
      const v = h.vertices[k];
      if (!Number.isInteger(v) || v < 0) fail(`${where}.vertices[${k}] = ${JSON.stringify(v) ?? 'nothing'} is not a vertex index`);
      if (seen.get(v) === where) fail(`${where}.vertices lists vertex ${v} more than once`);
      if (seen.has(v)) fail(`vertex ${v} is in ${seen.get(v)} and ${where}`);
      seen.set(v, where);
    }
    const translate = h.translate === undefined ? [0, 0, 0] : vector3(h.translate, `${where}.translate`);
    let rotate = null;
    if (h.rotate !== undefined) {
      const r = h.rotate;
      if (!r || typeof r !== 'object') fail(`${where}.rotate must be { axis, angle | degrees, center? }`);
      for (const key of Object.keys(r)) {
        if (!['axis', 'angle', 'degrees', 'center'].includes(key)) fail(`${where}.rotate has unknown field "${key}"`);
      }
      const axis = vector3(r.axis, `${where}.rotate.axis`);
      const unit = unitAxis(axis);
      if (!unit) fail(`${where}.rotate.axis must not be zero`);
      if ((r.angle === undefined) === (r.degrees === undefined)) fail(`${where}.rotate needs exactly one of "angle" (radians) or "degrees"`);
      const angle = r.angle !== undefined ? r.angle : (r.degrees * Math.PI) / 180;
      if (!isNumber(angle)) fail(`${where}.rotate.${r.angle !== undefined ? 'angle' : 'degrees'} must be a finite number`);
      const center = r.center === undefined || r.center === null ? null : vector3(r.center, `${where}.rotate.center`);
      rotate = { axis: unit, angle, center };
    }
    // Moving = has a motion, even a zero one (a saved scene keeps an undisplaced moving group moving).
    const moving = h.translate !== undefined || h.rotate !== undefined;
    return { vertices: h.vertices.slice(), translate, rotate, moving, line: sceneHandleLine(h, where) };
  });
}

// A handle's "along" or "from" (handle_lines.js): held only across the lines of a view, its depth free.
/** @param {any} h @param {string} where @returns {import('./handle_lines.js').HandleLine} */
function sceneHandleLine(h, where) {
  if (h.along !== undefined && h.from !== undefined) fail(`${where} needs at most one of "along" or "from"`);
  if (h.along === undefined && h.from === undefined) return null;
  try {
    return checkHandleLine(h.along !== undefined ? { along: h.along } : { from: h.from }, where);
  } catch (error) {
    return fail(/** @type {Error} */ (error).message);
  }
}

/**
 * A rotation axis as a unit vector, or null for a zero one. Scaled by its largest component first: the length
 * of an axis near 1e308 overflows to Infinity, and dividing by it would give a zero "unit" axis.
 * @param {number[]} axis 3 finite numbers
 * @returns {number[]|null}
 */
export function unitAxis(axis) {
  const scale = Math.max(...axis.map(Math.abs));
  if (!(scale > 0)) return null;
  const scaled = axis.map((a) => a / scale);
  const length = Math.hypot(...scaled);
  return scaled.map((a) => a / length);
}

/**
 * The most handle vertices a scene may list: 2^24 - 1, more than the vertices of any mesh that fits the
 * solver's 4 GB wasm heap (and the most entries a JS Map holds). Counted before any index is looked at, so
 * 20 million indices are refused at once rather than after seconds and gigabytes.
 */
export const MAX_HANDLE_VERTICES = 2 ** 24 - 1;

/** @param {any[]} list */
function checkHandleCount(list) {
  let count = 0;
  for (let i = 0; i < list.length; ++i) count += Array.isArray(list[i]?.vertices) ? list[i].vertices.length : 0;
  if (count > MAX_HANDLE_VERTICES) fail(`"handles" list ${count} vertices: more than the ${MAX_HANDLE_VERTICES} any mesh can have`);
}

// Where the model comes from: a mesh file or a built-in example; a cage file, a generated cage, or none.
/**
 * @param {any} scene @param {boolean} modelOptional
 * @returns {{ mesh: string|null, cage: string|null, example: string|null, generateCage: { vertices: number }|null }}
 */
function parseModelSource(scene, modelOptional) {
  const given = (/** @type {string} */ key) => scene[key] !== undefined && scene[key] !== null;
  const none = !given('example') && !given('mesh');
  if (none && modelOptional && (given('cage') || given('generateCage'))) fail('"cage" and "generateCage" need a "mesh"');
  if (given('example') === given('mesh') && !(none && modelOptional)) {
    fail('give exactly one of "mesh" (a file path) or "example" (a built-in name)');
  }
  if (given('mesh') && (typeof scene.mesh !== 'string' || scene.mesh.length === 0)) fail('"mesh" must be a file path (string)');
  if (given('example') && (typeof scene.example !== 'string' || scene.example.length === 0)) fail('"example" must be a built-in example name');
  if (given('cage') && (typeof scene.cage !== 'string' || scene.cage.length === 0)) fail('"cage" must be a file path (string) or null');
  // Models only in the scene's folder and below: a scene from a stranger must not make a tool read its own files.
  for (const key of ['mesh', 'cage']) if (given(key)) containedPath(scene[key], `scene: "${key}"`);
  if (given('cage') && given('generateCage')) fail('give either "cage" or "generateCage", not both');
  if (given('example') && given('cage')) fail('an "example" brings its own cage: drop "cage"');
  const { min, max } = CAGE_LIMITS.vertices;
  // null is not a cage request (unlike "cage": null, documented as no cage): it was silently taken as none.
  if (scene.generateCage === null) fail(`"generateCage" must be { "vertices": K } with an integer K from ${min} to ${max} (got null; leave "generateCage" out for no cage)`);
  let generateCage = null;
  if (given('generateCage')) {
    // The generator's own limits, checked here so that every tool refuses the same scenes before loading anything.
    // Only "vertices": the app's loading and its saved scenes carry nothing else, so an "offset" or "resolution"
    // here would be dropped silently; a cage made with them is a file ("deform.mjs cage") named by "cage".
    const vertices = scene.generateCage?.vertices;
    const fields = typeof scene.generateCage === 'object' && !Array.isArray(scene.generateCage) ? Object.keys(scene.generateCage) : [];
    const unknown = fields.find((key) => key !== 'vertices');
    if (unknown !== undefined) {
      fail(`generateCage has unknown field "${unknown}" (known: vertices; for another offset or resolution make the cage ` +
        'with "deform.mjs cage --offset/--resolution" and name its file in "cage")');
    }
    if (!Number.isInteger(vertices) || vertices < min || vertices > max) {
      fail(`"generateCage" must be { "vertices": K } with an integer K from ${min} to ${max} (got ${describeValue(scene.generateCage)})`);
    }
    generateCage = { vertices };
  }
  return { mesh: scene.mesh ?? null, cage: scene.cage ?? null, example: scene.example ?? null, generateCage };
}

/**
 * The Deformer's handle groups and targets for a scene's handles on a mesh.
 * @param {Float64Array} restPositions 3 per vertex
 * @param {SceneHandle[]} handles from parseScene
 * @returns {{ groups: number[][], targets: Float64Array, lines: import('./handle_lines.js').HandleLine[] }}
 *   targets: 3 per handle vertex, groups in order; lines: one per group (null: a point target)
 */
export function handleTargets(restPositions, handles) {
  assertAttached(restPositions, 'handleTargets: restPositions');
  const n = restPositions.length / 3;
  /** @type {number[][]} */
  const groups = [];
  const count = handles.reduce((sum, h) => sum + h.vertices.length, 0);
  const targets = new Float64Array(3 * count);
  let row = 0;
  handles.forEach((h, i) => {
    for (const v of h.vertices) {
      if (v >= n) fail(`handles[${i}] uses vertex ${v}, but the mesh has ${n} vertices`);
    }
    groups.push(h.vertices.slice());
    const R = h.rotate ? rotationMatrix(h.rotate.axis, h.rotate.angle) : null;
    const center = h.rotate ? (h.rotate.center ?? centroid(restPositions, h.vertices)) : null;
    for (const v of h.vertices) {
      let p = [restPositions[3 * v], restPositions[3 * v + 1], restPositions[3 * v + 2]];
      if (R && center) {
        const d = [p[0] - center[0], p[1] - center[1], p[2] - center[2]];
        p = [0, 1, 2].map((a) => center[a] + R[a][0] * d[0] + R[a][1] * d[1] + R[a][2] * d[2]);
      }
      for (let a = 0; a < 3; ++a) targets[3 * row + a] = p[a] + h.translate[a];
      checkTarget(targets.subarray(3 * row, 3 * row + 3), i, v);
      ++row;
    }
  });
  return { groups, targets, lines: handles.map((h) => h.line ?? null) };
}

/**
 * A handle vertex's target within the coordinates a mesh may have (MAX_MESH_COORDINATE): beyond them the
 * solve's energies overflow and it ends in a numerical failure with an infinite handle error, so the group is
 * refused up front. Finite inputs can overflow as well (a rotation about a center near 1e308).
 * @param {Float64Array} target 3 numbers @param {number} group @param {number} vertex
 */
function checkTarget(target, group, vertex) {
  if (!target.every(Number.isFinite)) fail(`handles[${group}] moves vertex ${vertex} to a non-finite position (its translate or rotate is too large)`);
  const largest = Math.max(...target.map(Math.abs));
  if (largest > MAX_MESH_COORDINATE) {
    fail(`handles[${group}] moves vertex ${vertex} to ${beyondMeshCoordinates(largest)}: use a smaller translate, or rescale the model`);
  }
}

/** @param {Float64Array} positions @param {number[]} vertices @returns {number[]} */
function centroid(positions, vertices) {
  const c = [0, 0, 0];
  for (const v of vertices) for (let a = 0; a < 3; ++a) c[a] += positions[3 * v + a];
  return c.map((x) => x / vertices.length);
}

// Rodrigues' formula for a unit axis.
/** @param {number[]} axis @param {number} angle @returns {number[][]} */
function rotationMatrix(axis, angle) {
  const [x, y, z] = axis;
  const c = Math.cos(angle), s = Math.sin(angle), t = 1 - c;
  return [
    [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
    [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
    [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
  ];
}
