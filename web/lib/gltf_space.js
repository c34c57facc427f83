// @ts-check
// The affine maps between a glTF node's own space and the scene's (gltf.js reads positions into scene space,
// gltf_write.js writes them back): column-major 4x4 matrices as glTF stores them, as plain arrays.

/** @typedef {ArrayLike<number>} Matrix4  column-major, 16 numbers (a plain array, or a glTF-Transform matrix) */

export const IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];

/**
 * a * b for column-major 4x4 matrices, as a plain array.
 * @param {Matrix4} a
 * @param {Matrix4} b
 * @returns {number[]}
 */
export function multiply4(a, b) {
  /** @type {number[]} */
  const out = new Array(16);
  for (let c = 0; c < 4; ++c) {
    for (let r = 0; r < 4; ++r) {
      out[4 * c + r] = a[r] * b[4 * c] + a[4 + r] * b[4 * c + 1] + a[8 + r] * b[4 * c + 2] + a[12 + r] * b[4 * c + 3];
    }
  }
  return out;
}

/**
 * m * (x, y, z, 1) into out[at..at+2].
 * @param {Matrix4} m
 * @param {number} x
 * @param {number} y
 * @param {number} z
 * @param {{ [index: number]: number }} out
 * @param {number} at
 */
export function transformPoint(m, x, y, z, out, at) {
  out[at] = m[0] * x + m[4] * y + m[8] * z + m[12];
  out[at + 1] = m[1] * x + m[5] * y + m[9] * z + m[13];
  out[at + 2] = m[2] * x + m[6] * y + m[10] * z + m[14];
}

/**
 * The determinant of m's 3x3 part (negative: the map mirrors).
 * @param {Matrix4} m
 * @returns {number}
 */
export function determinant3(m) {
  return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[4] * (m[1] * m[10] - m[2] * m[9]) + m[8] * (m[1] * m[6] - m[2] * m[5]);
}

/**
 * A normal through m's 3x3 part, as normals turn: the inverse transpose (the cofactor matrix divided by the
 * determinant; only its sign matters for a direction), normalised.
 * @param {Matrix4} m
 * @param {number} x
 * @param {number} y
 * @param {number} z
 * @returns {number[]}
 */
export function normalTransform(m, x, y, z) {
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

/**
 * The inverse of an affine column-major 4x4 matrix (scene -> node space), or null where there is none: a
 * node scaled by zero along some axis (valid glTF, used to hide an object) flattens its mesh, and no point of
 * the scene maps back into it.
 * @param {Matrix4} m
 * @returns {number[]|null}
 */
export function inverseAffine(m) {
  const det = determinant3(m);
  const inv = [
    (m[5] * m[10] - m[6] * m[9]) / det, (m[2] * m[9] - m[1] * m[10]) / det, (m[1] * m[6] - m[2] * m[5]) / det, 0,
    (m[6] * m[8] - m[4] * m[10]) / det, (m[0] * m[10] - m[2] * m[8]) / det, (m[2] * m[4] - m[0] * m[6]) / det, 0,
    (m[4] * m[9] - m[5] * m[8]) / det, (m[1] * m[8] - m[0] * m[9]) / det, (m[0] * m[5] - m[1] * m[4]) / det, 0,
    0, 0, 0, 1,
  ];
  for (let r = 0; r < 3; ++r) inv[12 + r] = -(inv[r] * m[12] + inv[4 + r] * m[13] + inv[8 + r] * m[14]);
  return det !== 0 && inv.every(Number.isFinite) ? inv : null;
}
