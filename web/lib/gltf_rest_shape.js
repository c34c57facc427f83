// @ts-check
// glTF features that make a viewer show another rest shape than the one gltf.js reads (the POSITION accessors
// through the node transforms): a file that uses one is refused (an InputError, code parse_error, naming the node)
// rather than deformed as a surface other than the one shown.
//   - A node matrix that is not a translation, rotation and scale (a shear or a projection): glTF forbids it and
//     readers disagree on it; glTF-Transform would decompose it into another transform.
//   - EXT_mesh_gpu_instancing when required: a viewer draws each instance, and this reader reads the node once.
//     When the file only uses it (with a fallback), the node's own transform is read and its instances are not.
//   - A skinned mesh whose joints pose it elsewhere than its node's transform places it: glTF ignores a skinned
//     node's transform and places the mesh by its joints. At its bind pose, each joint's world matrix times its
//     inverse bind matrix is the node's world matrix, and the mesh is read where it is shown; any other pose is
//     refused (the skin is not evaluated).
//   - Morph targets with default weights that are not zero on POSITION: the shape shown is the base plus the
//     weighted targets (the weights are not applied, and a written file would apply them again).
import { InputError } from './errors.js';
import { IDENTITY, multiply4 } from './gltf_space.js';

/** @import { Document, Node as GltfNode } from '@gltf-transform/core' */

// The largest difference, relative to the larger entry (or 1), between two matrices taken as the same: float32
// matrices of the same transform differ by about 1e-7 of their size.
const SAME_MATRIX = 1e-5;

/**
 * @param {string} filename
 * @returns {(message: string) => never}
 */
function failure(filename) {
  return (message) => {
    throw new InputError(`${filename}: ${message}`, { code: 'parse_error' });
  };
}

/**
 * The JSON's own rules (checkGltfJson calls it): no node matrix but translation, rotation and scale, and no
 * required EXT_mesh_gpu_instancing.
 * @param {any} json checked by checkGltfShape
 * @param {(message: string) => never} fail
 */
export function checkRestShapeJson(json, fail) {
  if ((json.extensionsRequired ?? []).includes('EXT_mesh_gpu_instancing')) {
    fail('it requires EXT_mesh_gpu_instancing (one mesh drawn at many places), which this reader does not read: ' +
      'each instance would be shown and only one deformed; export the instances as separate nodes');
  }
  (json.nodes ?? []).forEach((/** @type {any} */ node, /** @type {number} */ i) => {
    if (Array.isArray(node.matrix) && !isTrs(node.matrix)) {
      fail(`node ${i} has a matrix that is not a translation, rotation and scale (a shear or a projection; glTF ` +
        'requires a matrix it can decompose, and readers would show it differently)');
    }
  });
}

/**
 * Whether a column-major 4x4 matrix is T * R * S: its last row (0, 0, 0, 1) and its first three columns at
 * right angles (a zero column, a scale of 0, is at right angles to any).
 * @param {number[]} m
 * @returns {boolean}
 */
function isTrs(m) {
  const size = Math.max(1, ...m.map(Math.abs));
  if (Math.abs(m[3]) + Math.abs(m[7]) + Math.abs(m[11]) + Math.abs(m[15] - 1) > SAME_MATRIX * size) return false;
  const column = (/** @type {number} */ c) => [m[4 * c], m[4 * c + 1], m[4 * c + 2]];
  for (const [a, b] of [[0, 1], [0, 2], [1, 2]]) {
    const u = column(a), v = column(b);
    const dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    if (Math.abs(dot) > SAME_MATRIX * Math.hypot(...u) * Math.hypot(...v)) return false;
  }
  return true;
}

/**
 * The instances' nodes, checked for a skin posed elsewhere and for morph weights (readSurface calls it).
 * @param {Document} document
 * @param {any} json
 * @param {{ node: number, mesh: number, matrix: number[] }[]} instances
 * @param {string} filename
 */
export function checkInstancesRestShape(document, json, instances, filename) {
  const fail = failure(filename);
  /** @type {Map<GltfNode, number[]>|null} made on the first skinned node */
  let worlds = null;
  const nodes = document.getRoot().listNodes();
  for (const { node: n, mesh: m, matrix } of instances) {
    if (n < 0) continue;
    const node = json.nodes[n];
    if (node.skin !== undefined) {
      worlds ??= worldMatrices(nodes);
      checkBindPose(nodes[n], n, matrix, worlds, fail);
    }
    const weights = [node.weights, json.meshes[m].weights].find(Array.isArray) ?? [];
    const moved = weights.findIndex((/** @type {number} */ w, /** @type {number} */ k) => w !== 0 &&
      json.meshes[m].primitives.some((/** @type {any} */ p) => p.targets?.[k]?.POSITION !== undefined));
    if (moved >= 0) {
      fail(`node ${n} (mesh ${m}) gives morph target ${moved} the weight ${weights[moved]}: the shape shown is its ` +
        'mesh plus its weighted morph targets, which this reader does not add; set the weights to 0 (or apply the ' +
        'shape keys) before export');
    }
  }
}

/**
 * A skinned node at its bind pose: each joint's world matrix times its inverse bind matrix is the node's own.
 * @param {GltfNode} node
 * @param {number} n its index
 * @param {number[]} matrix its world matrix
 * @param {Map<GltfNode, number[]>} worlds
 * @param {(message: string) => never} fail
 */
function checkBindPose(node, n, matrix, worlds, fail) {
  const skin = node.getSkin();
  if (!skin) return;
  const inverseBind = skin.getInverseBindMatrices()?.getArray() ?? null;
  const joints = skin.listJoints();
  if (inverseBind && inverseBind.length !== 16 * joints.length) {
    fail(`node ${n}: its skin has ${inverseBind.length / 16} inverse bind matrices for ${joints.length} joints`);
  }
  joints.forEach((joint, j) => {
    const bind = inverseBind ? Array.from(inverseBind.subarray(16 * j, 16 * j + 16)) : IDENTITY;
    const placed = multiply4(/** @type {number[]} */ (worlds.get(joint)), bind);
    const size = Math.max(1, ...matrix.map(Math.abs));
    if (placed.some((x, i) => Math.abs(x - matrix[i]) > SAME_MATRIX * size)) {
      fail(`node ${n} is a skinned mesh whose joint ${j} poses it elsewhere than the node's transform places it: ` +
        'a viewer places a skinned mesh by its joints, and this reader does not evaluate skins; export it at its ' +
        'bind pose, or with the pose applied and no skin');
    }
  });
}

/**
 * Every node's world matrix, each from its parent's (a walk down from the roots: linear in the nodes).
 * @param {GltfNode[]} nodes
 * @returns {Map<GltfNode, number[]>}
 */
function worldMatrices(nodes) {
  /** @type {Map<GltfNode, number[]>} */
  const worlds = new Map();
  const stack = nodes.filter((n) => !n.getParentNode()).map((node) => ({ node, parent: IDENTITY }));
  while (stack.length) {
    const { node, parent } = /** @type {{ node: GltfNode, parent: number[] }} */ (stack.pop());
    const world = multiply4(parent, node.getMatrix());
    worlds.set(node, world);
    for (const child of node.listChildren()) stack.push({ node: child, parent: world });
  }
  return worlds;
}
