// @ts-check
// What glTF-Transform does not carry from a read file to the written one, put back into the written JSON so that
// a model comes back as it was: extensions it has no class for (VRMC_vrm, VRMC_materials_mtoon, a vendor's
// EXT_...) are dropped by its reader, and a camera's absent zfar (an infinite projection) is written as its
// default 100. The properties whose order it keeps -- scenes, nodes, meshes and their primitives, materials,
// cameras, skins, animations, images -- get back each extension and extras key the output lacks; a mesh
// gltf_write.js copied for another instance gets its original's. Their contents are copied as they are: an
// unknown extension that names accessors or textures by index is not renumbered (it cannot be understood).
// Elsewhere (textures and samplers, which it writes per use and merges, accessors and buffer views, which it
// renumbers, a material's texture references) an unknown extension is lost: the warning names where, and the
// output declares (extensionsUsed, extensionsRequired) only the names it still holds.
// glTF-Transform's warnings for those extensions ("Missing optional extension") are collected, not printed:
// readGltf reports them as the model's warnings, with a code.

/** The code of the warning for an extension the library does not interpret. */
export const UNKNOWN_EXTENSION_CODE = 'gltf_extension_kept_uninterpreted';
/** The code of any other warning glTF-Transform's reader gave: collected, so it must be said. */
export const READER_WARNING_CODE = 'gltf_reader_warning';

// Arrays whose elements glTF-Transform writes in the file's order (textures, samplers, accessors and buffer
// views it renumbers).
const ORDERED = ['scenes', 'nodes', 'meshes', 'materials', 'skins', 'animations', 'images'];

/**
 * A glTF-Transform logger that keeps the warnings it is given instead of printing them.
 * @returns {{ warnings: string[], debug: () => void, info: () => void, warn: (text: string) => void, error: (text: string) => void }}
 */
export function collectingLogger() {
  /** @type {string[]} */
  const warnings = [];
  return { warnings, debug() {}, info() {}, warn: (text) => warnings.push(text), error: (text) => warnings.push(text) };
}

/**
 * readGltf's warnings: the unknown extensions' (one finding), and every other line glTF-Transform's reader logged,
 * as it said it (code READER_WARNING_CODE): the logger collects them all, and none may vanish.
 * @param {any} json the file's JSON
 * @param {string} filename
 * @param {string[]} logged
 * @returns {import('./errors.js').Finding[]}
 */
export function readerWarnings(json, filename, logged) {
  const names = (Array.isArray(json.extensionsUsed) ? json.extensionsUsed : []).filter((/** @type {unknown} */ name) => typeof name === 'string');
  const others = logged.filter((line) => !names.some((/** @type {string} */ name) => line.includes(`"${name}"`)));
  return [...unknownExtensionWarnings(json, filename, logged),
    ...others.map((line) => ({ severity: /** @type {const} */ ('warning'), code: READER_WARNING_CODE, message: `${filename}: glTF reader: ${line}` }))];
}

/**
 * readGltf's warnings for the extensions the file uses and glTF-Transform does not know: kept as they are when the
 * model is written back where restoreUnknown can put them back, named as left out elsewhere; nothing here
 * interprets them.
 * @param {any} json the file's JSON
 * @param {string} filename
 * @param {string[]} logged what glTF-Transform's reader logged
 * @returns {import('./errors.js').Finding[]}
 */
export function unknownExtensionWarnings(json, filename, logged) {
  const names = (Array.isArray(json.extensionsUsed) ? json.extensionsUsed : [])
    .filter((/** @type {unknown} */ name) => typeof name === 'string' && logged.some((line) => line.includes(`"${name}"`)));
  if (!names.length) return [];
  const uses = extensionUses(json);
  const lost = names.flatMap((/** @type {string} */ name) => (uses.get(name) ?? []).filter((where) => !KEPT.test(where)).map((where) => `${name} on ${where}`));
  return [{ severity: 'warning', code: UNKNOWN_EXTENSION_CODE,
    message: `${filename}: extension${names.length > 1 ? 's' : ''} ${names.join(', ')} not interpreted here: kept as ` +
      'they are when the model is written back (indices inside them are not renumbered)' +
      (lost.length ? `, except ${listed(lost)}, which the writer leaves out (it renumbers or merges those objects)` : '') }];
}

// Where restoreUnknown puts an extension back: the root, an item of an ORDERED list, a primitive, a camera.
const KEPT = new RegExp(`^(root|(${ORDERED.join('|')})\\[\\d+\\]|meshes\\[\\d+\\]\\.primitives\\[\\d+\\]|cameras\\[\\d+\\].*)$`);

/** @param {string[]} items @returns {string} the first five, and how many more */
function listed(items) {
  return items.slice(0, 5).join(', ') + (items.length > 5 ? ` and ${items.length - 5} more` : '');
}

/**
 * Every object of `json` with an `extensions` field: extension name -> where ('root', 'textures[0]',
 * 'materials[0].pbrMetallicRoughness.baseColorTexture').
 * @param {any} json
 * @returns {Map<string, string[]>}
 */
export function extensionUses(json) {
  /** @type {Map<string, string[]>} */
  const uses = new Map();
  /** @param {any} value @param {string} where */
  const visit = (value, where) => {
    if (!value || typeof value !== 'object') return;
    if (Array.isArray(value)) {
      value.forEach((item, i) => visit(item, `${where}[${i}]`));
      return;
    }
    const extensions = value.extensions;
    if (extensions && typeof extensions === 'object' && !Array.isArray(extensions)) {
      for (const name of Object.keys(extensions)) uses.set(name, [...(uses.get(name) ?? []), where || 'root']);
    }
    for (const [key, child] of Object.entries(value)) {
      if (key !== 'extensions' && key !== 'extras') visit(child, where ? `${where}.${key}` : key);
    }
  };
  visit(json, '');
  return uses;
}

/**
 * Puts back into `out` (the written JSON) what glTF-Transform dropped from `file` (the read JSON): see the top.
 * @param {any} file
 * @param {any} out changed in place
 * @param {number[]} meshCopies for each mesh appended to the file's meshes, the index of the mesh it copies
 */
export function restoreUnknown(file, out, meshCopies) {
  mergeMissing(file, out);
  // Cameras carry nothing glTF-Transform changes on purpose: the file's own are exact (zfar absent stays absent).
  if (Array.isArray(file.cameras) && Array.isArray(out.cameras) && file.cameras.length === out.cameras.length) out.cameras = structuredClone(file.cameras);
  for (const key of ORDERED) {
    const fileList = file[key] ?? [], outList = out[key] ?? [];
    outList.forEach((/** @type {any} */ item, /** @type {number} */ i) => {
      const source = key === 'meshes' && i >= fileList.length ? fileList[meshCopies[i - fileList.length]] : fileList[i];
      if (!source || !item) return;
      mergeMissing(source, item);
      if (key === 'meshes') (item.primitives ?? []).forEach((/** @type {any} */ p, /** @type {number} */ k) => source.primitives?.[k] && mergeMissing(source.primitives[k], p));
    });
  }
  // Declared again only where an object of the output uses it: a name whose objects were left out is not declared.
  const used = extensionUses(out);
  for (const key of ['extensionsUsed', 'extensionsRequired']) {
    const missing = (file[key] ?? []).filter((/** @type {string} */ name) => used.has(name) && !(out[key] ?? []).includes(name));
    if (missing.length) out[key] = [...(out[key] ?? []), ...missing];
  }
}

/**
 * Each extension and extras key of `from` that `to` lacks, copied over.
 * @param {any} from
 * @param {any} to
 */
function mergeMissing(from, to) {
  for (const field of ['extensions', 'extras']) {
    const source = from[field];
    if (!source || typeof source !== 'object' || Array.isArray(source)) {
      if (source !== undefined && to[field] === undefined) to[field] = structuredClone(source);
      continue;
    }
    for (const [name, value] of Object.entries(source)) {
      if (to[field]?.[name] === undefined) to[field] = { ...(to[field] ?? {}), [name]: structuredClone(value) };
    }
  }
}

/**
 * The .glb `bytes` (as glTF-Transform writes it: a JSON chunk, then at most a binary one) with its JSON
 * replaced by `edit(json)`'s changes; the binary chunk is kept byte for byte.
 * @param {Uint8Array} bytes
 * @param {(json: any) => void} edit changes the parsed JSON in place
 * @returns {Uint8Array}
 */
export function editGlbJson(bytes, edit) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const jsonLength = view.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLength)));
  edit(json);
  const rest = bytes.subarray(20 + jsonLength);  // the binary chunk with its header, 4-aligned already
  let text = new TextEncoder().encode(JSON.stringify(json));
  const padded = new Uint8Array(Math.ceil(text.length / 4) * 4).fill(0x20);  // glTF pads the JSON chunk with spaces
  padded.set(text);
  text = padded;
  const out = new Uint8Array(20 + text.length + rest.length);
  const outView = new DataView(out.buffer);
  out.set(bytes.subarray(0, 12));
  outView.setUint32(8, out.length, true);
  outView.setUint32(12, text.length, true);
  outView.setUint32(16, 0x4e4f534a, true);  // 'JSON'
  out.set(text, 20);
  out.set(rest, 20 + text.length);
  return out;
}
