// @ts-check
// Models as files: every format the library reads (OBJ, OFF, PLY, STL by the C++ readers; glTF 2.0 by gltf.js)
// and writes (OBJ text; .glb). A model keeps what writing it back needs: a glTF's document, so that its
// deformed copy keeps the file's own vertex layout, materials, textures and nodes.
//
//   const model = await readModel(solver, bytes, 'robot.glb');    // { mesh, gltf? }
//   const d = Deformer.create(solver, model.mesh, cage);            // file numbering throughout
//   ... d.solve();
//   const glb = await writeModel(solver, model, d.positions(), 'robot-deformed.glb', { solverOfFile: d.layout().solverOfFile });
import { InputError } from './errors.js';
import { GLTF_EXTENSIONS } from './formats.js';
import { isGlb, meshToGlb, readGltf, writeGltf } from './gltf.js';
import { assertPositions, readMesh, writeObj } from './mesh.js';
import { assertAttached } from './typed_arrays.js';

export { MODEL_EXTENSIONS, OUTPUT_EXTENSIONS } from './formats.js';

/** @typedef {{ mesh: import('./mesh.js').MeshData, gltf?: import('./gltf.js').GltfModel }} Model */

/** @param {string} filename @returns {string} */
function extension(filename) {
  const dot = filename.lastIndexOf('.');
  return dot < 0 ? '' : filename.slice(dot + 1).toLowerCase();
}

/**
 * True for a file name (or bytes) that readModel reads as glTF.
 * @param {string} filename @param {unknown} [bytes] @returns {boolean}
 */
export function isGltfFile(filename, bytes) {
  return GLTF_EXTENSIONS.includes(extension(filename)) || (bytes instanceof Uint8Array && isGlb(bytes));
}

/**
 * Reads a model file. glTF is read here (asynchronously: its images and buffers may need decoding); the other
 * formats by the C++ readers (readMesh).
 * @param {import('./solver_module.js').SolverModule} solver the module from loadSolver()
 * @param {Uint8Array|ArrayBuffer} bytes
 * @param {string} filename for the format and in messages
 * @param {{ resources?: Record<string, Uint8Array> }} [options] files a .gltf refers to by name
 * @returns {Promise<Model>}
 */
export async function readModel(solver, bytes, filename, { resources } = {}) {
  assertAttached(bytes, 'readModel: bytes');
  for (const [name, file] of Object.entries(resources ?? {})) assertAttached(file, `readModel: resources["${name}"]`);
  if (bytes instanceof ArrayBuffer) bytes = new Uint8Array(bytes);
  if (typeof filename !== 'string') throw new InputError('readModel: filename must be a string');
  if (isGltfFile(filename, bytes)) return readGltf(bytes, filename, { resources });
  return { mesh: readMesh(solver, bytes, filename) };
}

/**
 * A model with new positions as a file, chosen by the output name's extension: .obj (text, the file's vertices
 * and faces) or .glb (the model's own glTF with the positions and normals replaced, or a plain one for other
 * sources).
 * @param {import('./solver_module.js').SolverModule} solver
 * @param {Model} model from readModel (or any { mesh })
 * @param {Float64Array} positions 3 per file vertex
 * @param {string} filename the output's name
 * @param {{ solverOfFile?: Int32Array, comment?: string }} [options] solverOfFile: welded points for the
 *   normals (Deformer.layout()); comment: OBJ header lines
 * @returns {Promise<string|Uint8Array>} OBJ text or GLB bytes
 */
export async function writeModel(solver, model, positions, filename, { solverOfFile, comment = '' } = {}) {
  assertPositions(positions, 'writeModel: positions');
  if (positions.length !== model.mesh.positions.length) {
    throw new InputError(`writeModel: ${positions.length / 3} positions for a model of ${model.mesh.positions.length / 3} vertices`);
  }
  const ext = extension(filename);
  if (ext === 'obj') return writeObj(solver, { positions, indices: model.mesh.indices }, comment);
  if (ext === 'glb') {
    if (model.gltf) return writeGltf(model.gltf, positions, model.mesh.indices, { solverOfFile });
    return meshToGlb({ positions, indices: model.mesh.indices }, { solverOfFile });
  }
  throw new InputError(`${filename}: cannot write .${ext} (write .obj, or .glb for glTF: binary glTF holds the whole model in one file)`);
}
