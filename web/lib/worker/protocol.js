// @ts-check
// The messages between the page (solver_client.js) and the solver worker (solver_worker.js). Every
// request is { id, type, ...payload } and is answered, in order, by one Reply with the same id; the worker
// also posts Progress messages while it binds W or generates a cage. Errors cross as ErrorData and are
// rebuilt into the library's typed errors on the page (errors.js), so `error instanceof CancelledError`
// and `error.code` work across the boundary. Arrays travel as transferable buffers (no copy). The worker checks
// every request against this description before acting (checkRequest), so a malformed message gets an
// InputError naming the field, never an 'internal' failure half-way through.

import { CAGE_LIMITS } from '../cage.js';
import { InputError } from '../errors.js';
import { isModelName } from '../formats.js';
import { describeValue } from '../options.js';
import { WORDINGS, parseSubspace } from '../subspace.js';

/** @typedef {import('../mesh.js').MeshData} MeshData */
/** @typedef {import('../options.js').SolverOptions} SolverOptions */
/** @typedef {import('../deformer.js').StepResult} StepResult */
/** @typedef {import('../errors.js').ErrorData} ErrorData */

// ---------------------------------------------------------------------------------------------------
// Requests (page -> worker): the payload of each type

/**
 * The subspace of the session (docs/library.md; subspace.js, the value scenes and Deformer.create share): the
 * cage's (the default; its coordinates 'mvc', 'pmvc' or 'harmonic' with their resolution, coordinates.js) or the
 * mesh's spectral basis, which needs no cage.
 * @typedef {import('../subspace.js').Subspace} Subspace
 */
/**
 * Loads the module with this many threads (load.js: the threaded build on a cross-origin isolated page,
 * whose pool holds pageCores(); docs/threads.md). Optional and only meaningful first: any other first
 * request loads the module with every core, and a later init only reports. SolverClient sends it as its
 * first request with the worker's share of the page's cores. Reply: SolverInfo.
 * @typedef {{ type: 'init', threads?: number }} InitRequest
 */
/**
 * Moves the worker's thread count within the pool started at load (SolverClient rebalances the page's
 * cores this way when a worker starts or stops); 0: every thread of the pool. Reply: SolverInfo.
 * @typedef {{ type: 'setThreads', threads: number }} SetThreadsRequest
 */
/**
 * A built-in example; no name: the default one. 'bunny' is the npm mesh with a cage generated in the
 * worker (examples.js). generateCage: a generated cage instead of the example's own (a scene's "example" with
 * "generateCage"), made in the same request so that a failure leaves the previous model bound. Reply: Model.
 * @typedef {{ type: 'loadExample', name?: string, generateCage?: { vertices: number }, subspace?: Subspace }} LoadExampleRequest
 */
/**
 * Model files (any format readModel reads: OBJ, OFF, PLY, STL, .glb, .gltf): the one with more vertices is the
 * mesh, the other the cage; any other files are what a .gltf refers to by name (its .bin, its textures). A lone
 * mesh needs generateCage or the spectral subspace, else the reply is an InputError with code 'no_cage' (or a
 * MeshError with code 'invalid_mesh' when the mesh could not get a cage anyway). Every load resolves its cage so
 * (worker/cage_resolution.js): the one given, else none with the spectral subspace, else a generated one if asked,
 * else that refusal; loadExample's generateCage replaces the example's own cage. Reply: Model.
 * @typedef {{ type: 'loadFiles', files: { name: string, bytes: Uint8Array }[], generateCage?: { vertices: number },
 *             subspace?: Subspace }} LoadFilesRequest
 */
/**
 * Meshes already parsed (compare views, scenes, "Generate cage" for the current mesh when cage is absent).
 * Without cage, generateCage and the spectral subspace the reply is loadFiles' (code 'no_cage'). A glTF
 * model also sends its file (gltf: the bytes, name and the files it refers to), so that its export keeps the
 * file's layout and materials. Reply: Model.
 * @typedef {{ type: 'loadMeshes', name: string, description?: string, mesh: MeshData, cage?: MeshData,
 *             generateCage?: { vertices: number }, subspace?: Subspace,
 *             gltf?: { name: string, bytes: Uint8Array, resources?: Record<string, Uint8Array> } }} LoadMeshesRequest
 */
/**
 * Volume kept per part: a description of parts.js (vertex lists, { triangles }, { auto: K }) or one part
 * index per triangle; null: the global volume. Reply: { parts: Int32Array (per triangle; empty when global),
 * restPartVolumes: Float64Array }.
 * @typedef {{ type: 'setVolumeParts', parts: unknown }} SetVolumePartsRequest
 */
/**
 * The skeleton (skeleton.js: { joints, bones }; null: none). Reply: { skeleton: SkeletonReport|null }; every
 * Frame then carries `skeleton` too, so a page can draw the bones where the mesh took them.
 * @typedef {{ type: 'setSkeleton', skeleton: unknown }} SetSkeletonRequest
 */
/** @typedef {{ type: 'setOptions', options: SolverOptions }} SetOptionsRequest  Reply: undefined */
/** @typedef {{ type: 'setHandles', groups: number[][] }} SetHandlesRequest  Reply: undefined */
/**
 * Targets, and optionally the groups' handle lines (handle_lines.js: per group { along }, { from } or null; null:
 * point targets; absent: unchanged). Reply: undefined
 * @typedef {{ type: 'setTargets', targets: Float64Array, lines?: unknown }} SetTargetsRequest
 */
/** @typedef {{ type: 'reset' }} ResetRequest  Back to the rest pose. Reply: Frame */
/** @typedef {{ type: 'step', iterations: number }} StepRequest  Up to that many iterations. Reply: Frame */
/**
 * ARAP step-through: one half of the next local-global iteration (Deformer.arapHalfStep). Reply: Frame with
 * `half` (ArapHalfStep of deformer.js).
 * @typedef {{ type: 'arapHalfStep', phase: 'local'|'global' }} ArapHalfStepRequest
 */
/**
 * Column `column` of the subspace basis (the weight of one cage vertex, or one spectral column, at every mesh
 * vertex): what the page colours the mesh by to show what it controls. Reply: BasisColumn.
 * @typedef {{ type: 'basisColumn', column: number }} BasisColumnRequest
 */
/**
 * Makes the reduced integration's fit now (Deformer.prepareReduced), so the first reduced step of a drag does not
 * wait for it. Reply: ReducedIntegrationInfo (deformer.js).
 * @typedef {{ type: 'prepareReduced' }} PrepareReducedRequest
 */
/**
 * Makes the factor preconditioner's pose-free parts now (Deformer.prepareFactor), so the first settle does not wait
 * for them. Reply: undefined.
 * @typedef {{ type: 'prepareFactor' }} PrepareFactorRequest
 */
/**
 * OBJ text of the deformed mesh or cage, or of the rest cage. Reply: string.
 * @typedef {{ type: 'exportObj', what: 'mesh'|'cage'|'restCage' }} ExportObjRequest
 */
/**
 * The deformed mesh as binary glTF in the model's own vertex layout: a glTF model keeps its materials,
 * textures, UVs and nodes (gltf.js). Reply: Uint8Array.
 * @typedef {{ type: 'exportGlb' }} ExportGlbRequest
 */
/**
 * Warnings about the current result (Deformer.resultWarnings: folded_triangles, cage_self_intersecting).
 * Reply: Finding[].
 * @typedef {{ type: 'resultWarnings' }} ResultWarningsRequest
 */
/**
 * @typedef {InitRequest|SetThreadsRequest|LoadExampleRequest|LoadFilesRequest|LoadMeshesRequest|
 *   SetOptionsRequest|SetHandlesRequest|SetTargetsRequest|ResetRequest|StepRequest|ArapHalfStepRequest|ExportObjRequest|
 *   ExportGlbRequest|ResultWarningsRequest|
 *   SetVolumePartsRequest|SetSkeletonRequest|BasisColumnRequest|PrepareReducedRequest|PrepareFactorRequest} Request
 */

// ---------------------------------------------------------------------------------------------------
// Results

/**
 * Which wasm build the worker runs, with how many threads (docs/threads.md).
 * @typedef {object} SolverInfo
 * @property {'threads'|'single'} build
 * @property {number} threads the count in effect (1 in the single-threaded build)
 * @property {string} [buildNote] why a page got the single-threaded build (not isolated, or the threaded
 *   one failed to load)
 */

/**
 * The model the worker bound.
 * @typedef {object} Model
 * @property {string} name
 * @property {string} description
 * @property {MeshData} mesh copies: the worker keeps its own
 * @property {MeshData} cage empty with the spectral basis and no cage
 * @property {'cage'|'spectral'} basis
 * @property {number} basisSize the basis' columns (cage vertices, or modes + 4)
 * @property {import('../deformer.js').CoordinatesReport|null} coordinates what binding the cage's W found (its
 *   type, smallest weight, rays or grid); null with the spectral basis
 * @property {number} [modesAsked] the spectral basis: the modes asked for (basisSize - 4 is less when some
 *   eigenvectors were in the span of the ones before them and left out)
 * @property {number} restVolume
 * @property {number} bindMs
 * @property {number} vertexCount
 * @property {boolean} float32 the basis is stored in single precision (chosen above 128 MB in double)
 * @property {string[]} exampleNames every built-in example, the default first
 * @property {boolean} canGenerateCage
 * @property {SolverInfo} solver the build and thread count that bound it
 * @property {import('../deformer.js').CageQuality|null} cageQuality how well the cage controls the mesh (its
 *   warnings: what the page shows about a poor cage); null with the spectral basis
 * @property {{ vertices: number, volumeRatio: number, minClearance: number, attempts: number, ms: number }} [generatedCage]
 * @property {{ axis: number, fixedBelow: number, movingAbove: number }} [defaultHandles] an example's
 *   suggested handles: fractions of the extent along axis
 * @property {{ direction: number[] }} [defaultView] an example's viewing direction (Spot faces -z)
 * @property {import('../errors.js').Finding[]} notes what loading did to the model, from its check: welded
 *   seams, holes capped, components each keeping its volume, vertices carried along (notes and warnings)
 * @property {import('../mesh.js').LayoutStats & { solverOfFile: Int32Array }} layout the vertex layout's
 *   counts and map (Deformer.layout())
 * @property {number} volumePartCount the volume constraints: 1 for one global volume, else the parts' count
 * @property {{ instances: import('../gltf.js').GltfInstance[] }} [gltf] a glTF model's primitive instances
 *   and their file-vertex ranges (what the page maps three's GLTFLoader meshes to)
 */

/**
 * One column of the subspace basis at every mesh vertex (a transferable Float32Array) and its range.
 * @typedef {{ column: number, values: Float32Array, min: number, max: number }} BasisColumn
 */

/**
 * One solver result and what the page draws: positions/cage are the solver's (exports, tests); render
 * holds Float32 positions and vertex normals computed in the worker (Deformer.renderBuffers, in wasm), so the page
 * only swaps its attribute arrays.
 * @typedef {object} Frame
 * @property {StepResult} result
 * @property {Float64Array} positions
 * @property {Float64Array} cage
 * @property {{ positions: Float32Array, normals: Float32Array, cage: Float32Array }} render
 * @property {import('../skeleton.js').SkeletonReport} [skeleton] with a skeleton: where its joints are and how
 *   well each bone is kept
 */

// ---------------------------------------------------------------------------------------------------
// Replies and progress (worker -> page)

/** @typedef {{ id: number, ok: true, result: any }} OkReply */
/** @typedef {{ id: number, ok: false, error: ErrorData }} ErrorReply */
/** @typedef {OkReply|ErrorReply} Reply */
/**
 * Unsolicited, while a load runs: phase says what (e.g. 'computing weights', 'generating the cage').
 * @typedef {{ type: 'progress', fraction: number, phase: string }} Progress
 */

/** The progress message's type (a request never has it). */
export const PROGRESS = 'progress';

// ---------------------------------------------------------------------------------------------------
// The check of a request, before the worker acts on it

const MAX_INT = 2147483647;
/** @type {(message: string) => never} */
const fail = (message) => { throw new InputError(message); };
/** @type {(v: unknown) => v is Record<string, any>} */
const isObject = (v) => !!v && typeof v === 'object' && !Array.isArray(v) && !ArrayBuffer.isView(v);

// Field checks: each throws an InputError naming the field (`at`). The value is any: what a page posted.
/** @typedef {(v: any, at: string) => void} FieldCheck */
/** @type {(min: number, max: number) => FieldCheck} */
const integer = (min, max) => (v, at) => {
  if (!(Number.isInteger(v) && v >= min && v <= max)) fail(`${at} must be an integer from ${min} to ${max} (got ${describeValue(v)})`);
};
/** @type {FieldCheck} */
const string = (v, at) => { if (typeof v !== 'string') fail(`${at} must be a string`); };
/** @type {FieldCheck} */
const object = (v, at) => { if (!isObject(v)) fail(`${at} must be an object`); };
/** @type {FieldCheck} */
const array = (v, at) => { if (!Array.isArray(v)) fail(`${at} must be an array`); };
/** @type {(...choices: string[]) => FieldCheck} */
const oneOf = (...choices) => (v, at) => {
  if (!choices.includes(v)) fail(`${at} must be ${choices.map((c) => `'${c}'`).join(', ')} (got ${describeValue(v)})`);
};
/** @type {FieldCheck} */
const float64 = (v, at) => { if (!(v instanceof Float64Array)) fail(`${at} must be a Float64Array`); };
/** @type {FieldCheck} */
const meshData = (v, at) => {
  object(v, at);
  float64(v.positions, `${at}.positions`);
  if (!(v.indices instanceof Uint32Array)) fail(`${at}.indices must be a Uint32Array`);
};
/** @type {FieldCheck} */
const subspace = (v, at) => { parseSubspace(v, WORDINGS.request(at)); };
/** @type {FieldCheck} */
const generateCage = (v, at) => {
  object(v, at);
  integer(CAGE_LIMITS.vertices.min, CAGE_LIMITS.vertices.max)(v.vertices, `${at}.vertices`);
};
// One model file, or a model and its cage, and at most 64 files a .gltf refers to (its .bin, its textures).
/** @type {FieldCheck} */
const files = (v, at) => {
  const models = Array.isArray(v) ? v.filter((/** @type {any} */ f) => isModelName(f?.name)).length : 0;
  if (!Array.isArray(v) || models < 1 || models > 2 || v.length > models + 64) {
    const got = !Array.isArray(v) ? describeValue(v) : models === v.length ? `${models}` : `${models} model files of ${v.length}`;
    fail(`${at} must be one mesh file, or a mesh and its cage (got ${got}), with at most 64 files a .gltf refers to`);
  }
  for (let i = 0; i < v.length; ++i) {
    object(v[i], `${at}[${i}]`);
    string(v[i].name, `${at}[${i}].name`);
    if (!(v[i].bytes instanceof Uint8Array)) fail(`${at}[${i}].bytes must be a Uint8Array`);
  }
};
// A glTF model's file for loadMeshes: its name, bytes and the files it refers to.
/** @type {FieldCheck} */
const gltfFile = (v, at) => {
  object(v, at);
  string(v.name, `${at}.name`);
  if (!(v.bytes instanceof Uint8Array)) fail(`${at}.bytes must be a Uint8Array`);
  if (v.resources !== undefined && v.resources !== null) {
    object(v.resources, `${at}.resources`);
    for (const [name, bytes] of Object.entries(v.resources)) if (!(bytes instanceof Uint8Array)) fail(`${at}.resources["${name}"] must be a Uint8Array`);
  }
};
/** @type {FieldCheck} */
const anything = () => {};

/**
 * Every request type and its payload's fields: [check, required]. A payload with another field, a missing
 * required one or a bad value is refused before the worker acts; so is an unknown type (a Map: a type is
 * data, and 'constructor' or 'toString' are no request).
 * @type {Map<string, Record<string, [FieldCheck, boolean]>>}
 */
const REQUESTS = new Map(/** @type {[string, Record<string, [FieldCheck, boolean]>][]} */ ([
  ['init', { threads: [integer(0, 1024), false] }],
  ['setThreads', { threads: [integer(0, 1024), true] }],
  ['loadExample', { name: [string, false], generateCage: [generateCage, false], subspace: [subspace, false] }],
  ['loadFiles', { files: [files, true], generateCage: [generateCage, false], subspace: [subspace, false] }],
  ['loadMeshes', { name: [string, true], description: [string, false], mesh: [meshData, true], cage: [meshData, false],
    generateCage: [generateCage, false], subspace: [subspace, false], gltf: [gltfFile, false] }],
  ['setVolumeParts', { parts: [anything, false] }], // parts.js checks the description (null: the global volume)
  ['setSkeleton', { skeleton: [anything, false] }], // Deformer.setSkeleton checks it (null: none)
  ['setOptions', { options: [object, true] }],
  ['setHandles', { groups: [array, true] }],
  ['setTargets', { targets: [float64, true], lines: [anything, false] }], // Deformer.setHandleLines checks the lines
  ['reset', {}],
  ['step', { iterations: [integer(0, MAX_INT), true] }],
  ['arapHalfStep', { phase: [oneOf('local', 'global'), true] }],
  ['basisColumn', { column: [integer(0, MAX_INT), true] }],
  ['prepareReduced', {}],
  ['prepareFactor', {}],
  ['exportObj', { what: [oneOf('mesh', 'cage', 'restCage'), true] }],
  ['exportGlb', {}],
  ['resultWarnings', {}],
]));

/** Every request type. */
export const REQUEST_TYPES = Object.freeze([...REQUESTS.keys()]);

/** The payload fields of a request type (an empty list for an unknown one). @param {string} type @returns {string[]} */
export function requestFields(type) {
  return Object.keys(REQUESTS.get(type) ?? {});
}

/**
 * Checks a message the worker received: { id, type, ...payload } as this file describes it (fields that are
 * undefined or null count as absent). Throws an InputError naming the problem.
 * @param {unknown} message
 * @returns {{ id: unknown, type: string, payload: Record<string, unknown> }}
 */
export function checkRequest(message) {
  if (!isObject(message)) fail('a request must be an object { id, type, ...payload }');
  const { id, type, ...payload } = message;
  const fields = typeof type === 'string' ? REQUESTS.get(type) : undefined;
  if (!fields) fail(`unknown request ${describeValue(type)} (known: ${REQUEST_TYPES.join(', ')})`);
  for (const [key, value] of Object.entries(payload)) {
    if (!Object.hasOwn(fields, key)) fail(`${type}: unknown field "${key}"`);
    if (value !== undefined && value !== null) fields[key][0](value, `${type}.${key}`);
  }
  for (const [key, [, required]] of Object.entries(fields)) {
    if (required && (payload[key] === undefined || payload[key] === null)) fail(`${type}: "${key}" is missing`);
  }
  return { id, type, payload };
}
