// @ts-check
// The solver options as data, and the one check of an options object that every JS entry uses
// (Deformer.setOptions, the scene parser, the app's settings). The data is the C++ table
// (cpp/core/solver/solver_options.cpp) written out by the wasm build as build/wasm/solver_schema.js, so it
// is known where no wasm module is loaded (the page parses scenes on its main thread; the module lives in
// the worker). Messages are the C++ ones: "maxIterations must be an integer from 1 to 2147483647 (got 0)".
import { SOLVER_OPTIONS } from '../../build/wasm/solver_schema.js';
import { InputError } from './errors.js';

/**
 * @typedef {object} OptionSchema
 * @property {string} name as JS and scene files spell it
 * @property {'choice'|'boolean'|'integer'|'number'} kind
 * @property {string|boolean|number} default
 * @property {number|null} min integer and number: the lower limit (null: none)
 * @property {number|null} max integer and number: the upper limit (null: none)
 * @property {boolean} minOpen the lower limit itself is excluded
 * @property {boolean} maxOpen the upper limit itself is excluded
 * @property {readonly string[]} choices choice: the allowed values
 * @property {string} doc one line, for people
 * @property {string} expects what a valid value is, e.g. "an integer from 1 to 2147483647"
 */

/** @typedef {import('../../build/wasm/solver_schema.js').SolverOptions} SolverOptions  generated from the table */

/** @type {readonly OptionSchema[]} every option, in the table's order */
export const OPTIONS = Object.freeze(SOLVER_OPTIONS.map((o) => Object.freeze({ ...o, choices: Object.freeze([...o.choices]) })));
const BY_NAME = new Map(OPTIONS.map((o) => [o.name, o]));

/** @type {readonly string[]} */
export const OPTION_NAMES = Object.freeze(OPTIONS.map((o) => o.name));
/** @type {Readonly<SolverOptions>} the C++ defaults (SolverOptions{}) */
export const DEFAULT_OPTIONS = Object.freeze(Object.fromEntries(OPTIONS.map((o) => [o.name, o.default])));
/** @type {readonly string[]} the deformation methods, the default first */
export const METHODS = Object.freeze(sortedDefaultFirst(BY_NAME.get('method')));
/** @type {readonly string[]} the Gauss-Newton step modes, the default first */
export const JACOBIANS = Object.freeze(sortedDefaultFirst(BY_NAME.get('jacobian')));

/** @param {OptionSchema|undefined} option @returns {string[]} */
function sortedDefaultFirst(option) {
  if (!option) return [];
  return [String(option.default), ...option.choices.filter((c) => c !== option.default)];
}

/**
 * @param {string} name
 * @returns {OptionSchema|undefined}
 */
export function optionSchema(name) {
  return BY_NAME.get(name);
}

/**
 * Whether `value` is valid for the option: the right type, in range, an integer where one is needed.
 * @param {OptionSchema} option
 * @param {unknown} value
 */
export function optionAllows(option, value) {
  switch (option.kind) {
    case 'choice':
      return option.choices.includes(/** @type {string} */ (value));
    case 'boolean':
      return typeof value === 'boolean';
    case 'integer':
    case 'number': {
      if (typeof value !== 'number' || !Number.isFinite(value)) return false;
      if (option.kind === 'integer' && !Number.isInteger(value)) return false;
      const { min, max, minOpen, maxOpen } = option;
      if (min !== null && (minOpen ? value <= min : value < min)) return false;
      return max === null || (maxOpen ? value < max : value <= max);
    }
    default:
      return false;
  }
}

/**
 * A value as messages show it (the C++ side prints the same): numbers as JS prints them, else JSON.
 * @param {unknown} value
 * @returns {string}
 */
export function describeValue(value) {
  if (typeof value === 'number' || value === undefined) return String(value);
  if (typeof value === 'bigint') return `${value}n`;
  if (typeof value === 'function') return 'a function';
  if (typeof value === 'symbol') return value.toString();
  // What a script passes may not be JSON: a cycle, a BigInt inside, a toJSON that throws. The message must still come.
  try {
    return JSON.stringify(value) ?? Object.prototype.toString.call(value);
  } catch {
    return Object.prototype.toString.call(value);
  }
}

/**
 * Checks an options object (every key optional; undefined and null values are skipped, as in C++) and
 * returns a copy without them. Throws an InputError naming the first unknown key or bad value.
 * @param {unknown} options
 * @param {string} where prefix of the messages, e.g. 'setOptions'
 * @returns {SolverOptions}
 */
export function checkSolverOptions(options, where) {
  if (!options || typeof options !== 'object' || Array.isArray(options)) throw new InputError(`${where}: options must be an object`);
  /** @type {Record<string, unknown>} */
  const out = {};
  for (const [key, value] of Object.entries(options)) {
    const option = BY_NAME.get(key);
    if (!option) throw new InputError(`${where}: unknown option '${key}' (known: ${OPTION_NAMES.join(', ')})`);
    if (value === undefined || value === null) continue;
    if (!optionAllows(option, value)) {
      throw new InputError(`${where}: ${key} must be ${option.expects} (got ${describeValue(value)})`);
    }
    out[key] = value;
  }
  return /** @type {SolverOptions} */ (out);
}
