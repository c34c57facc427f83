// The deformation methods the Deformer offers (the library's list, from the C++ options table) and how the
// app orders, names and colours them; and the views' keys: a method, or 'subspace:<coordinates>' for the
// subspace solve with given cage coordinates ("compare coordinates" shows two such views).
import { COORDINATES } from '../lib/coordinates.js';
import { InputError } from '../lib/errors.js';
import { METHODS, describeValue } from '../lib/options.js';
import { isSpectral } from '../lib/subspace.js';

export { METHODS };
export const COMPARE_METHODS = ['arap', 'subspace', 'full'];
// Maps, read through the functions below: a method name may come from a user (a URL parameter, a script).
const LABELS = new Map([['subspace', 'Subspace (cage)'], ['full', 'Full space'], ['arap', 'ARAP']]);
const COLORS = new Map([['subspace', '#f08a24'], ['full', '#7a4fd6'], ['arap', '#2a8a5a']]);

/** What the views call a method ('ARAP'); an unknown name as it is. */
export function methodLabel(method) {
  return LABELS.get(method) ?? String(method);
}

/** A method's colour in the views and plots (grey for an unknown name). */
export function methodColor(method) {
  return COLORS.get(method) ?? '#888888';
}

/** How the app names each cage coordinate type. */
export const COORDINATE_LABELS = Object.freeze({ mvc: 'mean value', pmvc: 'positive mean value', harmonic: 'harmonic' });

/** A view key's method and cage coordinates (null: the app's setting), or null for a key that is neither. */
export function parseViewKey(key) {
  if (typeof key !== 'string') return null; // from a script: anything (String() of { toString: false } throws)
  if (METHODS.includes(key)) return { method: key, coordinates: null };
  const [method, coordinates] = key.split(':');
  return method === 'subspace' && COORDINATES.types.includes(coordinates) ? { method, coordinates } : null;
}

/**
 * A view's label for its key (a method, or 'subspace:<coordinates>'): the method, and for the subspace its basis
 * (the spectral one with its modes; a key with coordinates names them).
 */
export function viewLabel(key, model) {
  const parsed = parseViewKey(key);
  if (!parsed) return String(key);
  if (parsed.coordinates) return `Subspace (${COORDINATE_LABELS[parsed.coordinates]} coordinates)`;
  if (parsed.method !== 'subspace' || !isSpectral(model)) return methodLabel(parsed.method);
  return `Subspace (spectral, ${model.basisSize - 4} modes)`;
}

/** The two views of "compare coordinates": the subspace solve with `first` and with `second` coordinates. */
export function compareCoordinatesKeys(first, second) {
  const other = second !== first ? second : COORDINATES.types.find((t) => t !== first);
  return [`subspace:${first}`, `subspace:${other}`];
}

/**
 * The views' keys for the app's `compare` value, as readCompare or checkCompare gave it: ['coordinates'] (the
 * settings' coordinates beside compareCoordinates), a list of keys, or null (the settings' method alone).
 * @param {string[]|null} compare
 * @param {{ method: string, coordinates: string, compareCoordinates: string }} settings
 */
export function viewKeys(compare, { method, coordinates, compareCoordinates }) {
  if (compare?.length === 1 && compare[0] === 'coordinates') return compareCoordinatesKeys(coordinates, compareCoordinates);
  return compare ?? [method];
}

/**
 * The views of the `compare` option: a list of methods or view keys ('subspace:harmonic'), a string
 * ("arap,subspace"), true (all three), 'coordinates' (two cage coordinates: viewKeys), or off (false, null: no
 * compare mode, `methods` null). Each key at most once, in the order given, so a list of any length gives few
 * views (a URL with 50 entries once started 100 workers); entries that are no key are returned in `unknown`. A
 * list with no key at all means all three methods.
 * @param {unknown} compare
 * @returns {{ methods: string[]|null, unknown: unknown[] }}
 */
export function readCompare(compare) {
  if (!compare) return { methods: null, unknown: [] };
  if (compare === true || compare === 'true' || compare === '1') return { methods: [...COMPARE_METHODS], unknown: [] };
  if (compare === 'coordinates') return { methods: ['coordinates'], unknown: [] };
  const entries = Array.isArray(compare) ? compare : typeof compare === 'string' ? compare.split(/[\s,|]+/).filter(Boolean) : [compare];
  const methods = [];
  const unknown = [];
  for (const entry of entries) {
    if (!parseViewKey(entry)) unknown.push(entry);
    else if (!methods.includes(entry)) methods.push(entry);
  }
  return { methods: methods.length ? methods : [...COMPARE_METHODS], unknown };
}

/** The methods of compare mode for the `compare` option (readCompare, leaving out what is no method), or null. */
export function compareMethods(compare) {
  return readCompare(compare).methods;
}

/**
 * The methods setCompare takes: readCompare's, but a list with something that is no method is refused (a
 * script's mistake, unlike a page's URL parameter, which the app reports and drops: page_options.js).
 * @returns {string[]|null}
 */
export function checkCompare(compare) {
  const { methods, unknown } = readCompare(compare);
  if (unknown.length) {
    throw new InputError(`setCompare: ${unknown.map((m) => describeValue(m)).join(', ')} ${unknown.length > 1 ? 'are no methods' : 'is no method'} (methods: ${METHODS.join(', ')})`);
  }
  return methods;
}
