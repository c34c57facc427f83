// @ts-check
// A read glTF model written back as .glb (gltf.js reads it): each instance's POSITION replaced by its
// deformed positions in its node's space, NORMAL (where the file has one) by normals of the deformed surface and
// TANGENT turned with it (gltf_tangents.js),
// everything else -- materials, textures, UVs, colours, nodes, animations, extensions, extras, cameras -- as it was;
// extensions glTF-Transform does not know are put back on the objects whose order it keeps (gltf_unknown.js), and
// are lost on textures, samplers, accessors and texture references (readGltf's warning names them).
//   - A mesh used by several nodes deforms per instance: each node whose new shape differs from the other
//     instances' gets its own copy of the mesh (the primitives copied, sharing UVs, indices and materials).
//   - The model is the default scene's nodes (readGltf's instances): a node elsewhere (in another scene, or in
//     none) that uses a deformed mesh keeps it as it was, on a copy of the mesh made before anything is written.
//   - A node whose transform is singular (a scale with a zero: valid glTF, used to hide an object) has no
//     node space to write deformed positions into; its instance keeps the file's own positions and normals.
//   - No NaN or infinity is written: the positions are checked, and coordinates that would pass float32's range
//     (glTF stores float32) in their node's space are refused, naming the vertex, rather than written as
//     infinity or silently replaced by the file's own.
import { Document, WebIO } from '@gltf-transform/core';
import { InputError } from './errors.js';
import { gltfIO } from './gltf_io.js';
import { inverseAffine, normalTransform, transformPoint } from './gltf_space.js';
import { collectingLogger, editGlbJson, restoreUnknown } from './gltf_unknown.js';
import { turnedTangents } from './gltf_tangents.js';
import { layoutNormals } from './normals.js';

// glTF-Transform's types, for the functions of this file that no declaration exports (gltf_io.js says why): an
// @import, unlike a @typedef, is not exported with the declarations (nor is a mesh's variant, { mesh, parts }).
/** @import { Root, Mesh, Buffer as GltfBuffer, Primitive, Accessor } from '@gltf-transform/core' */
/** @import { GltfInstance } from './gltf.js' */
/** @typedef {{ primitive: number, position: Float32Array|null, normal: Float32Array|null }} PartShape  a primitive's new local data (null: keep the file's) */
/** @typedef {{ node: number, mesh: number, parts: PartShape[] }} NodeShape */

/**
 * @param {unknown} positions
 * @param {number} count
 * @param {string} what
 * @returns {asserts positions is Float64Array}
 */
function assertFinite(positions, count, what) {
  if (!(positions instanceof Float64Array) || positions.length !== 3 * count) {
    throw new InputError(`${what}: positions must be a Float64Array of 3 x ${count} numbers`);
  }
  const bad = positions.findIndex((x) => !Number.isFinite(x));
  if (bad >= 0) throw new InputError(`${what}: vertex ${Math.floor(bad / 3)} has a position that is not finite (${positions[bad]})`);
}

/** The largest float32: a coordinate beyond it would be stored as infinity. */
const FLOAT32_MAX = 3.4028234663852886e38;

/**
 * Throws an InputError naming the first coordinate of `values` (float64) that float32 cannot hold.
 * @param {ArrayLike<number>} values 3 per vertex
 * @param {string} what e.g. 'meshToGlb', or the instance
 * @param {number} [first] the file vertex of values[0..2]
 */
function assertFitsFloat32(values, what, first = 0) {
  for (let i = 0; i < values.length; ++i) {
    // Written so that NaN fails too (every comparison with NaN is false): a NaN can come from the node's inverse
    // transform (an overflow to infinity times zero) although the scene-space positions were finite.
    if (!(Math.abs(values[i]) <= FLOAT32_MAX)) {
      const vertex = first + Math.floor(i / 3);
      if (Number.isNaN(values[i])) throw new InputError(`${what}: vertex ${vertex} has the coordinate NaN (not a number), which glTF cannot store`);
      throw new InputError(`${what}: vertex ${vertex} has the coordinate ${values[i]}, beyond float32's ` +
        `range (${FLOAT32_MAX.toPrecision(5)}) that glTF stores: it would be written as infinity (write .obj, which keeps double precision)`);
    }
  }
}

/**
 * The model written back as .glb (see the top).
 * @param {import('./gltf.js').GltfModel} model from readGltf
 * @param {Float64Array} positions the deformed file vertices, in scene space
 * @param {Uint32Array} indices the file's triangles (readGltf's mesh.indices)
 * @param {{ solverOfFile?: Int32Array }} [options] welded points (Deformer.layout()); none: every vertex its own
 * @returns {Promise<Uint8Array>}
 */
export async function writeGltf(model, positions, indices, { solverOfFile } = {}) {
  assertFinite(positions, model.instances.reduce((sum, i) => sum + i.count, 0), 'writeGltf');
  // The model as readGltf gave it: its JSON passed checkGltfJson, and its resources are no shared memory. What
  // glTF-Transform logs about it, readGltf reported already.
  const document = await gltfIO(collectingLogger()).readJSON({ json: /** @type {any} */ (structuredClone(model.json)),
    resources: /** @type {Record<string, Uint8Array<ArrayBuffer>>} */ (model.resources) });
  const normals = layoutNormals(positions, indices, { solverOfFile, restNormals: model.restNormals });
  const root = document.getRoot();
  const buffer = root.listBuffers()[0] ?? document.createBuffer();
  const copies = keepOthersAsRead(root, model.instances);
  const variants = placeShapes(root, nodeShapes(root, model.instances, positions, normals), copies);
  /** @type {Set<Accessor|null>} */
  const replaced = new Set();
  for (const { mesh, parts } of variants) {
    const primitives = mesh.listPrimitives();
    for (const part of parts) {
      const primitive = primitives[part.primitive];
      // The tangents first: they are turned by the change from the primitive's rest POSITION.
      const tangent = primitive.getAttribute('TANGENT');
      if (part.position && part.normal && tangent?.getType() === 'VEC4' && 3 * tangent.getCount() === part.position.length) {
        replaced.add(replaceAttribute(document, buffer, primitive, 'TANGENT', turnedTangents(primitive, part.position, part.normal), 'VEC4'));
      }
      if (part.position) replaced.add(replaceAttribute(document, buffer, primitive, 'POSITION', part.position));
      if (part.normal) replaced.add(replaceAttribute(document, buffer, primitive, 'NORMAL', part.normal));
    }
  }
  // An old accessor is dropped once nothing else (a kept instance, a morph target) uses it: no stale copy.
  for (const old of replaced) if (old && !old.listParents().some((p) => p.propertyType !== 'Root')) old.dispose();
  for (const extra of root.listBuffers().slice(1)) {
    for (const accessor of root.listAccessors()) if (accessor.getBuffer() === extra) accessor.setBuffer(buffer);
    extra.dispose();
  }
  const bytes = await gltfIO(collectingLogger()).writeBinary(document);
  return editGlbJson(bytes, (json) => restoreUnknown(model.json, json, copies));
}

/**
 * Each node's new shape (without nodes: each mesh's): its mesh and, per triangle primitive, the new local
 * positions and normals (null: keep the file's).
 * @param {Root} root
 * @param {GltfInstance[]} instances
 * @param {Float64Array} positions
 * @param {Float32Array} normals
 * @returns {NodeShape[]}
 */
function nodeShapes(root, instances, positions, normals) {
  const meshes = root.listMeshes();
  /** @type {Map<number, NodeShape>} */
  const shapes = new Map();
  for (const instance of instances) {
    const key = instance.node >= 0 ? instance.node : -1 - instance.mesh;
    const shape = shapes.get(key) ?? { node: instance.node, mesh: instance.mesh, parts: [] };
    shapes.set(key, shape);
    const hasNormal = !!meshes[instance.mesh].listPrimitives()[instance.primitive].getAttribute('NORMAL');
    shape.parts.push({ primitive: instance.primitive, ...localShape(instance, positions, hasNormal ? normals : null) });
  }
  return [...shapes.values()];
}

/**
 * One instance's positions (and normals) in its node's space, or nulls where they cannot be expressed there.
 * @param {GltfInstance} instance
 * @param {Float64Array} positions
 * @param {Float32Array|null} normals
 * @returns {{ position: Float32Array|null, normal: Float32Array|null }}
 */
function localShape(instance, positions, normals) {
  const inverse = inverseAffine(instance.matrix);
  if (!inverse) return { position: null, normal: null };
  const position = new Float32Array(3 * instance.count), normal = normals ? new Float32Array(3 * instance.count) : null;
  const scratch = new Float64Array(3);
  const where = `writeGltf: node ${instance.node} (mesh ${instance.mesh}, primitive ${instance.primitive}), in its node's space`;
  for (let v = 0; v < instance.count; ++v) {
    const p = 3 * (instance.start + v);
    transformPoint(inverse, positions[p], positions[p + 1], positions[p + 2], scratch, 0);
    assertFitsFloat32(scratch, where, instance.start + v);
    position.set(scratch, 3 * v);
    if (normal && normals) normal.set(normalTransform(inverse, normals[p], normals[p + 1], normals[p + 2]), 3 * v);
  }
  if (normal && !normal.every(Number.isFinite)) return { position, normal: null };  // the positions are checked above
  return { position, normal };
}

/**
 * Moves each node outside the model (not one of the default scene's instances) that uses a mesh the model
 * deforms onto a copy of that mesh, one copy per mesh, made before anything is written: such a node is not part
 * of what was read and deformed (another scene's view of the mesh, or an unused node), so it keeps the file's
 * shape. Returns, for each copy (appended to the document's meshes in order), the index of the mesh it copies.
 * @param {Root} root
 * @param {GltfInstance[]} instances
 * @returns {number[]}
 */
function keepOthersAsRead(root, instances) {
  const meshes = root.listMeshes();
  const inModel = new Set(instances.map((i) => i.node));
  const deformed = new Set(instances.map((i) => i.mesh));
  /** @type {Map<number, Mesh>} */
  const kept = new Map();
  /** @type {number[]} */
  const copies = [];
  root.listNodes().forEach((node, n) => {
    const mesh = node.getMesh();
    const m = mesh ? meshes.indexOf(mesh) : -1;
    if (inModel.has(n) || !deformed.has(m)) return;
    if (!kept.has(m)) {
      kept.set(m, copyMesh(meshes[m]));
      copies.push(m);
    }
    node.setMesh(/** @type {Mesh} */ (kept.get(m)));
  });
  return copies;
}

/**
 * Gives each node the mesh for its shape: the first shape of a mesh keeps the file's mesh, a later one equal
 * to an earlier shares that one's, any other gets a copy (all copies made before anything is written, so
 * each starts from the file's data). Returns the distinct meshes with the shapes to write into them, and
 * appends to `copies`, for each copy (appended to the document's meshes in order), the index of the mesh it copies.
 * @param {Root} root
 * @param {NodeShape[]} shapes
 * @param {number[]} copies
 * @returns {{ mesh: Mesh, parts: PartShape[] }[]}
 */
function placeShapes(root, shapes, copies) {
  const meshes = root.listMeshes(), nodes = root.listNodes();
  /** @type {Map<number, { mesh: Mesh, parts: PartShape[] }[]>} */
  const byMesh = new Map();
  /** @type {{ mesh: Mesh, parts: PartShape[] }[]} */
  const variants = [];
  for (const shape of shapes) {
    const list = byMesh.get(shape.mesh) ?? [];
    byMesh.set(shape.mesh, list);
    let variant = list.find((v) => sameParts(v.parts, shape.parts));
    if (!variant) {
      if (list.length) copies.push(shape.mesh);
      variant = { mesh: list.length ? copyMesh(meshes[shape.mesh]) : meshes[shape.mesh], parts: shape.parts };
      list.push(variant);
      variants.push(variant);
    }
    if (shape.node >= 0) nodes[shape.node].setMesh(variant.mesh);
  }
  return variants;
}

/**
 * @param {PartShape[]} a
 * @param {PartShape[]} b
 * @returns {boolean}
 */
function sameParts(a, b) {
  /** @type {(x: Float32Array|null, y: Float32Array|null) => boolean} */
  const same = (x, y) => x === y || (!!x && !!y && x.length === y.length && x.every((value, i) => Object.is(value, /** @type {Float32Array} */ (y)[i])));
  return a.length === b.length && a.every((part, k) => part.primitive === b[k].primitive &&
    same(part.position, b[k].position) && same(part.normal, b[k].normal));
}

/**
 * A mesh with copies of its primitives (Mesh.clone alone shares them), in order; the copies share the
 * accessors, material and morph targets until an attribute is replaced.
 * @param {Mesh} mesh
 * @returns {Mesh}
 */
function copyMesh(mesh) {
  const copy = mesh.clone();
  for (const primitive of copy.listPrimitives()) {
    copy.removePrimitive(primitive);
    copy.addPrimitive(primitive.clone());
  }
  return copy;
}

/**
 * Sets a new accessor (VEC3 unless said) as the primitive's attribute; returns the old one.
 * @param {Document} document
 * @param {GltfBuffer} buffer
 * @param {Primitive} primitive
 * @param {string} name
 * @param {Float32Array} array
 * @param {'VEC3'|'VEC4'} [type]
 * @returns {Accessor|null}
 */
function replaceAttribute(document, buffer, primitive, name, array, type = 'VEC3') {
  const old = primitive.getAttribute(name);
  primitive.setAttribute(name, document.createAccessor().setType(type).setArray(array).setBuffer(buffer));
  return old;
}

/**
 * A plain .glb of a mesh (positions and triangles, smooth normals): for models that did not come from glTF.
 * @param {import('./mesh.js').MeshData} mesh
 * @param {{ solverOfFile?: Int32Array }} [options]
 * @returns {Promise<Uint8Array>}
 */
export async function meshToGlb(mesh, { solverOfFile } = {}) {
  assertFinite(mesh.positions, mesh.positions.length / 3, 'meshToGlb');
  assertFitsFloat32(mesh.positions, 'meshToGlb');
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
