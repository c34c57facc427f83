// Reading what the user gives the app: URLs (the one fetch helper, for meshes, cages, scenes and the files a
// scene names) and File objects (dropped or picked), sorted into meshes and scenes. Both are bounded by the
// library's file limit (web/lib/file_limits.js): a larger file is refused by its declared size, or once the
// bytes read pass the limit, with an InputError (code 'file_too_large').

import { InputError } from '../../lib/errors.js';
import { checkFileSize } from '../../lib/file_limits.js';
import { MESH_EXTENSIONS } from '../../lib/mesh.js';

const MESH_FILE = new RegExp(`\\.(${MESH_EXTENSIONS.join('|')})$`, 'i');
const SCENE_FILE = /\.json$/i;

/**
 * Fetches a URL (relative to `base`). Rejects with an Error naming the URL and the HTTP status; its `reason`
 * is the status alone (for messages that name the URL their own way).
 * @param {string} url
 * @param {{ base?: string, as?: 'bytes'|'text' }} [options]
 * @returns {Promise<{ name: string, url: string, bytes?: Uint8Array, text?: string }>} name: the file name
 */
export async function fetchFile(url, { base = document.baseURI, as = 'bytes' } = {}) {
  const resolved = new URL(url, base);
  const response = await fetch(resolved).catch((e) => ({ ok: false, statusText: e.message }));
  if (!response.ok) {
    const reason = `${response.status ?? ''} ${response.statusText}`;
    throw Object.assign(new InputError(`could not fetch ${resolved}: ${reason}`, { code: 'unreadable_file' }), { reason });
  }
  const file = { name: resolved.pathname.split('/').pop(), url: resolved.href };
  const bytes = await boundedBody(response, file.name);
  if (as === 'text') file.text = new TextDecoder().decode(bytes);
  else file.bytes = bytes;
  return file;
}

// The response's bytes, refused by the declared length or as soon as more than the limit arrive.
async function boundedBody(response, name) {
  const declared = Number(response.headers?.get('content-length'));
  if (Number.isFinite(declared)) checkFileSize(declared, name);
  if (!response.body?.getReader) {
    const bytes = new Uint8Array(await response.arrayBuffer());
    checkFileSize(bytes.length, name);
    return bytes;
  }
  const reader = response.body.getReader();
  const chunks = [];
  let length = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    length += value.length;
    try {
      checkFileSize(length, name, undefined, { exact: false });
    } catch (error) {
      reader.cancel().catch(() => {});
      throw error;
    }
    chunks.push(value);
  }
  const bytes = new Uint8Array(length);
  let at = 0;
  for (const chunk of chunks) {
    bytes.set(chunk, at);
    at += chunk.length;
  }
  return bytes;
}

/** A File's name and bytes (what the worker reads), refused by its size when over the limit. */
export async function readFile(file) {
  checkFileSize(file.size, file.name);
  return { name: file.name, bytes: new Uint8Array(await file.arrayBuffer()) };
}

/**
 * Sorts dropped or picked files into scenes and meshes; throws naming any other file.
 * @param {File[]} files
 * @returns {{ scenes: File[], meshes: File[] }}
 */
export function sortFiles(files) {
  const scenes = files.filter((f) => SCENE_FILE.test(f.name));
  const meshes = files.filter((f) => MESH_FILE.test(f.name));
  const other = files.filter((f) => !scenes.includes(f) && !meshes.includes(f));
  if (other.length) {
    throw new InputError(`${other.map((f) => f.name).join(', ')}: unsupported file type (use OBJ, OFF, PLY, STL, or a scene .json)`);
  }
  return { scenes, meshes };
}
