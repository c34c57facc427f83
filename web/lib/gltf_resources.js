// @ts-check
// Where a glTF's buffers and images come from (gltf.js reads them through here): the .glb's own chunk, data:
// URIs, or files given by name. Everything a file names is untrusted, so
//   - a named file must lie in the .gltf's folder or below (contained_path.js), whether given or not;
//   - all of a model's resources together stay within the one file limit (file_limits.js, 1 GiB: what a .glb
//     holding everything may have), each data: URI checked by its length before it is decoded;
//   - base64 is decoded by the platform (Buffer in Node, atob in a browser) into one byte array, never
//     through per-byte JS values (a 100 MB image would take gigabytes that way).
import { containedUri } from './contained_path.js';
import { InputError } from './errors.js';
import { MAX_FILE_BYTES, checkFileSize } from './file_limits.js';

/** glTF-Transform's name for the GLB's own binary chunk. */
export const GLB_BUFFER = '@glb.bin';

const BASE64 = /^[A-Za-z0-9+/\t\n\f\r ]*=?=?[\t\n\f\r ]*$/;

/**
 * @param {string} filename
 * @param {string} message
 * @param {string} [code] one of ERROR_CODES
 * @returns {never}
 */
function fail(filename, message, code = 'parse_error') {
  throw new InputError(`${filename}: ${message}`, { code });
}

/**
 * @param {string} payload
 * @returns {Uint8Array|null} null: not base64
 */
function decodeBase64(payload) {
  if (!BASE64.test(payload)) return null;
  const NodeBuffer = globalThis.Buffer;
  if (typeof NodeBuffer === 'function') {
    const bytes = NodeBuffer.from(payload, 'base64');
    return new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.length);
  }
  let text;
  try {
    text = atob(payload);
  } catch {
    return null;
  }
  const out = new Uint8Array(text.length);
  for (let i = 0; i < text.length; ++i) out[i] = text.charCodeAt(i);
  return out;
}

/**
 * @param {string} payload
 * @returns {Uint8Array|null} null: not percent-encoded text
 */
function decodePercent(payload) {
  try {
    return new TextEncoder().encode(decodeURIComponent(payload));
  } catch {
    return null;
  }
}

/**
 * The file given under `name`: an own property only. A file named "constructor" or "toString" found
 * Object.prototype's function in a plain object of files, whose byteLength of undefined then read as a resource
 * of NaN GB (file_too_large) instead of a file that was not given.
 * @param {Record<string, Uint8Array>|undefined} given
 * @param {string} name
 * @returns {Uint8Array|undefined}
 */
function givenFile(given, name) {
  return given && Object.hasOwn(given, name) ? given[name] : undefined;
}

/**
 * Resolves every buffer and image of a document into named resources (item.uri is replaced by its key for
 * data: URIs). A missing file is an InputError (code unreadable_file) naming it, one outside the folder too,
 * resources beyond the file limit together one with code file_too_large.
 * @param {any} json the parsed document (changed in place)
 * @param {Uint8Array|null} bin the .glb's binary chunk
 * @param {Record<string, Uint8Array>|undefined} given files by name (their URI, or its last part)
 * @param {string} filename
 * @param {{ maxBytes?: number }} [options] the limit for all resources together (default MAX_FILE_BYTES)
 * @returns {Record<string, Uint8Array>}
 */
export function resolveResources(json, bin, given, filename, { maxBytes = MAX_FILE_BYTES } = {}) {
  /** @type {Record<string, Uint8Array>} */
  const resources = {};
  let total = bin ? bin.byteLength : 0;
  /** @type {(bytes: number, name: string) => void} */
  const take = (bytes, name) => {
    checkFileSize(total + bytes, `${filename} with its resources up to ${name}`, maxBytes);
    total += bytes;
  };
  /** @type {(item: { uri?: unknown }, what: 'buffer'|'image', index: number) => void} */
  const resolve = (item, what, index) => {
    if (item.uri === undefined) return;
    const where = `${filename}: ${what} ${index}`;
    if (typeof item.uri !== 'string') return fail(filename, `${what} ${index} has a uri that is not a string`);
    const uri = item.uri;
    const match = /^data:[^,]*?(;base64)?,/.exec(uri);
    if (match) {
      const payload = uri.slice(match[0].length);
      take(match[1] ? Math.floor(payload.length * 3 / 4) : payload.length, `${what} ${index} (a data: URI)`);
      const data = match[1] ? decodeBase64(payload) : decodePercent(payload);
      if (!data) return fail(filename, `${what} ${index}: its data: URI is not valid ${match[1] ? 'base64' : 'percent-encoded text'}`);
      const key = `@${what}${index}`;
      resources[key] = data;
      item.uri = key;
      return;
    }
    const path = containedUri(uri, where);
    const file = givenFile(given, uri) ?? givenFile(given, path) ?? givenFile(given, /** @type {string} */ (path.split('/').pop()));
    if (!file) {
      return fail(filename, `${what} ${index} is in the separate file "${uri}", which was not given: load it together with ` +
        'the .gltf (or use a .glb, which holds everything)', 'unreadable_file');
    }
    take(file.byteLength, `${what} ${index} ("${uri}")`);
    resources[uri] = file;
  };
  (json.buffers ?? []).forEach((/** @type {any} */ b, /** @type {number} */ i) => {
    if (b && typeof b === 'object' && b.uri === undefined && i === 0 && bin) resources[GLB_BUFFER] = bin;
    else if (b && typeof b === 'object' && b.uri === undefined) fail(filename, `buffer ${i} has no data (no uri, and no .glb chunk holds it)`, 'unreadable_file');
    else if (b && typeof b === 'object') resolve(b, 'buffer', i);
  });
  (json.images ?? []).forEach((/** @type {any} */ image, /** @type {number} */ i) => {
    if (image && typeof image === 'object' && image.bufferView === undefined) resolve(image, 'image', i);
  });
  return resources;
}
