// The deformation methods the Deformer offers (the library's list, from the C++ options table) and how the
// app orders, names and colours them; and the views' keys: a method, or 'subspace:<coordinates>' for the
// subspace solve with given cage coordinates (compare mode's "compare coordinates" shows two such views).
import { COORDINATES } from '../lib/coordinates.js';
import { METHODS } from '../lib/options.js';

export { METHODS };
export const COMPARE_METHODS = ['arap', 'subspace', 'full'];
export const METHOD_LABELS = { subspace: 'Subspace (cage)', full: 'Full space', arap: 'ARAP' };
export const METHOD_COLORS = { subspace: '#f08a24', full: '#7a4fd6', arap: '#2a8a5a' };
/** How the app names each cage coordinate type. */
export const COORDINATE_LABELS = { mvc: 'mean value', pmvc: 'positive mean value', harmonic: 'harmonic' };

/** A view key's method and cage coordinates (null: the app's setting), or null for a key that is neither. */
export function parseViewKey(key) {
  if (METHODS.includes(key)) return { method: key, coordinates: null };
  const [method, coordinates] = String(key).split(':');
  return method === 'subspace' && COORDINATES.types.includes(coordinates) ? { method, coordinates } : null;
}

/** The label of a view: its method's, and for a key with coordinates the subspace with those coordinates. */
export function viewLabel(key) {
  const { method, coordinates } = parseViewKey(key);
  return coordinates ? `Subspace (${COORDINATE_LABELS[coordinates]} coordinates)` : METHOD_LABELS[method];
}

/** The two views of "compare coordinates": the subspace solve with `first` and with `second` coordinates. */
export function compareCoordinatesKeys(first, second) {
  const other = second !== first ? second : COORDINATES.types.find((t) => t !== first);
  return [`subspace:${first}`, `subspace:${other}`];
}

/**
 * The views' keys for the app's `compare` value: 'coordinates' (the settings' coordinates beside
 * compareCoordinates), what compareMethods takes, or off (the settings' method alone).
 * @param {unknown} compare
 * @param {{ method: string, coordinates: string, compareCoordinates: string }} settings
 */
export function viewKeys(compare, { method, coordinates, compareCoordinates }) {
  if (compare === 'coordinates') return compareCoordinatesKeys(coordinates, compareCoordinates);
  return compareMethods(compare) ?? [method];
}

/**
 * The views of compare mode for the `compare` option: a list, a string ("arap,subspace" or
 * "subspace:mvc,subspace:harmonic"), true, or off (null).
 */
export function compareMethods(compare) {
  if (!compare) return null;
  if (Array.isArray(compare)) return compare.filter((m) => parseViewKey(m));
  if (typeof compare === 'string' && compare !== 'true' && compare !== '') {
    const list = compare.split(/[\s,|]+/).filter((m) => parseViewKey(m));
    if (list.length) return list;
  }
  return COMPARE_METHODS;
}
