// @ts-check
// The cage coordinates a cage basis binds (cpp/core/basis/cage_coordinates.h, docs/method.md sections 2,
// 18 and 19): 'mvc' (mean value coordinates, the default), 'pmvc' (positive mean value coordinates) and
// 'harmonic' (harmonic coordinates), with their resolutions. One check for every caller: computeWeights,
// Deformer.create, scenes, the worker and the CLI; which basis they belong to is subspace.js'.
import { COORDINATES } from '../../build/wasm/solver_schema.js';
import { InputError } from './errors.js';

/** The types and the limits of their resolutions, from the C++ core (the first type is the default). */
export { COORDINATES };

/** @typedef {import('../../build/wasm/solver_schema.js').CoordinateType} CoordinateType */
/**
 * Which coordinates to bind: the type and, for it alone, its resolution.
 *   pmvcResolution: the hidden parts' sampling, cells of at most 4 pi / (6 r^2) steradians (a cube map with r^2
 *     pixels per face), from COORDINATES.pmvcResolution.min to max, default 32.
 *   harmonicResolution: grid cells along the longest side of the cage's bounding box, from
 *     COORDINATES.harmonicResolution.min to max; 0 (the default): chosen from the cage (about 20000 grid nodes
 *     inside it).
 * @typedef {{ coordinates?: CoordinateType, pmvcResolution?: number, harmonicResolution?: number }} CoordinatesChoice
 */

/**
 * What binding the cage's W found (Deformer.coordinatesReport(), a worker Model's `coordinates`): the fields of
 * WeightsResult (weights.js) without the matrix itself: the type, the smallest weight and where, and per type the
 * rays cast (pmvc) or the grid and its factor (harmonic).
 * @typedef {Omit<import('./weights.js').WeightsResult, 'weights'|'rows'|'cols'|'bytes'|'evaluations'|'ms'>} CoordinatesReport
 */

const names = COORDINATES.types.map((t) => `'${t}'`).join(', ');

/**
 * Checks a CoordinatesChoice (each field optional) and returns the fields given, for the wasm module. A
 * resolution belongs to its own type: pmvcResolution with coordinates other than 'pmvc' is refused, and so on.
 * @param {CoordinatesChoice} choice
 * @param {string} where how error messages start (e.g. 'Deformer.create')
 * @param {(message: string) => never} [fail] how to refuse (default: throw an InputError)
 * @returns {CoordinatesChoice}
 */
export function checkCoordinates(choice, where, fail = (message) => { throw new InputError(message); }) {
  const { coordinates, pmvcResolution, harmonicResolution } = choice;
  /** @type {Record<string, unknown>} */
  const out = {};
  if (coordinates !== undefined) {
    if (!COORDINATES.types.includes(coordinates)) fail(`${where}: coordinates must be one of ${names} (got ${JSON.stringify(coordinates)})`);
    out.coordinates = coordinates;
  }
  const type = coordinates ?? COORDINATES.types[0];
  /**
   * @param {number|undefined} value @param {'pmvcResolution'|'harmonicResolution'} name @param {CoordinateType} own
   * @param {{ min: number, max: number }} range @param {boolean} zeroAllowed
   */
  const resolution = (value, name, own, { min, max }, zeroAllowed) => {
    if (value === undefined) return;
    if (type !== own) fail(`${where}: ${name} is for coordinates '${own}' (the coordinates are '${type}')`);
    if (!(Number.isInteger(value) && ((value >= min && value <= max) || (zeroAllowed && value === 0)))) {
      fail(`${where}: ${name} must be an integer from ${min} to ${max}${zeroAllowed ? ', or 0 (chosen from the cage)' : ''} (got ${JSON.stringify(value)})`);
    }
    out[name] = value;
  };
  resolution(pmvcResolution, 'pmvcResolution', 'pmvc', COORDINATES.pmvcResolution, false);
  resolution(harmonicResolution, 'harmonicResolution', 'harmonic', COORDINATES.harmonicResolution, true);
  return /** @type {CoordinatesChoice} */ (out);
}
