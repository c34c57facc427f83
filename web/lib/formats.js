// The file formats of models, by extension: what the library reads (model_io.js) and writes. A module of its
// own with no imports, so that a page can sort dropped files without loading the readers.

/** Read by the C++ readers (mesh.js readMesh). */
export const MESH_EXTENSIONS = ['obj', 'off', 'ply', 'stl'];
/** Read by gltf.js. */
export const GLTF_EXTENSIONS = ['glb', 'gltf'];
/** Every file extension readModel reads. */
export const MODEL_EXTENSIONS = [...MESH_EXTENSIONS, ...GLTF_EXTENSIONS];
/** Every file extension writeModel writes. */
export const OUTPUT_EXTENSIONS = ['obj', 'glb'];

/** True when a file name ends in one of MODEL_EXTENSIONS. */
export function isModelName(name) {
  return MODEL_EXTENSIONS.includes(String(name).split('.').pop().toLowerCase());
}
