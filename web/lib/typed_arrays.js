// @ts-check
// Typed arrays handed to the library. One whose buffer was transferred (to a worker by postMessage, or by
// structuredClone(x, { transfer })) is detached: it reads as empty, so it would pass as an empty mesh, target
// list or partition, and copying it into wasm fails with a TypeError ('internal'). Every entry that takes typed
// arrays names it instead, as the caller's mistake (an InputError).
import { InputError } from './errors.js';

const isArrayBuffer = (/** @type {unknown} */ value) => Object.prototype.toString.call(value) === '[object ArrayBuffer]';

/**
 * True when `value` is an ArrayBuffer, or a typed array or DataView of one, that was detached.
 * @param {unknown} value
 * @returns {boolean}
 */
export function isDetached(value) {
  const view = ArrayBuffer.isView(value) ? value.buffer : value;
  if (!isArrayBuffer(view)) return false;
  const buffer = /** @type {ArrayBuffer & { detached?: boolean }} */ (view);
  if (buffer.byteLength > 0) return false;
  if (typeof buffer.detached === 'boolean') return buffer.detached; // ArrayBuffer.prototype.detached (ES2024)
  try {
    new Uint8Array(buffer); // an empty buffer takes a view; a detached one throws
    return false;
  } catch {
    return true;
  }
}

/**
 * Returns `value`, or throws an InputError naming it (`what`, e.g. 'setTargets: targets') when it is a detached
 * typed array or ArrayBuffer. Anything else passes unchanged (the caller checks its type).
 * @template T @param {T} value @param {string} what @returns {T}
 */
export function assertAttached(value, what) {
  if (isDetached(value)) {
    const type = ArrayBuffer.isView(value) ? value.constructor.name : 'ArrayBuffer';
    throw new InputError(`${what} is a detached ${type}: its buffer was transferred (postMessage or structuredClone ` +
      'with transfer) and holds nothing any more; pass a copy (.slice()) instead of transferring it');
  }
  return value;
}

/**
 * The path of the first detached typed array or ArrayBuffer within plain objects and arrays (at most `depth`
 * levels down), e.g. 'files[1].bytes'; null when there is none.
 * @param {unknown} value @param {string} [path] @param {number} [depth] @returns {string|null}
 */
export function findDetached(value, path = '', depth = 4) {
  if (isDetached(value)) return path || 'the value';
  if (depth <= 0 || !value || typeof value !== 'object' || ArrayBuffer.isView(value)) return null;
  const entries = Array.isArray(value) ? value.map((v, i) => [`${path}[${i}]`, v]) : Object.entries(value).map(([k, v]) => [path ? `${path}.${k}` : k, v]);
  for (const [at, item] of entries) {
    /** @type {string|null} */
    const found = item && typeof item === 'object' ? findDetached(item, at, depth - 1) : null;
    if (found) return found;
  }
  return null;
}
