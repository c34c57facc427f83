// @ts-check
// How large a file the library and the app read: one limit for mesh, cage and scene files wherever they come
// from (a path in Node: node_files.js; a dropped file or a URL in the app: web/app/loading/files.js). A mesh
// file is copied into the wasm heap (at most 4 GB) and parsed there, so a file beyond this could not be used
// anyway; the limit turns it (or /dev/zero) into a named error at once instead of minutes of reading.
import { InputError } from './errors.js';

/** The most bytes one file may have: 1 GiB (a binary STL of about 20 million triangles). */
export const MAX_FILE_BYTES = 2 ** 30;

/** Bytes as people read them: "512 B", "3.4 MB", "1.07 GB". @param {number} bytes @returns {string} */
export function formatBytes(bytes) {
  if (bytes < 1e3) return `${bytes} B`;
  const [unit, scale] = bytes < 1e6 ? ['kB', 1e3] : bytes < 1e9 ? ['MB', 1e6] : ['GB', 1e9];
  return `${(bytes / scale).toPrecision(3)} ${unit}`;
}

/**
 * Throws an InputError with code 'file_too_large' naming the file when `bytes` exceeds `maxBytes`.
 * @param {number} bytes the file's size, or (exact: false) what was read of it before the limit was passed
 * @param {string} name the file, for the message
 * @param {number} [maxBytes]
 * @param {{ exact?: boolean }} [options] exact: `bytes` is the whole size (else only "larger" is known)
 */
export function checkFileSize(bytes, name, maxBytes = MAX_FILE_BYTES, { exact = true } = {}) {
  if (bytes <= maxBytes) return;
  let size = formatBytes(bytes), limit = formatBytes(maxBytes);
  if (size === limit) [size, limit] = [`${bytes} bytes`, `${maxBytes} bytes`]; // just over: say by how much
  throw new InputError(`${name} ${exact ? `is ${size}` : 'is larger'}: more than the ${limit} a file may have here`,
    { code: 'file_too_large' });
}
