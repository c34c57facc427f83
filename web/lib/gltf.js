// glTF 2.0 models (.glb, and .gltf with embedded buffers or with its files given): read into the library's
// MeshData in the file's own vertex numbering, and written back as .glb with the deformed positions (and
// normals) in that same layout, everything else -- materials, textures, UVs, colours, nodes, animations,
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
//   are skipped (counted in skippedPrimitives). Triangle strips and fans become triangles.
import { Document, WebIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { InputError } from './errors.js';
import { COMPRESSION_EXTENSIONS, checkGltfJson, checkGltfShape } from './gltf_check.js';
import { resolveResources } from './gltf_resources.js';
import { layoutNormals } from './normals.js';

export { GLTF_EXTENSIONS } from './formats.js';

const GLB_MAGIC = 0x46546c67; // 'glTF'
const CHUNK_JSON = 0x4e4f534a;
const CHUNK_BIN = 0x004e4942;
// Vertices of all mesh instances together: 2^24 (16.7 million, 400 MB of positions). A mesh used by many nodes
// counts once per node, so a small file could otherwise ask for gigabytes.
const MAX_INSTANCE_VERTICES = 2 ** 24;
const TRIANGLES = 4, TRIANGLE_STRIP = 5, TRIANGLE_FAN = 6;

/**
 * A read glTF model: what writing it back needs. Plain data (it crosses to a worker only as the bytes).
 * @typedef {object} GltfModel
 * @property {object} json the document's JSON (buffers resolved into resources)
 * @property {Record<string, Uint8Array>} resources its binary resources by name
 * @property {GltfInstance[]} instances one per deformed primitive instance, in file-vertex order
 * @property {Float32Array|null} restNormals scene-space normals per file vertex (NaN where a primitive has none)
 * @property {number} skippedPrimitives points and lines, not part of the surface
 */
/**
 * @typedef {{ node: number, mesh: number, primitive: number, start: number, count: number, matrix: number[] }} GltfInstance
 *   node, mesh, primitive: indices in the file; start, count: its range of file vertices; matrix: the node's
 *   world matrix (column-major 4x4)
 */

function fail(filename, message, code = 'parse_error') {
  throw new InputError(`${filename}: ${message}`, { code });
}

/** True when the bytes start like a binary glTF. */
export function isGlb(bytes) {
  return bytes.byteLength >= 12 && new DataView(bytes.buffer, bytes.byteOffset, 12).getUint32(0, true) === GLB_MAGIC;
}

// The JSON and binary chunk of a .glb, checked against its own header.
function splitGlb(bytes, filename) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (bytes.byteLength < 20) fail(filename, `a .glb needs at least 20 bytes (got ${bytes.byteLength})`);
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

function parseJson(text, filename) {
  try {
    return JSON.parse(text);
  } catch (error) {
    return fail(filename, `not valid glTF JSON (${error.message})`);
  }
}

function io() {
  // Every extension glTF-Transform knows is kept on the way back, except the compressed geometry ones, whose
  // decoders are not bundled (checkGltfJson refuses files that require them).
  const extensions = ALL_EXTENSIONS.filter((e) => !COMPRESSION_EXTENSIONS.includes(e.EXTENSION_NAME));
  return new WebIO().registerExtensions(extensions);
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
  const { text, bin } = isGlb(bytes) ? splitGlb(bytes, filename) : { text: new TextDecoder().decode(bytes), bin: null };
  const json = parseJson(text, filename);
  checkGltfShape(json, filename);
  const resources = resolveResources(json, bin, given, filename);
  checkGltfJson(json, resources, filename);
  let document;
  try {
    document = await io().readJSON({ json: structuredClone(json), resources });
  } catch (error) {
    return fail(filename, `glTF that cannot be read (${error.message})`);
  }
  const { mesh, ...layout } = readSurface(document, json, filename);
  return { mesh, gltf: { json, resources, ...layout } };
}

// The instances of the default scene's mesh primitives in file-vertex order (see the top), with node and
// primitive indices as in the file.
function listInstances(document, json) {
  const root = document.getRoot();
  const nodes = root.listNodes(), meshes = root.listMeshes();
  const nodeIndex = new Map(nodes.map((n, i) => [n, i])), meshIndex = new Map(meshes.map((m, i) => [m, i]));
  const scene = root.getDefaultScene() ?? root.listScenes()[0];
  const roots = scene ? scene.listChildren() : nodes.filter((n) => !n.getParentNode());
  const instances = [];
  // Depth-first with an explicit stack (a 10,000-deep chain would overflow the call stack), each world matrix
  // from its parent's (getWorldMatrix would walk up from every node: quadratic in the depth).
  const stack = roots.map((node) => ({ node, parent: IDENTITY })).reverse();
  while (stack.length) {
    const { node, parent } = stack.pop();
    const matrix = multiply4(parent, node.getMatrix());
    const mesh = node.getMesh();
    mesh?.listPrimitives().forEach((primitive, p) => {
      instances.push({ node: nodeIndex.get(node), mesh: meshIndex.get(mesh), primitive: p, primitiveObject: primitive, matrix });
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
  return instances.filter((i) => [TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN].includes(i.primitiveObject.getMode()));
}

// a * b for column-major 4x4 matrices, as a plain array.
function multiply4(a, b) {
  const out = new Array(16);
  for (let c = 0; c < 4; ++c) {
    for (let r = 0; r < 4; ++r) {
      out[4 * c + r] = a[r] * b[4 * c] + a[4 + r] * b[4 * c + 1] + a[8 + r] * b[4 * c + 2] + a[12 + r] * b[4 * c + 3];
    }
  }
  return out;
}

const IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];

// An accessor's elements as float64 (normalised integers decoded as glTF defines them).
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

function transformPoint(m, x, y, z, out, at) {
  out[at] = m[0] * x + m[4] * y + m[8] * z + m[12];
  out[at + 1] = m[1] * x + m[5] * y + m[9] * z + m[13];
  out[at + 2] = m[2] * x + m[6] * y + m[10] * z + m[14];
}

function determinant3(m) {
  return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[4] * (m[1] * m[10] - m[2] * m[9]) + m[8] * (m[1] * m[6] - m[2] * m[5]);
}

// The triangles of a primitive as vertex indices local to it (strips and fans unrolled, in glTF's orders).
function primitiveTriangles(primitive, count) {
  const indexAccessor = primitive.getIndices();
  const index = indexAccessor ? indexAccessor.getArray() : null;
  const n = index ? index.length : count;
  const at = (k) => (index ? index[k] : k);
  const mode = primitive.getMode();
  const out = [];
  if (mode === TRIANGLES) for (let k = 0; k + 2 < n; k += 3) out.push(at(k), at(k + 1), at(k + 2));
  if (mode === TRIANGLE_STRIP) {
    for (let k = 0; k + 2 < n; ++k) out.push(...(k % 2 ? [at(k + 1), at(k), at(k + 2)] : [at(k), at(k + 1), at(k + 2)]));
  }
  if (mode === TRIANGLE_FAN) for (let k = 1; k + 1 < n; ++k) out.push(at(0), at(k), at(k + 1));
  return out;
}

// The instances' vertices (scene space), triangles and rest normals in file numbering, and the instances as
// plain data (what the writer and the app need).
function readSurface(document, json, filename) {
  const instances = listInstances(document, json);
  if (!instances.length) fail(filename, 'no triangle mesh in the default scene (points and lines are not surfaces)');
  let vertexCount = 0;
  for (const i of instances) vertexCount += i.primitiveObject.getAttribute('POSITION').getCount();
  if (vertexCount > MAX_INSTANCE_VERTICES) {
    fail(filename, `its scene has ${vertexCount} vertices (a mesh counts once per node that uses it): more than the ` +
      `${MAX_INSTANCE_VERTICES} a model may have here`);
  }
  const positions = new Float64Array(3 * vertexCount);
  const restNormals = new Float32Array(3 * vertexCount).fill(NaN);
  const indices = [];
  let start = 0;
  const plain = instances.map((instance) => {
    const primitive = instance.primitiveObject;
    const values = accessorValues(primitive.getAttribute('POSITION'));
    const count = values.length / 3;
    for (let v = 0; v < count; ++v) transformPoint(instance.matrix, values[3 * v], values[3 * v + 1], values[3 * v + 2], positions, 3 * (start + v));
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
  const skippedPrimitives = (json.meshes ?? []).reduce((sum, m) => sum + (m.primitives ?? []).filter((p) => (p.mode ?? 4) < 4).length, 0);
  return { mesh: { positions, indices: Uint32Array.from(indices) }, instances: plain, restNormals, skippedPrimitives };
}

// Appends a primitive's triangles in file numbering; a mirroring node transform flips them to stay outward.
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

// A normal through m's 3x3 part, as normals turn: the inverse transpose (the cofactor matrix divided by the
// determinant; only its sign matters for a direction), normalised.
function normalTransform(m, x, y, z) {
  const c = [
    m[5] * m[10] - m[6] * m[9], m[6] * m[8] - m[4] * m[10], m[4] * m[9] - m[5] * m[8],
    m[2] * m[9] - m[1] * m[10], m[0] * m[10] - m[2] * m[8], m[1] * m[8] - m[0] * m[9],
    m[1] * m[6] - m[2] * m[5], m[2] * m[4] - m[0] * m[6], m[0] * m[5] - m[1] * m[4],
  ];
  const sign = determinant3(m) < 0 ? -1 : 1;
  const nx = c[0] * x + c[3] * y + c[6] * z, ny = c[1] * x + c[4] * y + c[7] * z, nz = c[2] * x + c[5] * y + c[8] * z;
  const length = sign * (Math.hypot(nx, ny, nz) || 1);
  return [nx / length, ny / length, nz / length];
}

/** The inverse of an affine column-major 4x4 matrix (for scene -> node space). */
function inverseAffine(m) {
  const det = determinant3(m);
  const inv = [
    (m[5] * m[10] - m[6] * m[9]) / det, (m[2] * m[9] - m[1] * m[10]) / det, (m[1] * m[6] - m[2] * m[5]) / det, 0,
    (m[6] * m[8] - m[4] * m[10]) / det, (m[0] * m[10] - m[2] * m[8]) / det, (m[2] * m[4] - m[0] * m[6]) / det, 0,
    (m[4] * m[9] - m[5] * m[8]) / det, (m[1] * m[8] - m[0] * m[9]) / det, (m[0] * m[5] - m[1] * m[4]) / det, 0,
    0, 0, 0, 1,
  ];
  for (let r = 0; r < 3; ++r) inv[12 + r] = -(inv[r] * m[12] + inv[4 + r] * m[13] + inv[8 + r] * m[14]);
  return inv;
}

/**
 * The model written back as .glb: each instance's POSITION replaced by the deformed positions (in its node's
 * space), NORMAL (where the file has one) by normals of the deformed surface (normals.js: smooth across
 * welded points, hard where the file's own normals differ); a mesh shared by several nodes is copied so that
 * each instance keeps its own shape. Everything else is written as read.
 * @param {GltfModel} model from readGltf
 * @param {Float64Array} positions the deformed file vertices, in scene space
 * @param {Uint32Array} indices the file's triangles (readGltf's mesh.indices)
 * @param {{ solverOfFile?: Int32Array }} [options] welded points (Deformer.layout()); none: every vertex its own
 * @returns {Promise<Uint8Array>}
 */
export async function writeGltf(model, positions, indices, { solverOfFile } = {}) {
  const document = await io().readJSON({ json: structuredClone(model.json), resources: model.resources });
  const normals = layoutNormals(positions, indices, { solverOfFile, restNormals: model.restNormals });
  const root = document.getRoot();
  const buffer = root.listBuffers()[0] ?? document.createBuffer();
  const nodes = root.listNodes(), meshes = root.listMeshes();
  const copied = new Map(); // mesh index -> the nodes that already hold it
  for (const instance of model.instances) {
    let mesh = meshes[instance.mesh];
    if (instance.node >= 0) {
      const node = nodes[instance.node];
      const holders = copied.get(instance.mesh) ?? new Set();
      if (!holders.has(instance.node) && holders.size > 0 && node.getMesh() === mesh) node.setMesh(mesh.clone());
      holders.add(instance.node);
      copied.set(instance.mesh, holders);
      mesh = node.getMesh();
    }
    const primitive = mesh.listPrimitives()[instance.primitive];
    writeInstance(document, buffer, primitive, instance, positions, normals);
  }
  for (const extra of root.listBuffers().slice(1)) {
    for (const accessor of root.listAccessors()) if (accessor.getBuffer() === extra) accessor.setBuffer(buffer);
    extra.dispose();
  }
  return io().writeBinary(document);
}

// One instance's new POSITION (and NORMAL) accessors, in its node's space.
function writeInstance(document, buffer, primitive, instance, positions, normals) {
  const inverse = inverseAffine(instance.matrix);
  const local = new Float32Array(3 * instance.count);
  const scratch = new Float64Array(3);
  for (let v = 0; v < instance.count; ++v) {
    const p = 3 * (instance.start + v);
    transformPoint(inverse, positions[p], positions[p + 1], positions[p + 2], scratch, 0);
    local.set(scratch, 3 * v);
  }
  replaceAttribute(document, buffer, primitive, 'POSITION', local);
  if (primitive.getAttribute('NORMAL')) {
    const localNormals = new Float32Array(3 * instance.count);
    for (let v = 0; v < instance.count; ++v) {
      const p = 3 * (instance.start + v);
      localNormals.set(normalTransform(inverse, normals[p], normals[p + 1], normals[p + 2]), 3 * v);
    }
    replaceAttribute(document, buffer, primitive, 'NORMAL', localNormals);
  }
}

function replaceAttribute(document, buffer, primitive, name, array) {
  const old = primitive.getAttribute(name);
  primitive.setAttribute(name, document.createAccessor().setType('VEC3').setArray(array).setBuffer(buffer));
  // Dropped once nothing else (another primitive, a morph target) uses it: no stale copy in the file.
  if (old && !old.listParents().some((p) => p.propertyType !== 'Root')) old.dispose();
}

/**
 * A plain .glb of a mesh (positions and triangles, smooth normals): for models that did not come from glTF.
 * @param {import('./mesh.js').MeshData} mesh
 * @param {{ solverOfFile?: Int32Array }} [options]
 * @returns {Promise<Uint8Array>}
 */
export async function meshToGlb(mesh, { solverOfFile } = {}) {
  const document = new Document();
  const buffer = document.createBuffer();
  const normals = layoutNormals(mesh.positions, mesh.indices, { solverOfFile });
  const primitive = document.createPrimitive()
    .setAttribute('POSITION', document.createAccessor().setType('VEC3').setArray(Float32Array.from(mesh.positions)).setBuffer(buffer))
    .setAttribute('NORMAL', document.createAccessor().setType('VEC3').setArray(normals).setBuffer(buffer))
    .setIndices(document.createAccessor().setType('SCALAR').setArray(Uint32Array.from(mesh.indices)).setBuffer(buffer));
  const node = document.createNode('mesh').setMesh(document.createMesh('mesh').addPrimitive(primitive));
  document.createScene('scene').addChild(node);
  return new WebIO().writeBinary(document);
}
