// @ts-check
// The library's typed errors. Everything the library, the solver worker's client and the CLI throw is a
// SubspaceDeformError with a stable `code` (the C++ core's codes, cpp/core/error.h, plus the same ones
// for checks made here); code that reacts to an error reads `code` or the class, never the message.
// The class says what the caller can do about it:
//   InputError      fix the call or the file: invalid_argument, parse_error, unreadable_file, file_too_large,
//                   unwritable_file, no_cage, invalid_skeleton
//   MeshError       a mesh or cage failed its checks: invalid_mesh, mesh_outside_cage (.findings lists them)
//   SolverError     the computation failed: memory_budget, out_of_memory, numerical_failure, cage_failed,
//                   internal
//   CancelledError  a progress callback returned false, or the worker was terminated: cancelled
// Errors cross the worker boundary as plain data ({ code, message, findings }: errorToData) and are
// rebuilt on the other side (errorFromData), so the page sees the same classes the worker threw. The list
// of the C++ codes is ERROR_CODES in build/wasm/solver_schema.js (library.js exports it); this module
// itself depends on no build output.

/** @typedef {{ severity: 'error'|'warning'|'note', code: string, message: string }} Finding */
/** @typedef {{ code: string, message: string, findings?: Finding[] }} ErrorData  code: one of ERROR_CODES */

export class SubspaceDeformError extends Error {
  /**
   * @param {string} message
   * @param {{ code?: string, findings?: Finding[], cause?: unknown }} [details]
   */
  constructor(message, { code = 'internal', findings, cause } = {}) {
    super(message, cause === undefined ? undefined : { cause });
    this.name = 'SubspaceDeformError';
    /** @type {string} */
    this.code = code;
    if (findings !== undefined) {
      /** @type {Finding[] | undefined} */
      this.findings = findings;
    }
  }
}

/** A bad argument or input: the message names it. */
export class InputError extends SubspaceDeformError {
  /** @param {string} message @param {{ code?: string, findings?: Finding[], cause?: unknown }} [details] */
  constructor(message, { code = 'invalid_argument', ...rest } = {}) {
    super(message, { code, ...rest });
    this.name = 'InputError';
  }
}

/** A mesh or cage that failed its checks; `findings` lists every problem. */
export class MeshError extends SubspaceDeformError {
  /** @param {string} message @param {{ code?: string, findings?: Finding[], cause?: unknown }} [details] */
  constructor(message, { code = 'invalid_mesh', findings = [], ...rest } = {}) {
    super(message, { code, findings, ...rest });
    this.name = 'MeshError';
  }
}

/** The solver, the binding or the cage generation failed on valid input. */
export class SolverError extends SubspaceDeformError {
  /** @param {string} message @param {{ code?: string, findings?: Finding[], cause?: unknown }} [details] */
  constructor(message, { code = 'internal', ...rest } = {}) {
    super(message, { code, ...rest });
    this.name = 'SolverError';
  }
}

/** Cancelled by a progress callback or by terminating the worker. */
export class CancelledError extends SubspaceDeformError {
  /** @param {string} [message] @param {{ cause?: unknown }} [details] */
  constructor(message = 'cancelled', { cause } = {}) {
    super(message, { code: 'cancelled', cause });
    this.name = 'CancelledError';
  }
}

/** @type {Map<string, new (message: string, details?: object) => SubspaceDeformError>} (a Map: a code is data) */
const CLASS_OF_CODE = new Map([
  ['invalid_argument', InputError],
  ['parse_error', InputError],
  ['unreadable_file', InputError],
  ['file_too_large', InputError],
  ['unwritable_file', InputError],
  ['no_cage', InputError],
  ['invalid_skeleton', InputError],
  ['invalid_mesh', MeshError],
  ['mesh_outside_cage', MeshError],
  ['memory_budget', SolverError],
  ['out_of_memory', SolverError],
  ['numerical_failure', SolverError],
  ['cage_failed', SolverError],
  ['internal', SolverError],
  ['cancelled', CancelledError],
]);

/** The codes each class stands for (tests check that every C++ code has one). */
export const CODES_BY_CLASS = Object.freeze({
  InputError: codesOf(InputError),
  MeshError: codesOf(MeshError),
  SolverError: codesOf(SolverError),
  CancelledError: codesOf(CancelledError),
});

/** @param {Function} type @returns {string[]} */
function codesOf(type) {
  return [...CLASS_OF_CODE].filter(([, Type]) => Type === type).map(([code]) => code);
}

/**
 * The typed error for plain error data (from the worker, or an Error the wasm bindings threw).
 * @param {ErrorData} data
 * @param {unknown} [cause]
 * @returns {SubspaceDeformError}
 */
export function errorFromData({ code, message, findings }, cause) {
  const Type = CLASS_OF_CODE.get(code) ?? SolverError;
  if (Type === CancelledError) return new CancelledError(message, { cause });
  return new Type(message, { code: CLASS_OF_CODE.has(code) ? code : 'internal', findings, cause });
}

/**
 * Plain data for any error (what the worker posts): a typed error keeps its code and findings, an Error
 * thrown by the wasm bindings its code; anything else is 'internal'.
 * @param {unknown} error
 * @returns {ErrorData}
 */
export function errorToData(error) {
  const typed = typedError(error);
  /** @type {ErrorData} */
  const data = { code: typed.code, message: typed.message };
  if (typed.findings) data.findings = typed.findings.map((f) => ({ ...f }));
  return data;
}

/**
 * `error` as a SubspaceDeformError: typed errors as they are, Errors from the wasm bindings (they carry
 * a string `code`) by their code, anything else as an 'internal' SolverError with the original as cause.
 * @param {unknown} error
 * @returns {SubspaceDeformError}
 */
export function typedError(error) {
  if (error instanceof SubspaceDeformError) return error;
  const thrown = /** @type {{ message?: unknown, code?: unknown, findings?: Finding[] } | null | undefined} */ (error);
  const message = String(thrown?.message ?? error);
  if (typeof thrown?.code === 'string' && CLASS_OF_CODE.has(thrown.code)) {
    return errorFromData({ code: thrown.code, message, findings: thrown.findings }, error);
  }
  return new SolverError(message, { code: 'internal', cause: error });
}

/**
 * Calls into the wasm module, turning what it throws into typed errors.
 * @template T
 * @param {() => T} call
 * @returns {T}
 */
export function callWasm(call) {
  try {
    return call();
  } catch (error) {
    throw typedError(error);
  }
}

const NOTHING = Symbol('nothing thrown');

/**
 * callWasm for a call that hands the module a caller's callback (onProgress): the callback's own exception
 * reaches the caller as it was thrown (its class and message), not as an 'internal' SolverError. The bindings
 * catch it inside the module, free what the call held and throw that same value (cpp/bindings/js_bridge.h).
 * @template T
 * @param {Function|undefined|null} callback
 * @param {(callback: Function|undefined) => T} call receives the callback to hand over (undefined without one)
 * @returns {T}
 */
export function callWasmWithCallback(callback, call) {
  if (typeof callback !== 'function') return callWasm(() => call(undefined));
  /** @type {unknown} */
  let thrown = NOTHING;
  const watched = (/** @type {any[]} */ ...args) => {
    try {
      return callback(...args);
    } catch (error) {
      thrown = error;
      throw error;
    }
  };
  try {
    return call(watched);
  } catch (error) {
    if (thrown !== NOTHING && error === thrown) throw error;
    throw typedError(error);
  }
}
