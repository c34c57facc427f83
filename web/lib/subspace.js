// @ts-check
// The subspace a session binds (docs/method.md sections 2, 15, 18 and 19): the cage's, with its coordinates and
// that type's resolution, or the mesh's own spectral basis of k modes, which needs no cage. One value for every
// layer that carries it: a scene's "subspace" (scene.js, docs/scene-format.md), Deformer.create's options
// (deformer.js), the worker's load requests (worker/protocol.js) and the app's settings
// (web/app/loading/subspace_choice.js). Its shape is the one those formats already use:
//
//   { basis: 'cage', coordinates?: 'mvc'|'pmvc'|'harmonic', pmvcResolution?, harmonicResolution? }
//   { basis: 'spectral', modes: k }
//
// Its rules are written here once (parseSubspace); each boundary keeps its own wording of a refusal (WORDINGS),
// because its messages are part of its format and tests and users match them.
import { COORDINATES, checkCoordinates } from './coordinates.js';
import { InputError } from './errors.js';
import { describeValue } from './options.js';

/** @typedef {import('./coordinates.js').CoordinatesChoice} CoordinatesChoice */
/** @typedef {import('./coordinates.js').CoordinateType} CoordinateType */
/**
 * The cage's basis: its coordinates (none: mean value) and that type's resolution, if given.
 * @typedef {{ basis: 'cage' } & CoordinatesChoice} CageSubspace
 */
/**
 * The mesh's k = modes lowest Laplace-Beltrami modes (docs/method.md section 15): no cage.
 * @typedef {{ basis: 'spectral', modes: number }} SpectralSubspace
 */
/** @typedef {CageSubspace|SpectralSubspace} Subspace */
/**
 * The fields as callers give them one by one (Deformer.create's options, a scene's "subspace"): basis absent
 * means the cage's.
 * @typedef {{ basis?: 'cage'|'spectral', modes?: number } & CoordinatesChoice} SubspaceFields
 */

/** The subspace bases: the cage's coordinates, or the mesh's low Laplacian modes (no cage). */
export const BASES = ['cage', 'spectral'];

/** Every field a subspace may have. */
export const SUBSPACE_FIELDS = Object.freeze(['basis', 'modes', 'coordinates', 'pmvcResolution', 'harmonicResolution']);

/** The default: the cage's mean value coordinates. */
export const DEFAULT_SUBSPACE = Object.freeze(/** @type {CageSubspace} */ ({ basis: 'cage' }));

// Modes cross into C++ as int.
const MAX_MODES = 2147483647;

/**
 * How one boundary words each refusal of parseSubspace (the rules are the same everywhere).
 * @typedef {object} Wording
 * @property {string} where how checkCoordinates' messages start (coordinates.js)
 * @property {boolean} basisRequired whether a missing basis is refused (the worker's requests) rather than the cage's
 * @property {boolean} refusesUnknown whether a field outside SUBSPACE_FIELDS is refused (false: the caller took
 *   the fields out of a larger options object)
 * @property {string} notObject
 * @property {(key: string) => string} unknownField
 * @property {(got: unknown) => string} basis a basis that is neither 'cage' nor 'spectral'
 * @property {(got: unknown) => string} modes the spectral basis without an integer from 1 to 2^31 - 1 modes
 * @property {string} modesForCage modes given with the cage's basis
 * @property {string} coordinatesForSpectral coordinates given with the spectral basis
 */

/** @param {string} at the subspace's name in the request, e.g. 'loadFiles.subspace' @returns {Wording} */
function requestWording(at) {
  return {
    where: at,
    basisRequired: true,
    refusesUnknown: true,
    notObject: `${at} must be an object`,
    unknownField: (key) => `${at}: unknown field "${key}"`,
    basis: (got) => `${at}.basis must be 'cage', 'spectral' (got ${describeValue(got)})`,
    modes: (got) => `${at}.modes must be an integer from 1 to ${MAX_MODES} (got ${describeValue(got)})`,
    modesForCage: `${at}.modes is for the 'spectral' basis`,
    coordinatesForSpectral: `${at}.coordinates are for the 'cage' basis (the spectral basis has no cage)`,
  };
}

/** Each boundary's wording: a scene file's "subspace", Deformer.create's options, a worker request's field. */
export const WORDINGS = Object.freeze({
  /** @type {Wording} */
  scene: {
    where: 'scene: subspace',
    basisRequired: false,
    refusesUnknown: true,
    notObject: 'scene: "subspace" must be { "basis": "cage" } or { "basis": "spectral", "modes": k }',
    unknownField: (key) => `scene: subspace has unknown field "${key}" (known: ${SUBSPACE_FIELDS.join(', ')})`,
    basis: (got) => `scene: subspace.basis must be "cage" or "spectral" (got ${describeValue(got)})`,
    modes: (got) => `scene: subspace.modes must be an integer >= 1 (got ${describeValue(got)})`,
    modesForCage: 'scene: subspace.modes is for the "spectral" basis',
    coordinatesForSpectral: 'scene: subspace.coordinates are for the "cage" basis (the spectral basis has no cage)',
  },
  /** @type {Wording} */
  deformerCreate: {
    where: 'Deformer.create',
    basisRequired: false,
    refusesUnknown: false,
    notObject: 'Deformer.create: options must be an object',
    unknownField: (key) => `Deformer.create: unknown option "${key}"`,
    basis: (got) => `Deformer.create: basis must be 'cage' or 'spectral' (got ${JSON.stringify(got)})`,
    modes: (got) => `Deformer.create: the spectral basis needs modes, an integer >= 1 (got ${JSON.stringify(got)})`,
    modesForCage: "Deformer.create: modes is for the 'spectral' basis",
    coordinatesForSpectral: "Deformer.create: coordinates are for the 'cage' basis (the spectral basis has no cage)",
  },
  request: requestWording,
});

/**
 * Checks a subspace and returns it as a Subspace holding only the fields given (no defaults filled in: a scene
 * read and written again keeps its text). Absent (undefined or null): the cage's. Refusals are InputErrors
 * (code 'invalid_argument') worded by `wording`, in this order: not an object, an unknown field, the basis, the
 * spectral modes, the coordinates (checkCoordinates), modes with the cage's basis, coordinates with the spectral one.
 * @param {unknown} input
 * @param {Wording} [wording] default: Deformer.create's
 * @returns {Subspace}
 */
export function parseSubspace(input, wording = WORDINGS.deformerCreate) {
  if (input === undefined || input === null) return { ...DEFAULT_SUBSPACE };
  const refuse = (/** @type {string} */ message) => { throw new InputError(message); };
  if (typeof input !== 'object' || Array.isArray(input) || ArrayBuffer.isView(input)) return refuse(wording.notObject);
  const fields = /** @type {Record<string, unknown>} */ (input);
  if (wording.refusesUnknown) for (const key of Object.keys(fields)) if (!SUBSPACE_FIELDS.includes(key)) refuse(wording.unknownField(key));
  const { basis = wording.basisRequired ? undefined : 'cage', modes, coordinates, pmvcResolution, harmonicResolution } = fields;
  if (!BASES.includes(/** @type {string} */ (basis))) refuse(wording.basis(basis));
  if (basis === 'spectral' && !(typeof modes === 'number' && Number.isInteger(modes) && modes >= 1 && modes <= MAX_MODES)) {
    refuse(wording.modes(modes));
  }
  const choice = checkCoordinates(/** @type {CoordinatesChoice} */ ({ coordinates, pmvcResolution, harmonicResolution }), wording.where);
  if (basis === 'spectral') {
    if (Object.keys(choice).length > 0) refuse(wording.coordinatesForSpectral);
    return { basis, modes: /** @type {number} */ (modes) };
  }
  if (modes !== undefined) refuse(wording.modesForCage);
  return { basis: 'cage', ...choice };
}

/**
 * Whether a subspace, or anything that names its basis (a worker Model, a Deformer), is the spectral basis.
 * @param {{ basis?: string }|null|undefined} value
 * @returns {value is SpectralSubspace}
 */
export function isSpectral(value) {
  return value?.basis === 'spectral';
}

/**
 * A subspace with its defaults written out: the cage's coordinates (mean value when none) and that type's
 * resolution (positive mean value: 32; harmonic: 0, chosen from the cage), from the C++ core's table; the
 * spectral basis as it is. Absent: the default subspace.
 * @param {Subspace|null} [subspace]
 * @returns {Subspace}
 */
export function normaliseSubspace(subspace = DEFAULT_SUBSPACE) {
  const s = subspace ?? DEFAULT_SUBSPACE;
  if (s.basis === 'spectral') return { basis: 'spectral', modes: s.modes };
  const coordinates = s.coordinates ?? COORDINATES.types[0];
  if (coordinates === 'pmvc') return { basis: 'cage', coordinates, pmvcResolution: s.pmvcResolution ?? COORDINATES.pmvcResolution.default };
  if (coordinates === 'harmonic') {
    return { basis: 'cage', coordinates, harmonicResolution: s.harmonicResolution ?? COORDINATES.harmonicResolution.default };
  }
  return { basis: 'cage', coordinates };
}

/** The cage coordinates' names in words (the app's menus and labels, the worker's progress). */
export const COORDINATE_WORDS = Object.freeze(/** @type {Record<CoordinateType, string>} */ ({
  mvc: 'mean value coordinates', pmvc: 'positive mean value coordinates', harmonic: 'harmonic coordinates',
}));

/**
 * What a subspace binds, in the words the app and the worker show: 'the spectral basis (40 modes)', or the cage's
 * coordinates: 'mean value coordinates', 'positive mean value coordinates', 'harmonic coordinates'.
 * @param {Subspace|null} [subspace] absent: the default
 * @param {{ modes?: boolean }} [options] modes: false leaves the spectral basis' size out ('the spectral basis':
 *   the progress bar's phase while it binds)
 * @returns {string}
 */
export function describeSubspace(subspace, { modes = true } = {}) {
  const s = normaliseSubspace(subspace);
  if (s.basis === 'spectral') return modes ? `the spectral basis (${s.modes} modes)` : 'the spectral basis';
  return COORDINATE_WORDS[/** @type {CoordinateType} */ (s.coordinates)];
}
