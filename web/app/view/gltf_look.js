// The look of a glTF model -- its own materials, textures, UVs and vertex colours -- from three's GLTFLoader,
// matched to the model's primitive instances (web/lib/gltf.js: node, mesh and primitive indices, and each
// instance's range of file vertices), so that the deformed positions the worker sends can be drawn with it.
// Each instance is drawn in scene space (its node transform is already in the positions), so its three mesh
// sits at the root with an identity transform; skins and morph targets are not applied (the deformation
// replaces the pose).
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { LoadingManager } from 'three';

/**
 * @typedef {{ instance: import('../../lib/gltf.js').GltfInstance, geometry: import('three').BufferGeometry,
 *             material: import('three').Material|import('three').Material[] }} LookPart
 * @typedef {{ parts: LookPart[], dispose: () => void }} GltfLook
 */

// The glTF node index of a loaded object: the nearest ancestor (or itself) the loader associated with a node.
function nodeIndexOf(parser, object) {
  for (let o = object; o; o = o.parent) {
    const association = parser.associations.get(o);
    if (association?.nodes !== undefined) return association.nodes;
  }
  return -1;
}

/**
 * Parses the model's file and pairs each instance with the loaded geometry and material of its primitive.
 * @param {{ name: string, bytes: Uint8Array, resources?: Record<string, Uint8Array> }} file
 * @param {import('../../lib/gltf.js').GltfInstance[]} instances
 * @returns {Promise<GltfLook>}
 */
export async function loadGltfLook(file, instances) {
  // Files a .gltf refers to by name come from what was dropped with it.
  const urls = Object.fromEntries(Object.entries(file.resources ?? {}).map(([name, bytes]) => [name, URL.createObjectURL(new Blob([bytes]))]));
  const manager = new LoadingManager();
  manager.setURLModifier((url) => urls[url] ?? urls[decodeURIComponent(url.split('/').pop())] ?? url); // keyed by uri
  const data = file.bytes.buffer.slice(file.bytes.byteOffset, file.bytes.byteOffset + file.bytes.byteLength);
  const gltf = await new GLTFLoader(manager).parseAsync(data, '');
  const found = new Map(); // 'node/mesh/primitive' -> { geometry, material }
  gltf.scene.traverse((object) => {
    if (!object.isMesh) return;
    const association = gltf.parser.associations.get(object);
    if (association?.meshes === undefined) return;
    found.set(`${nodeIndexOf(gltf.parser, object)}/${association.meshes}/${association.primitives ?? 0}`,
      { geometry: object.geometry, material: object.material });
  });
  const parts = [];
  for (const instance of instances) {
    const match = found.get(`${instance.node}/${instance.mesh}/${instance.primitive}`);
    if (match) parts.push({ instance, ...match });
  }
  return {
    parts,
    dispose() {
      for (const url of Object.values(urls)) URL.revokeObjectURL(url);
      gltf.scene.traverse((object) => object.geometry?.dispose());
    },
  };
}
