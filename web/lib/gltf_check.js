// @ts-check
// Checks of a glTF document's JSON against its own resources, made before anything reads or allocates from it
// (gltf.js): every index points at something, every accessor fits inside its buffer view and every view inside
// its buffer, counts stay below fixed limits, the node graph is a forest, and no extension is required that
// cannot be read. Every problem is an InputError (code parse_error) naming the file and the object.

import { InputError } from './errors.js';
import { checkNodeTransform } from './gltf_node_transform.js';
import { checkGltfReferences } from './gltf_refs.js';
import { checkRestShapeJson } from './gltf_rest_shape.js';

/** Geometry compressions whose decoders are not bundled: a file that requires one is refused by name. */
export const COMPRESSION_EXTENSIONS = ['KHR_draco_mesh_compression', 'EXT_meshopt_compression', 'KHR_meshopt_compression'];

// Elements of all accessors together: 2^27 (134M numbers' worth of vertices); a real model is far below it,
// and an attacker's count stops here before any array is made.
const MAX_ELEMENTS = 2 ** 27;
const MAX_ITEMS = 2 ** 20; // nodes, meshes, primitives, accessors, views... each
// Objects of all lists together (accessors, views, nodes, meshes, primitives, materials, animation channels...):
// glTF-Transform builds a graph object of some kilobytes and tens of microseconds for each, so 2^17 is about
// 3 s and 500 MB, where a million unused accessors took 40 s and 3 GB. Real models have thousands.
export const MAX_GLTF_OBJECTS = 2 ** 17;
/** @type {Record<string, number>} bytes per component, by componentType (undefined: not one glTF has) */
const COMPONENT_BYTES = { 5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4 };
/** @type {Record<string, number>} components per element, by type (undefined: not one glTF has) */
const TYPE_COMPONENTS = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4, MAT2: 4, MAT3: 9, MAT4: 16 };
const INDEX_TYPES = [5121, 5123, 5125];
const POSITION_TYPES = [5126, 5120, 5121, 5122, 5123]; // float, or integers (KHR_mesh_quantization)

/**
 * @param {any} value
 * @param {number} length
 * @returns {boolean}
 */
function isIndex(value, length) {
  return Number.isInteger(value) && value >= 0 && value < length;
}

/**
 * @param {any} value
 * @param {number} max
 * @returns {boolean}
 */
function isCount(value, max) {
  return Number.isInteger(value) && value >= 0 && value <= max;
}

const LISTS = ['buffers', 'bufferViews', 'accessors', 'meshes', 'nodes', 'scenes', 'images', 'textures', 'materials', 'samplers',
  'skins', 'animations', 'cameras'];

/**
 * Throws an InputError naming the file and the problem; never returns. The JSON it checks is the file's
 * own, untrusted and of any shape: the checks below take its parts as `any` and look at every field.
 * @typedef {(message: string) => never} Fail
 */

/**
 * @param {string} filename
 * @returns {Fail}
 */
function failure(filename) {
  return (message) => {
    throw new InputError(`${filename}: ${message}`, { code: 'parse_error' });
  };
}

/**
 * The document's shape, before its resources are looked at: an object of a 2.x version whose lists are arrays
 * of objects, requiring no extension that cannot be read.
 * @param {any} json
 * @param {string} filename
 */
export function checkGltfShape(json, filename) {
  /** @type {Fail} */
  const fail = failure(filename);
  if (!json || typeof json !== 'object' || Array.isArray(json)) fail('the glTF JSON must be an object');
  const version = json.asset?.version;
  if (typeof version !== 'string' || !version.startsWith('2.')) fail(`glTF version ${JSON.stringify(version)} (only 2.x is supported)`);
  checkExtensions(json, fail);
  for (const key of LISTS) {
    const value = json[key];
    if (value !== undefined && (!Array.isArray(value) || value.length > MAX_ITEMS || value.some((v) => !v || typeof v !== 'object'))) {
      fail(`"${key}" must be an array of at most ${MAX_ITEMS} objects`);
    }
  }
  const objects = countObjects(json);
  if (objects > MAX_GLTF_OBJECTS) {
    fail(`it declares ${objects} objects (accessors, buffer views, nodes, meshes, primitives, materials...): more than ` +
      `the ${MAX_GLTF_OBJECTS} a model may have here`);
  }
}

/**
 * The objects of every list, with the meshes' primitives and the animations' channels and samplers.
 * @param {any} json
 * @returns {number}
 */
function countObjects(json) {
  let count = 0;
  for (const key of LISTS) count += json[key]?.length ?? 0;
  for (const mesh of json.meshes ?? []) count += Array.isArray(mesh.primitives) ? mesh.primitives.length : 0;
  for (const a of json.animations ?? []) count += (Array.isArray(a.channels) ? a.channels.length : 0) + (Array.isArray(a.samplers) ? a.samplers.length : 0);
  return count;
}

/**
 * Throws an InputError naming the first problem (checkGltfShape's, then the resources'). `resources`: the bytes
 * of each buffer by the name gltf.js gave it (buffer.uri, or '@glb.bin' for the .glb's own chunk).
 * @param {any} json
 * @param {Record<string, Uint8Array>} resources
 * @param {string} filename
 */
export function checkGltfJson(json, resources, filename) {
  /** @type {Fail} */
  const fail = failure(filename);
  checkGltfShape(json, filename);
  /** @type {(key: string) => any[]} */
  const list = (key) => json[key] ?? [];
  const buffers = list('buffers'), views = list('bufferViews'), accessors = list('accessors');
  const bufferBytes = buffers.map((b, i) => checkBuffer(b, i, resources, fail));
  views.forEach((view, i) => checkView(view, i, bufferBytes, fail));
  let elements = 0;
  accessors.forEach((accessor, i) => {
    elements += checkAccessor(accessor, i, views, fail);
    if (elements > MAX_ELEMENTS) fail(`the accessors hold more than ${MAX_ELEMENTS} elements together: too large to load`);
  });
  accessors.forEach((accessor, i) => {
    if (accessor.sparse !== undefined) checkSparseIndices(accessor, i, views, (b) => resources[buffers[b].uri ?? '@glb.bin'], fail);
  });
  checkMeshes(list('meshes'), accessors, views, fail);
  const parent = checkNodes(list('nodes'), list('meshes').length, fail);
  checkRestShapeJson(json, fail);
  list('scenes').forEach((scene, i) => checkScene(scene, i, parent, fail));
  if (json.scene !== undefined && !isIndex(json.scene, list('scenes').length)) fail(`the default scene ${json.scene} does not exist`);
  list('images').forEach((image, i) => {
    if (image.bufferView !== undefined && !isIndex(image.bufferView, views.length)) fail(`image ${i} refers to a buffer view that does not exist`);
  });
  checkGltfReferences(json, fail);
}

/**
 * @param {any} json
 * @param {Fail} fail
 */
function checkExtensions(json, fail) {
  const required = json.extensionsRequired ?? [];
  if (!Array.isArray(required)) fail('"extensionsRequired" must be an array');
  const compressed = required.filter((name) => COMPRESSION_EXTENSIONS.includes(name));
  if (compressed.length) {
    fail(`its geometry is compressed (${compressed.join(', ')}), which this reader does not decode: export it without ` +
      'mesh compression (in three.js GLTFExporter, or Blender\'s glTF exporter with compression off)');
  }
}

/**
 * The bytes a buffer really has (its resource), which must cover its declared byteLength.
 * @param {any} buffer
 * @param {number} i
 * @param {Record<string, Uint8Array>} resources
 * @param {Fail} fail
 * @returns {number}
 */
function checkBuffer(buffer, i, resources, fail) {
  if (!isCount(buffer.byteLength, 2 ** 31)) fail(`buffer ${i} has byteLength ${JSON.stringify(buffer.byteLength)} (a count of bytes up to 2^31)`);
  const data = resources[buffer.uri ?? '@glb.bin'];
  if (!data) fail(`buffer ${i} has no data`);
  if (data.byteLength < buffer.byteLength) {
    fail(`buffer ${i} declares ${buffer.byteLength} bytes but holds ${data.byteLength} (truncated)`);
  }
  return buffer.byteLength;
}

/**
 * @param {any} view
 * @param {number} i
 * @param {number[]} bufferBytes
 * @param {Fail} fail
 */
function checkView(view, i, bufferBytes, fail) {
  if (!isIndex(view.buffer, bufferBytes.length)) fail(`buffer view ${i} refers to buffer ${JSON.stringify(view.buffer)}, which does not exist`);
  const offset = view.byteOffset ?? 0;
  if (!isCount(offset, 2 ** 31) || !isCount(view.byteLength, 2 ** 31) || offset + view.byteLength > bufferBytes[view.buffer]) {
    fail(`buffer view ${i} (bytes ${offset} to ${offset + view.byteLength}) lies outside buffer ${view.buffer} ` +
      `(${bufferBytes[view.buffer]} bytes)`);
  }
  if (view.byteStride !== undefined && !(Number.isInteger(view.byteStride) && view.byteStride >= 4 && view.byteStride <= 252 && view.byteStride % 4 === 0)) {
    fail(`buffer view ${i} has byteStride ${JSON.stringify(view.byteStride)} (a multiple of 4 from 4 to 252)`);
  }
}

/**
 * The accessor's elements fit in their view (and so in the buffer); returns its element count.
 * @param {any} accessor
 * @param {number} i
 * @param {any[]} views
 * @param {Fail} fail
 * @returns {number}
 */
function checkAccessor(accessor, i, views, fail) {
  const componentBytes = COMPONENT_BYTES[accessor.componentType];
  const components = TYPE_COMPONENTS[accessor.type];
  if (!componentBytes) fail(`accessor ${i} has componentType ${JSON.stringify(accessor.componentType)}`);
  if (!components) fail(`accessor ${i} has type ${JSON.stringify(accessor.type)}`);
  if (!isCount(accessor.count, MAX_ELEMENTS) || accessor.count < 1) {
    fail(`accessor ${i} has count ${JSON.stringify(accessor.count)} (from 1 to ${MAX_ELEMENTS})`);
  }
  const elementBytes = componentBytes * components;
  if (accessor.bufferView !== undefined) {
    if (!isIndex(accessor.bufferView, views.length)) fail(`accessor ${i} refers to buffer view ${JSON.stringify(accessor.bufferView)}, which does not exist`);
    const view = views[accessor.bufferView];
    const offset = accessor.byteOffset ?? 0;
    const stride = view.byteStride ?? elementBytes;
    // A stride below the element's size would make consecutive elements overlap (and readers disagree).
    if (stride < elementBytes) {
      fail(`accessor ${i} (${accessor.type} of ${elementBytes} bytes) does not fit in the byteStride ${stride} of buffer view ${accessor.bufferView}`);
    }
    if (!isCount(offset, 2 ** 31) || offset + (accessor.count - 1) * stride + elementBytes > view.byteLength) {
      fail(`accessor ${i} (${accessor.count} x ${accessor.type}) does not fit in buffer view ${accessor.bufferView} ` +
        `(${view.byteLength} bytes)`);
    }
  }
  if (accessor.sparse !== undefined) checkSparse(accessor, i, views, fail);
  return accessor.count;
}

/**
 * @param {any} accessor
 * @param {number} i
 * @param {any[]} views
 * @param {Fail} fail
 */
function checkSparse(accessor, i, views, fail) {
  const { count, indices, values } = accessor.sparse ?? {};
  if (!isCount(count, accessor.count) || count < 1) fail(`accessor ${i} has a sparse count of ${JSON.stringify(count)}`);
  /** @type {(part: any, bytes: number) => boolean} */
  const fits = (part, bytes) => part && isIndex(part.bufferView, views.length) && isCount(part.byteOffset ?? 0, 2 ** 31) &&
    (part.byteOffset ?? 0) + count * bytes <= views[part.bufferView].byteLength;
  if (!INDEX_TYPES.includes(indices?.componentType) || !fits(indices, COMPONENT_BYTES[indices.componentType])) {
    fail(`accessor ${i}: its sparse indices do not fit in their buffer view`);
  }
  if (!fits(values, COMPONENT_BYTES[accessor.componentType] * TYPE_COMPONENTS[accessor.type])) {
    fail(`accessor ${i}: its sparse values do not fit in their buffer view`);
  }
}

/**
 * Each sparse index names an element of its accessor (glTF: below count, increasing); glTF-Transform would
 * otherwise write past the end of the array it builds, silently.
 * @param {any} accessor
 * @param {number} i
 * @param {any[]} views
 * @param {(buffer: number) => Uint8Array} bufferData
 * @param {Fail} fail
 */
function checkSparseIndices(accessor, i, views, bufferData, fail) {
  const { count, indices } = accessor.sparse;
  const view = views[indices.bufferView];
  const data = bufferData(view.buffer);
  const bytes = COMPONENT_BYTES[indices.componentType];
  const dataView = new DataView(data.buffer, data.byteOffset + (view.byteOffset ?? 0) + (indices.byteOffset ?? 0), count * bytes);
  /** @type {(k: number) => number} */
  const read = bytes === 1 ? (k) => dataView.getUint8(k) : bytes === 2 ? (k) => dataView.getUint16(2 * k, true) : (k) => dataView.getUint32(4 * k, true);
  let previous = -1;
  for (let k = 0; k < count; ++k) {
    const index = read(k);
    if (index >= accessor.count) fail(`accessor ${i}: sparse index ${index} >= count ${accessor.count}`);
    if (index <= previous) fail(`accessor ${i}: sparse index ${index} follows ${previous} (they must increase)`);
    previous = index;
  }
}

/**
 * A primitive's element count fits its mode: TRIANGLES takes whole triangles (glTF: count % 3 == 0, where a
 * reader would drop or misread the rest).
 * @param {any} primitive
 * @param {string} where
 * @param {any[]} accessors
 * @param {any[]} views
 * @param {Fail} fail
 */
function checkPrimitiveCount(primitive, where, accessors, views, fail) {
  const mode = primitive.mode ?? 4;
  const indices = primitive.indices === undefined ? undefined : accessors[primitive.indices];
  if (indices && indices.bufferView !== undefined && views[indices.bufferView].byteStride !== undefined) {
    fail(`${where}: its indices (accessor ${primitive.indices}) lie in buffer view ${indices.bufferView}, which has a byteStride ` +
      '(index data must be tightly packed)');
  }
  const count = indices ? indices.count : accessors[primitive.attributes.POSITION].count;
  if (mode === 4 && count % 3 !== 0) {
    fail(`${where}: ${count} ${indices ? 'indices' : 'vertices without indices'} for triangles (not a multiple of 3)`);
  }
}

/**
 * @param {any[]} meshes
 * @param {any[]} accessors
 * @param {any[]} views
 * @param {Fail} fail
 */
function checkMeshes(meshes, accessors, views, fail) {
  meshes.forEach((mesh, m) => {
    if (!Array.isArray(mesh.primitives) || mesh.primitives.length === 0) fail(`mesh ${m} has no primitives`);
    mesh.primitives.forEach((/** @type {any} */ primitive, /** @type {number} */ p) => {
      const where = `mesh ${m} primitive ${p}`;
      if (!primitive || typeof primitive !== 'object' || !primitive.attributes || typeof primitive.attributes !== 'object') {
        fail(`${where} has no attributes`);
      }
      const mode = primitive.mode ?? 4;
      if (!(Number.isInteger(mode) && mode >= 0 && mode <= 6)) fail(`${where} has mode ${JSON.stringify(mode)}`);
      for (const [name, index] of Object.entries(primitive.attributes)) {
        if (!isIndex(index, accessors.length)) fail(`${where}: attribute ${name} refers to accessor ${JSON.stringify(index)}, which does not exist`);
      }
      const position = accessors[primitive.attributes.POSITION];
      if (!position) fail(`${where} has no POSITION`);
      if (position.type !== 'VEC3' || !POSITION_TYPES.includes(position.componentType)) fail(`${where}: POSITION must be VEC3 float or integer`);
      if (primitive.indices !== undefined) {
        const indices = accessors[primitive.indices];
        if (!indices || indices.type !== 'SCALAR' || !INDEX_TYPES.includes(indices.componentType)) {
          fail(`${where}: indices must be a SCALAR accessor of unsigned integers`);
        }
      }
      checkPrimitiveCount(primitive, where, accessors, views, fail);
    });
  });
}

/**
 * A scene lists root nodes, each once (as glTF requires): else a subtree would be read, and its vertices
 * counted, once per listing.
 * @param {any} scene
 * @param {number} i
 * @param {number[]} parent
 * @param {Fail} fail
 */
function checkScene(scene, i, parent, fail) {
  if (scene.nodes === undefined) return;
  if (!Array.isArray(scene.nodes) || !scene.nodes.every((/** @type {unknown} */ n) => isIndex(n, parent.length))) fail(`scene ${i} lists a node that does not exist`);
  const seen = new Set();
  for (const n of scene.nodes) {
    if (seen.has(n)) fail(`scene ${i} lists node ${n} twice`);
    if (parent[n] >= 0) fail(`scene ${i} lists node ${n}, which is not a root (it is a child of node ${parent[n]})`);
    seen.add(n);
  }
}

/**
 * Every node has at most one parent and no node is its own ancestor (a loop would never end a traversal).
 * Returns each node's parent (-1: a root).
 * @param {any[]} nodes
 * @param {number} meshCount
 * @param {Fail} fail
 * @returns {number[]}
 */
function checkNodes(nodes, meshCount, fail) {
  const parent = new Array(nodes.length).fill(-1);
  nodes.forEach((node, i) => {
    if (node.mesh !== undefined && !isIndex(node.mesh, meshCount)) fail(`node ${i} refers to mesh ${JSON.stringify(node.mesh)}, which does not exist`);
    if (node.matrix !== undefined && !(Array.isArray(node.matrix) && node.matrix.length === 16 && node.matrix.every(Number.isFinite))) {
      fail(`node ${i} has a matrix that is not 16 finite numbers`);
    }
    for (const [key, length] of [['translation', 3], ['rotation', 4], ['scale', 3]]) {
      const v = node[key];
      if (v !== undefined && !(Array.isArray(v) && v.length === length && v.every(Number.isFinite))) fail(`node ${i} has a ${key} that is not ${length} finite numbers`);
    }
    checkNodeTransform(node, i, fail);
    const children = node.children ?? [];
    if (!Array.isArray(children)) fail(`node ${i} has children that are not an array`);
    for (const child of children) {
      if (!isIndex(child, nodes.length)) fail(`node ${i} has child ${JSON.stringify(child)}, which does not exist`);
      if (parent[child] >= 0) fail(`node ${child} is the child of both node ${parent[child]} and node ${i}`);
      parent[child] = i;
    }
  });
  // Walk up from each node until a node already known to reach a root; meeting this walk's own path again is
  // a loop. Each node is walked once: O(#nodes).
  const mark = new Int32Array(nodes.length); // 0: unknown, -1: reaches a root, i + 1: on the walk from i
  nodes.forEach((_, i) => {
    const path = [];
    let n = /** @type {number} */ (i);
    while (n >= 0 && mark[n] === 0) {
      mark[n] = i + 1;
      path.push(n);
      n = parent[n];
    }
    if (n >= 0 && mark[n] === i + 1) fail(`node ${n} is its own ancestor (the node hierarchy loops)`);
    for (const p of path) mark[p] = -1;
  });
  return parent;
}
