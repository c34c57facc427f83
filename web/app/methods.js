// The deformation methods the Deformer offers (the library's list, from the C++ options table) and how the
// app orders, names and colours them.
import { InputError } from '../lib/errors.js';
import { METHODS, describeValue } from '../lib/options.js';

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

/**
 * The views of the `compare` option: a list of methods, a string ("arap,subspace"), true (all three), or off
 * (false, null: no compare mode, `methods` null). Each method at most once, in the order given, so a list of
 * any length gives at most three views (a URL with 50 entries once started 100 workers); entries that are no
 * method are returned in `unknown`. A list with no method at all means all three.
 * @param {unknown} compare
 * @returns {{ methods: string[]|null, unknown: unknown[] }}
 */
export function readCompare(compare) {
  if (!compare) return { methods: null, unknown: [] };
  if (compare === true || compare === 'true' || compare === '1') return { methods: [...COMPARE_METHODS], unknown: [] };
  const entries = Array.isArray(compare) ? compare : typeof compare === 'string' ? compare.split(/[\s,|]+/).filter(Boolean) : [compare];
  const methods = [];
  const unknown = [];
  for (const entry of entries) {
    if (!METHODS.includes(/** @type {string} */ (entry))) unknown.push(entry);
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

/** A view's label: the method, and for the subspace its basis (the cage's, or the spectral one with its modes). */
export function viewLabel(method, model) {
  if (method !== 'subspace' || model?.basis !== 'spectral') return methodLabel(method);
  return `Subspace (spectral, ${model.basisSize - 4} modes)`;
}
