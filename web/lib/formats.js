// @ts-check
// The file formats of models, by extension (and, for a file named without one, by content): what the library
// reads (model_io.js) and writes. A module of its own with no imports, so that a page can sort dropped files
// without loading the readers.

/** Read by the C++ readers (mesh.js readMesh). */
export const MESH_EXTENSIONS = ['obj', 'off', 'ply', 'stl'];
/** Read by gltf.js. */
export const GLTF_EXTENSIONS = ['glb', 'gltf'];
/** Every file extension readModel reads. */
export const MODEL_EXTENSIONS = [...MESH_EXTENSIONS, ...GLTF_EXTENSIONS];
/** Every file extension writeModel writes. */
export const OUTPUT_EXTENSIONS = ['obj', 'glb'];

/** True when a file name ends in one of MODEL_EXTENSIONS. @param {unknown} name @returns {boolean} */
export function isModelName(name) {
  return MODEL_EXTENSIONS.includes((String(name).split('.').pop() ?? '').toLowerCase());
}

// What starts a file of each text format, after leading whitespace (the C++ readers' own detection,
// cpp/core/mesh/mesh_io.cpp sniff(), which reads a file without a known extension the same way).
const OFF_STARTS = ['OFF', 'COFF', 'NOFF', 'CNOFF', 'STOFF'];
const SPACES = [9, 10, 11, 12, 13, 32];
const OBJ_STARTS = ['v ', 'v\t', 'f ', '#', 'o ', 'g ', 'mtllib', 'vn ', 'vt '];

/**
 * The model format of a file's content, for a file whose name says none (a URL such as /api/model/17): 'glb'
 * (its magic), 'gltf' (a JSON object), 'ply', 'off', 'stl' (ASCII "solid", or a binary STL's exact size) or
 * 'obj'; null when it is none of them.
 * @param {Uint8Array} bytes
 * @returns {'glb'|'gltf'|'ply'|'off'|'stl'|'obj'|null}
 */
export function modelFormatOf(bytes) {
  if (bytes.length >= 12 && bytes[0] === 0x67 && bytes[1] === 0x6c && bytes[2] === 0x54 && bytes[3] === 0x46) return 'glb';
  let i = 0;
  while (i < bytes.length && SPACES.includes(bytes[i])) ++i;
  const head = String.fromCharCode(...bytes.subarray(i, i + 8));
  if (head.startsWith('{')) return 'gltf';
  if (/^ply(\r|\n|$)/.test(head)) return 'ply';
  if (OFF_STARTS.some((s) => head.startsWith(s))) return 'off';
  const binaryStl = bytes.length >= 84 && 84 + 50 * new DataView(bytes.buffer, bytes.byteOffset + 80, 4).getUint32(0, true) === bytes.length;
  if (/^solid(\s|$)/i.test(head) || binaryStl) return 'stl';
  if (OBJ_STARTS.some((s) => head.startsWith(s))) return 'obj';
  return null;
}
