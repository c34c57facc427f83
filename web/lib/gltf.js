// @ts-check
// glTF 2.0 models (.glb, and .gltf with embedded buffers or with its files given): read into the library's
// MeshData in the file's own vertex numbering, and written back as .glb with the deformed positions (and
// normals and tangents) in that same layout, everything else -- materials, textures, UVs, colours, nodes, animations,
// extensions -- as it was. Reading and writing use glTF-Transform (@gltf-transform/core and its extensions,
// MIT); everything the file declares is checked first (checkGltfJson), so a malformed file, a missing buffer
// or a huge accessor count is an InputError naming it before anything is allocated.
//
// The file's vertex numbering (what handle indices in a scene refer to; docs/scene-format.md):
//   the default scene's nodes depth-first in the order glTF lists them (scene.nodes, then each node's
//   children), each node that has a mesh contributing its triangle primitives in order, each primitive all the
//   vertices of its POSITION accessor in accessor order. A mesh used by two nodes contributes twice: each
//   instance deforms on its own. Positions are in scene space (node transforms applied); a mirroring
//   transform flips its triangles so that they stay outward. Points and lines are not part of the surface and
//   are skipped (counted in skippedPrimitives). Triangle strips and fans become triangles. A file whose shape as
//   shown differs from that (a posed skin, morph weights, GPU instancing, a sheared matrix) is refused:
//   gltf_rest_shape.js.
import { InputError } from './errors.js';
import { checkGltfJson, checkGltfShape } from './gltf_check.js';
import { resolveResources } from './gltf_resources.js';
import { checkInstancesRestShape } from './gltf_rest_shape.js';
import { IDENTITY, determinant3, inverseAffine, multiply4, normalTransform, transformPoint } from './gltf_space.js';
import { gltfIO } from './gltf_io.js';
import { TRIANGLE_MODES, primitiveTriangles } from './gltf_triangles.js';
import { collectingLogger, readerWarnings } from './gltf_unknown.js';

export { GLTF_EXTENSIONS } from './formats.js';
export { meshToGlb, writeGltf } from './gltf_write.js';

const GLB_MAGIC = 0x46546c67; // 'glTF'
const CHUNK_JSON = 0x4e4f534a;
const CHUNK_BIN = 0x004e4942;
// Vertices of all mesh instances together: 2^24 (16.7 million, 400 MB of positions). A mesh used by many nodes
// counts once per node, so a small file could otherwise ask for gigabytes.
const MAX_INSTANCE_VERTICES = 2 ** 24;

// glTF-Transform's types, for the functions of this file that no declaration exports (gltf_io.js says why): an
// @import, unlike a @typedef, is not exported with the declarations.
/** @import { Document, Node as GltfNode, Primitive, Accessor } from '@gltf-transform/core' */

/**
 * A read glTF model: what writing it back needs. Plain data (it crosses to a worker only as the bytes).
 * @typedef {object} GltfModel
 * @property {object} json the document's JSON (buffers resolved into resources)
 * @property {Record<string, Uint8Array>} resources its binary resources by name
 * @property {GltfInstance[]} instances one per deformed primitive instance, in file-vertex order
 * @property {Float32Array|null} restNormals scene-space normals per file vertex (NaN where a primitive has none)
 * @property {number} skippedPrimitives points and lines, not part of the surface
 * @property {import('./errors.js').Finding[]} warnings what the reader noticed and the caller should say (extensions
 *   it keeps without interpreting them), with codes
 */
/**
 * @typedef {{ node: number, mesh: number, primitive: number, start: number, count: number, matrix: number[] }} GltfInstance
 *   node, mesh, primitive: indices in the file; start, count: its range of file vertices; matrix: the node's
 *   world matrix (column-major 4x4)
 */

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
 * True when the bytes start like a binary glTF (its magic, 'glTF'; a header cut short is still one, and
 * splitGlb says it is truncated rather than the JSON parser quoting its bytes).
 * @param {Uint8Array} bytes
 * @returns {boolean}
 */
export function isGlb(bytes) {
  return bytes.byteLength >= 4 && new DataView(bytes.buffer, bytes.byteOffset, 4).getUint32(0, true) === GLB_MAGIC;
}

/**
 * Whether the bytes are read as a .glb: they start like one, or the name says .glb and they are not JSON text
 * (an empty file, a binary one): splitGlb then says what is wrong with them as a .glb. A .glb that holds JSON
 * is still read as JSON.
 * @param {Uint8Array} bytes
 * @param {string} filename
 */
function readAsGlb(bytes, filename) {
  if (isGlb(bytes)) return true;
  if (!/\.glb$/i.test(filename)) return false;
  // The decoder drops a byte order mark; JSON text starts with '{' after white space.
  return !new TextDecoder().decode(bytes.subarray(0, 64)).trimStart().startsWith('{');
}

/**
 * The JSON and binary chunk of a .glb, checked against its own header.
 * @param {Uint8Array} bytes
 * @param {string} filename
 * @returns {{ text: string, bin: Uint8Array|null }}
 */
function splitGlb(bytes, filename) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (!bytes.byteLength) fail(filename, 'the file is empty');
  if (!isGlb(bytes)) fail(filename, 'not a binary glTF: a .glb starts with the bytes "glTF", and this file does not');
  if (bytes.byteLength < 20) fail(filename, `truncated: a .glb needs at least 20 bytes, its header and a chunk's, and this one has ${bytes.byteLength}`);
  const version = view.getUint32(4, true), length = view.getUint32(8, true);
  if (version !== 2) fail(filename, `glTF binary version ${version} (only 2 is supported)`);
  if (length > bytes.byteLength) fail(filename, `the header says ${length} bytes but the file has ${bytes.byteLength} (truncated)`);
  const chunks = [];
  for (let offset = 12; offset + 8 <= length;) {
    const size = view.getUint32(offset, true), type = view.getUint32(offset + 4, true);
    if (offset + 8 + size > length) fail(filename, `chunk at byte ${offset} runs past the end of the file (${size} bytes)`);
    chunks.push({ type, data: bytes.subarray(offset + 8, offset + 8 + size) });
    offset += 8 + size;
  }
  if (!chunks.length || chunks[0].type !== CHUNK_JSON) fail(filename, 'the first chunk of a .glb must be its JSON');
  const bin = chunks.find((c) => c.type === CHUNK_BIN)?.data ?? null;
  return { text: new TextDecoder().decode(chunks[0].data), bin };
}

/**
 * @param {string} text
 * @param {string} filename
 * @returns {any}
 */
function parseJson(text, filename) {
  try {
    return JSON.parse(text);
  } catch (error) {
    if (!text.trim()) fail(filename, 'the file is empty');
    // Bytes that are not UTF-8 (a binary file named .gltf): the parser's excerpt of them would only be noise.
    if (text.includes('\uFFFD')) fail(filename, 'not valid glTF JSON: not UTF-8 text (a binary file?)');
    return fail(filename, `not valid glTF JSON (${/** @type {Error} */ (error).message})`);
  }
}

/**
 * Reads a .glb or .gltf. `resources`: files a .gltf refers to by name (its .bin, textures), when not embedded.
 * @param {Uint8Array|ArrayBuffer} bytes
 * @param {string} filename
 * @param {{ resources?: Record<string, Uint8Array> }} [options]
 * @returns {Promise<{ mesh: import('./mesh.js').MeshData, gltf: GltfModel }>}
 */
export async function readGltf(bytes, filename, { resources: given } = {}) {
  if (bytes instanceof ArrayBuffer) bytes = new Uint8Array(bytes);
  if (!(bytes instanceof Uint8Array)) throw new InputError('readGltf: bytes must be a Uint8Array or ArrayBuffer');
  const { text, bin } = readAsGlb(bytes, filename) ? splitGlb(bytes, filename) : { text: new TextDecoder().decode(bytes), bin: null };
  const json = parseJson(text, filename);
  checkGltfShape(json, filename);
  const resources = resolveResources(json, bin, given, filename);
  checkGltfJson(json, resources, filename);
  let document;
  const logger = collectingLogger();
  try {
    // The resources' bytes are never shared memory: they are the file's, or decoded from it.
    document = await gltfIO(logger).readJSON({ json: structuredClone(json), resources: /** @type {Record<string, Uint8Array<ArrayBuffer>>} */ (resources) });
  } catch (error) {
    return fail(filename, `glTF that cannot be read (${/** @type {Error} */ (error).message})`);
  }
  const { mesh, ...layout } = readSurface(document, json, filename);
  const warnings = readerWarnings(json, filename, logger.warnings);
  return { mesh, gltf: { json, resources, ...layout, warnings } };
}

/**
 * The instances of the default scene's mesh primitives in file-vertex order (see the top), with node and
 * primitive indices as in the file.
 * @param {Document} document
 * @param {any} json
 * @returns {{ node: number, mesh: number, primitive: number, primitiveObject: Primitive, matrix: number[] }[]}
 *   GltfInstance's indices and matrix with the instance's glTF-Transform primitive
 */
function listInstances(document, json) {
  const root = document.getRoot();
  const nodes = root.listNodes(), meshes = root.listMeshes();
  const nodeIndex = new Map(nodes.map((n, i) => [n, i])), meshIndex = new Map(meshes.map((m, i) => [m, i]));
  /** @type {(map: Map<object, number>, key: object) => number} every node and mesh of the root is in its map */
  const indexOf = (map, key) => /** @type {number} */ (map.get(key));
  const scene = root.getDefaultScene() ?? root.listScenes()[0];
  const roots = scene ? scene.listChildren() : nodes.filter((n) => !n.getParentNode());
  /** @type {{ node: number, mesh: number, primitive: number, primitiveObject: Primitive, matrix: number[] }[]} */
  const instances = [];
  // Depth-first with an explicit stack (a 10,000-deep chain would overflow the call stack), each world matrix
  // from its parent's (getWorldMatrix would walk up from every node: quadratic in the depth).
  /** @type {{ node: GltfNode, parent: number[] }[]} */
  const stack = roots.map((node) => ({ node, parent: IDENTITY })).reverse();
  while (stack.length) {
    const { node, parent } = /** @type {{ node: GltfNode, parent: number[] }} */ (stack.pop());
    const matrix = multiply4(parent, node.getMatrix());
    const mesh = node.getMesh();
    mesh?.listPrimitives().forEach((primitive, p) => {
      instances.push({ node: indexOf(nodeIndex, node), mesh: indexOf(meshIndex, mesh), primitive: p, primitiveObject: primitive, matrix });
    });
    const children = node.listChildren();
    for (let c = children.length - 1; c >= 0; --c) stack.push({ node: children[c], parent: matrix });
  }
  // A document with meshes but no nodes shows each mesh once, untransformed.
  if (!nodes.length && json.meshes?.length) {
    meshes.forEach((mesh, m) => mesh.listPrimitives().forEach((primitive, p) => {
      instances.push({ node: -1, mesh: m, primitive: p, primitiveObject: primitive, matrix: IDENTITY });
    }));
  }
  return instances.filter((i) => TRIANGLE_MODES.includes(i.primitiveObject.getMode()));
}

/**
 * An accessor's elements as float64 (normalised integers decoded as glTF defines them).
 * @param {Accessor} accessor
 * @returns {Float64Array}
 */
function accessorValues(accessor) {
  const array = accessor.getArray();
  const out = new Float64Array(array.length);
  if (!accessor.getNormalized()) {
    out.set(array);
    return out;
  }
  const scale = array instanceof Int8Array ? 127 : array instanceof Uint8Array ? 255 : array instanceof Int16Array ? 32767 : 65535;
  const signed = array instanceof Int8Array || array instanceof Int16Array;
  for (let i = 0; i < array.length; ++i) out[i] = signed ? Math.max(array[i] / scale, -1) : array[i] / scale;
  return out;
}

/**
 * A primitive's POSITION accessor: every primitive has one (checkGltfJson refuses a file without it).
 * @param {Primitive} primitive
 * @returns {Accessor}
 */
function position(primitive) {
  return /** @type {Accessor} */ (primitive.getAttribute('POSITION'));
}

/**
 * The instances' vertices (scene space), triangles and rest normals in file numbering, and the instances as
 * plain data (what the writer and the app need).
 * @param {Document} document
 * @param {any} json
 * @param {string} filename
 * @returns {{ mesh: import('./mesh.js').MeshData, instances: GltfInstance[], restNormals: Float32Array, skippedPrimitives: number }}
 */
function readSurface(document, json, filename) {
  const instances = listInstances(document, json);
  if (!instances.length) fail(filename, 'no triangle mesh in the default scene (points and lines are not surfaces)');
  checkInstancesRestShape(document, json, instances, filename);
  let vertexCount = 0;
  for (const i of instances) vertexCount += position(i.primitiveObject).getCount();
  if (vertexCount > MAX_INSTANCE_VERTICES) {
    fail(filename, `its scene has ${vertexCount} vertices (a mesh counts once per node that uses it): more than the ` +
      `${MAX_INSTANCE_VERTICES} a model may have here`);
  }
  const positions = new Float64Array(3 * vertexCount);
  const restNormals = new Float32Array(3 * vertexCount).fill(NaN);
  /** @type {number[]} */
  const indices = [];
  let start = 0;
  const plain = instances.map((instance) => {
    const primitive = instance.primitiveObject;
    const values = accessorValues(position(primitive));
    const count = values.length / 3;
    const place = placement(instance.matrix);
    for (let v = 0; v < count; ++v) transformPoint(place, values[3 * v], values[3 * v + 1], values[3 * v + 2], positions, 3 * (start + v));
    addTriangles(indices, primitiveTriangles(primitive, count), start, count, instance, filename);
    const normal = primitive.getAttribute('NORMAL');
    if (normal && normal.getCount() === count) {
      const n = accessorValues(normal);
      for (let v = 0; v < count; ++v) restNormals.set(normalTransform(instance.matrix, n[3 * v], n[3 * v + 1], n[3 * v + 2]), 3 * (start + v));
    }
    const out = { node: instance.node, mesh: instance.mesh, primitive: instance.primitive, start, count, matrix: instance.matrix };
    start += count;
    return out;
  });
  const skippedPrimitives = (json.meshes ?? []).reduce((/** @type {number} */ sum, /** @type {any} */ m) =>
    sum + (m.primitives ?? []).filter((/** @type {any} */ p) => (p.mode ?? 4) < 4).length, 0);
  return { mesh: { positions, indices: Uint32Array.from(indices) }, instances: plain, restNormals, skippedPrimitives };
}

/**
 * Where an instance's vertices are read: through its node's world matrix; for a singular one (a scale with a zero:
 * valid glTF, used to hide an object), all at the node's origin. A node flattened on one axis would otherwise
 * give the solver a surface with no volume, pressed onto itself; collapsed to a point, its triangles are left out
 * of the solve and its vertices carried along, as a node scaled by zero on every axis is (docs/library.md).
 * gltf_write.js writes such an instance back with the file's own positions.
 * @param {number[]} matrix
 * @returns {number[]}
 */
function placement(matrix) {
  return inverseAffine(matrix) ? matrix : [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, matrix[12], matrix[13], matrix[14], 1];
}

/**
 * Appends a primitive's triangles in file numbering; a mirroring node transform flips them to stay outward.
 * @param {number[]} indices
 * @param {number[]} triangles
 * @param {number} start
 * @param {number} count
 * @param {{ mesh: number, primitive: number, matrix: number[] }} instance
 * @param {string} filename
 */
function addTriangles(indices, triangles, start, count, instance, filename) {
  const flip = determinant3(instance.matrix) < 0;
  for (let t = 0; t < triangles.length; t += 3) {
    const a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    if (a >= count || b >= count || c >= count) {
      fail(filename, `mesh ${instance.mesh} primitive ${instance.primitive} uses vertex ${Math.max(a, b, c)} of its ${count}`);
    }
    if (flip) indices.push(start + a, start + c, start + b);
    else indices.push(start + a, start + b, start + c);
  }
}
