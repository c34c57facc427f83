// @ts-check
// A glTF node's own transform checked as the spec defines it (gltf_check.js runs it on every node).

// How far a rotation quaternion's length may be from 1: float32 storage leaves ~1e-7, careless exporters ~1e-4.
const UNIT_TOLERANCE = 1e-3;

/**
 * A node's transform as glTF defines it, so that it is not guessed at: either a matrix or translation, rotation
 * and scale, never both (a matrix with a translation was read with the translation ignored), and a unit rotation
 * quaternion (a longer one was read as a rotation with a skewing scale).
 * @param {any} node
 * @param {number} i
 * @param {(message: string) => never} fail
 */
export function checkNodeTransform(node, i, fail) {
  const trs = ['translation', 'rotation', 'scale'].filter((key) => node[key] !== undefined);
  if (node.matrix !== undefined && trs.length) {
    fail(`node ${i} has both a matrix and ${trs.join(', ')}: glTF allows only one of the two ways to give a transform`);
  }
  if (node.rotation === undefined) return;
  const length = Math.hypot(...node.rotation);
  if (!(Math.abs(length - 1) <= UNIT_TOLERANCE)) {
    fail(`node ${i} has a rotation [${node.rotation.join(', ')}] of length ${length.toPrecision(3)}: glTF rotations are unit quaternions`);
  }
}
