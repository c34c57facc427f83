// Models as three.js users make them, for the tests of glTF, seams, open meshes and components: three's own
// geometries (whose vertices are split at UV seams and face edges) exported by three's GLTFExporter and
// OBJExporter in Node. GLTFExporter reads its Blob output through FileReader, which Node lacks: the minimal
// stand-in below reads Blobs the same way (the library itself does not need it).
import {
  BoxGeometry, BufferGeometry, Float32BufferAttribute, Group, Mesh, MeshStandardMaterial, Scene, SphereGeometry,
} from 'three';
import { GLTFExporter } from 'three/examples/jsm/exporters/GLTFExporter.js';
import { OBJExporter } from 'three/examples/jsm/exporters/OBJExporter.js';
import { mergeVertices } from 'three/examples/jsm/utils/BufferGeometryUtils.js';

if (typeof globalThis.FileReader === 'undefined') {
  globalThis.FileReader = class {
    readAsArrayBuffer(blob) {
      blob.arrayBuffer().then((buffer) => {
        this.result = buffer;
        this.onloadend?.();
      });
    }
    readAsDataURL(blob) {
      blob.arrayBuffer().then((buffer) => {
        this.result = `data:${blob.type || 'application/octet-stream'};base64,${Buffer.from(buffer).toString('base64')}`;
        this.onloadend?.();
      });
    }
  };
}

/** A .glb of a three.js object (binary GLTFExporter output). @returns {Promise<Uint8Array>} */
export async function exportGlb(object) {
  const result = await new GLTFExporter().parseAsync(object, { binary: true });
  return new Uint8Array(result);
}

/** A .gltf (JSON with its buffer as a data: URI) of a three.js object. @returns {Promise<Uint8Array>} */
export async function exportGltfJson(object) {
  const result = await new GLTFExporter().parseAsync(object, { binary: false });
  return new TextEncoder().encode(JSON.stringify(result));
}

/** OBJ text of a three.js object (OBJExporter: one `v` per vertex of the geometry). */
export function exportObj(object) {
  return new OBJExporter().parse(object);
}

/** A sphere with its UV seam and poles split (three's SphereGeometry: 16 x 12 segments). */
export function seamSphere(radius = 1) {
  return new SphereGeometry(radius, 16, 12);
}

/** The same geometry with its split vertices merged (three's mergeVertices on positions only). */
export function welded(geometry) {
  const positionsOnly = new BufferGeometry();
  positionsOnly.setAttribute('position', geometry.getAttribute('position'));
  positionsOnly.setIndex(geometry.getIndex());
  return mergeVertices(positionsOnly);
}

/** The geometry without the triangles whose centroid satisfies `drop` (holes), same vertices. */
export function withHoles(geometry, drop) {
  const p = geometry.getAttribute('position');
  const index = geometry.getIndex().array;
  const kept = [];
  for (let t = 0; t < index.length; t += 3) {
    const c = [0, 1, 2].map((a) => (p.getComponent(index[t], a) + p.getComponent(index[t + 1], a) + p.getComponent(index[t + 2], a)) / 3);
    if (!drop(c)) kept.push(index[t], index[t + 1], index[t + 2]);
  }
  const out = geometry.clone();
  out.setIndex(kept);
  return out;
}

/** A mesh with a plain material (GLTFExporter needs none, but users always have one). */
export function meshOf(geometry, color = 0x88aacc) {
  return new Mesh(geometry, new MeshStandardMaterial({ color }));
}

/** The non-indexed copy of a geometry: one vertex per corner (flat-shaded exports). */
export function nonIndexed(geometry) {
  return geometry.toNonIndexed();
}

/** A unit box with 2 x 2 x 2 segments (24 + seams: its faces do not share vertices). */
export function segmentedBox() {
  return new BoxGeometry(1, 1, 1, 2, 2, 2);
}

/** A scene of several meshes under transformed nodes (rotation, scale, a mirrored one). */
export function nodeScene() {
  const scene = new Scene();
  const group = new Group();
  group.position.set(0.5, 0, 0);
  group.rotation.set(0.2, 0.4, -0.1);
  group.scale.set(1.5, 1.5, 1.5);
  const a = meshOf(segmentedBox());
  a.position.set(-1, 0, 0);
  const b = meshOf(seamSphere(0.4), 0xcc8844);
  b.position.set(1, 0.2, 0);
  b.scale.set(-1, 1, 1); // mirrored
  group.add(a, b);
  scene.add(group);
  scene.updateMatrixWorld(true);
  return { scene, meshes: [a, b] };
}

/** Scene-space positions of a three.js mesh (its matrixWorld applied), Float64Array. */
export function worldPositions(mesh) {
  mesh.updateMatrixWorld(true);
  const p = mesh.geometry.getAttribute('position');
  const out = new Float64Array(3 * p.count);
  const e = mesh.matrixWorld.elements;
  for (let i = 0; i < p.count; ++i) {
    const x = p.getX(i), y = p.getY(i), z = p.getZ(i);
    out[3 * i] = e[0] * x + e[4] * y + e[8] * z + e[12];
    out[3 * i + 1] = e[1] * x + e[5] * y + e[9] * z + e[13];
    out[3 * i + 2] = e[2] * x + e[6] * y + e[10] * z + e[14];
  }
  return out;
}

export { Float32BufferAttribute, Group, Mesh, Scene };
