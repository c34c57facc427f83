// A pose in a link (issue 31, item 4): a scene (docs/scene-format.md: the model by example name or path, the
// handle groups with their targets, the solver options, the basis, the volume parts and a "view") packed into
// one URL parameter, index.html?pose=..., so that a teacher can share a pose by its link. The text is the
// scene's JSON with every long list of vertex numbers written as runs ("0-41,57,60-63"), compressed
// (deflate-raw, the browser's CompressionStream) and written in base64url after a version, "1.". The app
// decodes it before it mounts (main.js) and loads it as the scene; ui/share_link.js makes the link.
import { InputError } from '../../lib/errors.js';

/** The URL parameter of index.html that carries a pose. */
export const POSE_PARAM = 'pose';
const VERSION = '1';
// Lists of at least this many indices become runs; shorter ones (vectors, a few vertices) stay as they are.
const RUNS_FROM = 4;

const isIndex = (v) => Number.isSafeInteger(v) && v >= 0;

/** "0-3,7,9-10" from [0, 1, 2, 3, 7, 9, 10] (in the list's order; a run only where numbers go up by one). */
export function toRuns(list) {
  const parts = [];
  for (let i = 0; i < list.length;) {
    let j = i;
    while (j + 1 < list.length && list[j + 1] === list[j] + 1) j++;
    parts.push(j > i ? `${list[i]}-${list[j]}` : `${list[i]}`);
    i = j + 1;
  }
  return parts.join(',');
}

/** The list that toRuns wrote (an InputError for text that is no such list). */
export function fromRuns(text) {
  if (typeof text !== 'string' || !/^(\d+(-\d+)?)(,\d+(-\d+)?)*$/.test(text)) throw new InputError(`pose: "${String(text).slice(0, 40)}" is no list of vertex runs`);
  const list = [];
  for (const part of text.split(',')) {
    const [a, b = a] = part.split('-').map(Number);
    if (!(b >= a) || list.length + b - a >= 1e8) throw new InputError(`pose: the run ${part} is not increasing or too long`);
    for (let v = a; v <= b; ++v) list.push(v);
  }
  return list;
}

// Every long list of indices in a JSON value as { runs }, and back.
function packed(value) {
  if (Array.isArray(value)) {
    if (value.length >= RUNS_FROM && value.every(isIndex)) return { runs: toRuns(value) };
    return value.map(packed);
  }
  if (value && typeof value === 'object') return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, packed(v)]));
  return value;
}

function unpacked(value) {
  if (Array.isArray(value)) return value.map(unpacked);
  if (value && typeof value === 'object') {
    const keys = Object.keys(value);
    if (keys.length === 1 && keys[0] === 'runs') return fromRuns(value.runs);
    return Object.fromEntries(keys.map((k) => [k, unpacked(value[k])]));
  }
  return value;
}

async function transformed(bytes, stream) {
  return new Uint8Array(await new Response(new Blob([bytes]).stream().pipeThrough(stream)).arrayBuffer());
}

function base64url(bytes) {
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function fromBase64url(text) {
  const binary = atob(text.replace(/-/g, '+').replace(/_/g, '/'));
  return Uint8Array.from(binary, (c) => c.charCodeAt(0));
}

/**
 * The text of ?pose= for a scene (a plain JSON value: the app's sceneJson() and a "view").
 * @param {object} scene
 * @returns {Promise<string>}
 */
export async function encodePose(scene) {
  const json = new TextEncoder().encode(JSON.stringify(packed(scene)));
  return `${VERSION}.${base64url(await transformed(json, new CompressionStream('deflate-raw')))}`;
}

/**
 * The scene of a ?pose= text; an InputError saying what is wrong with it (cut short, another version, not a
 * scene). The scene itself is checked where it loads (web/lib/scene.js's parser, as a scene file is).
 * @param {string} text
 * @returns {Promise<object>}
 */
export async function decodePose(text) {
  const [version, data] = String(text ?? '').split('.', 2);
  if (version !== VERSION || !data || !/^[\w-]+$/.test(data)) {
    throw new InputError(`pose: this link's pose is not one the app reads (it should start with "${VERSION}." and hold only ` +
      'letters, digits, - and _): was the link cut short or changed?', { code: 'invalid_argument' });
  }
  let scene;
  try {
    const bytes = await transformed(fromBase64url(data), new DecompressionStream('deflate-raw'));
    scene = JSON.parse(new TextDecoder().decode(bytes));
  } catch (error) {
    throw new InputError(`pose: this link's pose cannot be read (${error.message}): was the link cut short?`, { cause: error });
  }
  if (!scene || typeof scene !== 'object' || Array.isArray(scene)) throw new InputError('pose: this link holds no scene');
  return unpacked(scene);
}
