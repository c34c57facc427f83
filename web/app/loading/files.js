// Reading what the user gives the app: URLs (the one fetch helper, for meshes, cages, scenes and the files a
// scene names) and File objects (dropped or picked), sorted into meshes and scenes. Both are bounded by the
// library's file limit (web/lib/file_limits.js): a larger file is refused by its declared size, or once the
// bytes read pass the limit, with an InputError (code 'file_too_large').

import { InputError } from '../../lib/errors.js';
import { checkFileSize } from '../../lib/file_limits.js';
import { MODEL_EXTENSIONS, isModelName, modelFormatOf } from '../../lib/formats.js';

const MESH_FILE = new RegExp(`\\.(${MODEL_EXTENSIONS.join('|')})$`, 'i');
const SCENE_FILE = /\.json$/i;
// What a .gltf may keep in separate files: its buffers and its textures.
const GLTF_RESOURCE = /\.(bin|png|jpe?g|webp|ktx2|avif)$/i;

/**
 * Fetches a URL (relative to `base`). Rejects with an Error naming the URL and the HTTP status; its `reason`
 * is the status alone (for messages that name the URL their own way).
 * @param {string} url
 * @param {{ base?: string, as?: 'bytes'|'text', signal?: AbortSignal }} [options] signal: aborts the fetch (the app disposed)
 * @returns {Promise<{ name: string, url: string, bytes?: Uint8Array, text?: string }>} name: the file name
 */
export async function fetchFile(url, { base = document.baseURI, as = 'bytes', signal } = {}) {
  const resolved = new URL(url, base);
  const response = await fetch(resolved, { signal }).catch((e) => ({ ok: false, statusText: e.message }));
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

/**
 * A File's name and bytes (what the worker reads), refused by its size when over the limit; `path`: its place in
 * a picked folder (File.webkitRelativePath), when it has one.
 */
export async function readFile(file) {
  checkFileSize(file.size, file.name);
  const read = { name: file.name, bytes: new Uint8Array(await file.arrayBuffer()) };
  return file.webkitRelativePath ? { ...read, path: file.webkitRelativePath } : read;
}

/**
 * A fetched model file under a name that says its format: its own, or, for a URL without a model extension (an
 * API endpoint such as /api/model/17), that name with the extension of the format its content has (formats.js
 * modelFormatOf: what the library and the CLI read it as). Content that is no model is an InputError naming the URL.
 * @param {{ name: string, url?: string, bytes: Uint8Array }} file
 */
export function asModelFile(file) {
  if (isModelName(file.name) || !file.bytes) return file;
  const format = modelFormatOf(file.bytes);
  if (!format) {
    throw new InputError(`${file.url ?? file.name} is no model the app reads: its name has no extension of OBJ, OFF, PLY, ` +
      'STL or glTF, and its content is none of them', { code: 'parse_error' });
  }
  return { ...file, name: `${file.name || 'model'}.${format}` };
}

/**
 * Sorts dropped or picked files into scenes, models and the files a .gltf refers to (its .bin and textures,
 * accepted beside a .gltf only); throws naming any other file.
 * @param {File[]} files
 * @returns {{ scenes: File[], meshes: File[], resources: File[] }}
 */
export function sortFiles(files) {
  const scenes = files.filter((f) => SCENE_FILE.test(f.name));
  const meshes = files.filter((f) => MESH_FILE.test(f.name));
  const gltf = meshes.some((f) => /\.gltf$/i.test(f.name));
  const resources = gltf ? files.filter((f) => GLTF_RESOURCE.test(f.name)) : [];
  const other = files.filter((f) => !scenes.includes(f) && !meshes.includes(f) && !resources.includes(f));
  if (other.length) {
    throw new InputError(`${other.map((f) => f.name).join(', ')}: unsupported file type (use OBJ, OFF, PLY, STL, glTF ` +
      '(.glb, or .gltf with its files), or a scene .json)');
  }
  return { scenes, meshes, resources };
}

/**
 * Reads dropped or picked files: a scene .json (its text) and/or meshes (at most two without a scene). Other files,
 * or too many meshes, are refused through `refuse(error)` (the loader's banner), which throws.
 * @param {File[]} files
 * @param {(error: Error) => never} refuse
 * @returns {Promise<{ scene: { name: string, text: string }|null, meshes: { name: string, bytes: Uint8Array }[] }>}
 */
export async function readDropped(files, refuse) {
  let sorted;
  try {
    sorted = sortFiles(files);
  } catch (error) {
    refuse(error);
  }
  const { scenes, meshes, resources } = sorted;
  if (!scenes.length && meshes.length > 2) refuse(new InputError(`drop one mesh and at most one cage (got ${meshes.length} mesh files)`));
  const scene = scenes.length ? { name: scenes[0].name, text: await scenes[0].text() } : null;
  // A .gltf's own files travel with the models: the worker reads them by their uri (withGltfFiles).
  return { scene, meshes: await Promise.all([...meshes, ...resources].map(readFile)) };
}

// At most this many separate files are fetched for one .gltf (a real model has a .bin and a few textures).
const MAX_GLTF_FILES = 64;

// The file names a .gltf refers to (buffers and images outside it; data: URIs need none), each once. A .gltf
// that does not parse names none: the reader then says what is wrong with it.
function separateFiles(file) {
  let json;
  try {
    json = JSON.parse(new TextDecoder().decode(file.bytes));
  } catch {
    return [];
  }
  const items = [json?.buffers, json?.images].filter(Array.isArray).flat();
  return [...new Set(items.map((item) => item?.uri).filter((uri) => typeof uri === 'string' && !uri.startsWith('data:')))];
}

// The path a uri names from the .gltf's folder, unescaped, without '.' parts (the reader refuses '..').
function uriPath(uri) {
  let path = uri;
  try {
    path = decodeURIComponent(uri);
  } catch { /* the reader names a malformed escape */ }
  return path.split('/').filter((part) => part && part !== '.').join('/');
}
const baseName = (path) => path.split('/').pop();
const pathOf = (file) => file.path || file.name;

/**
 * The dropped file a uri of `gltf` names: the one at its path from the .gltf's folder (files of a picked folder
 * know theirs), else the one of its base name, unless that is ambiguous: two dropped files of that name, or two
 * uris of the .gltf with that base name (a/data.bin, b/data.bin), is an InputError naming them, never a guess.
 */
function droppedFileFor(uri, uris, gltf, dropped) {
  const folder = pathOf(gltf).slice(0, pathOf(gltf).lastIndexOf('/') + 1);
  const path = folder + uriPath(uri);
  const exact = dropped.filter((f) => pathOf(f) === path);
  if (exact.length === 1) return exact[0];
  const name = baseName(path);
  const named = dropped.filter((f) => baseName(pathOf(f)) === name);
  const sharing = uris.filter((u) => baseName(uriPath(u)) === name);
  if (named.length > 1 || (named.length === 1 && sharing.length > 1)) {
    throw new InputError(`${gltf.name} refers to ${sharing.join(', ')}, and ${named.length} dropped files are named ${name}: which is ` +
      'which cannot be told from their names alone; convert the model to a .glb (one file), or load it by URL', { code: 'unreadable_file' });
  }
  return named[0];
}

/** Dropped or picked files: each model with, for a .gltf, its own files among the rest (withGltfFiles), each once. */
export async function withDroppedFiles(files) {
  const models = files.filter((f) => MESH_FILE.test(f.name));
  const rest = files.filter((f) => !models.includes(f));
  const out = [];
  for (const model of models) {
    for (const file of await withGltfFiles(model, rest)) {
      const same = out.find((f) => f.name === file.name);
      if (!same) out.push(file);
      else if (same.bytes !== file.bytes) throw new InputError(`two dropped .gltf files refer to ${file.name}, each to another file: load them one at a time`);
    }
  }
  return out;
}

/**
 * A model file with, for a .gltf, the separate files it refers to (its .bin, its textures), each named by its uri
 * as the .gltf writes it (the key the reader looks it up by): those among `dropped` (droppedFileFor), the rest
 * fetched relative to the .gltf's URL. So a .gltf the app fetches (a URL parameter,
 * the embed's attribute, a scene's mesh) loads as one dropped with its files does.
 * @param {{ name: string, bytes: Uint8Array, url?: string }} file
 * @param {{ name: string, bytes: Uint8Array }[]} [dropped]
 * @param {{ signal?: AbortSignal }} [options] signal: aborts the fetches (the app disposed), as fetchFile's
 * @returns {Promise<{ name: string, bytes: Uint8Array }[]>} the file first
 */
export async function withGltfFiles(file, dropped = [], { signal } = {}) {
  if (!/\.gltf$/i.test(file.name) || !file.bytes) return [file];
  const uris = separateFiles(file);
  if (uris.length > MAX_GLTF_FILES) {
    throw new InputError(`${file.name} refers to ${uris.length} separate files, more than ${MAX_GLTF_FILES}`, { code: 'parse_error' });
  }
  const out = [file];
  for (const uri of uris) {
    const local = droppedFileFor(uri, uris, file, dropped);
    if (local || !file.url) {
      if (local) out.push({ name: uri, bytes: local.bytes });  // none and no URL: the reader names the missing file
      continue;
    }
    out.push(await fetchFile(uri, { base: file.url, signal }).then((fetched) => ({ ...fetched, name: uri }), (error) => {
      throw new InputError(`${file.name} refers to ${uri}, which could not be loaded (${error.reason ?? error.message})`,
        { code: 'unreadable_file' });
    }));
  }
  return out;
}
