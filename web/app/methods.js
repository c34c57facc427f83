// The deformation methods the Deformer offers (the library's list, from the C++ options table) and how the
// app orders, names and colours them.
import { METHODS } from '../lib/options.js';

export { METHODS };
export const COMPARE_METHODS = ['arap', 'subspace', 'full'];
export const METHOD_LABELS = { subspace: 'Subspace (cage)', full: 'Full space', arap: 'ARAP' };
export const METHOD_COLORS = { subspace: '#f08a24', full: '#7a4fd6', arap: '#2a8a5a' };

/** The methods of compare mode for the `compare` option: a list, a string ("arap,subspace"), true, or off (null). */
export function compareMethods(compare) {
  if (!compare) return null;
  if (Array.isArray(compare)) return compare.filter((m) => METHODS.includes(m));
  if (typeof compare === 'string' && compare !== 'true' && compare !== '') {
    const list = compare.split(/[\s,|]+/).filter((m) => METHODS.includes(m));
    if (list.length) return list;
  }
  return COMPARE_METHODS;
}

/** A view's label: the method, and for the subspace its basis (the cage's, or the spectral one with its modes). */
export function viewLabel(method, model) {
  if (method !== 'subspace' || model?.basis !== 'spectral') return METHOD_LABELS[method];
  return `Subspace (spectral, ${model.basisSize - 4} modes)`;
}
