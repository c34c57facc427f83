// @ts-check
// A primitive's TANGENT turned with its surface. gltf_write.js recomputes NORMAL from the deformed surface; a
// tangent left as the file had it is no longer perpendicular to that normal (a handle turned by 80 degrees left
// |N.T| at 0.98), and a normal map then shades the surface in the wrong directions. A tangent is the surface's
// direction of increasing u, so it is carried by the surface's own change: each triangle's deformation gradient
// F (the linear map taking its rest edges and unit normal to its deformed ones) maps the tangents of its
// corners, a vertex takes the area-weighted sum over its triangles, made perpendicular to the new normal and of
// unit length. A rigid turn turns it exactly; w (the bitangent's sign, the UVs' handedness) is kept.

import { primitiveTriangles } from './gltf_triangles.js';

/** @import { Primitive, Accessor } from '@gltf-transform/core' */

/**
 * @param {Primitive} primitive with POSITION and a VEC4 TANGENT (node space)
 * @param {Float32Array} positions its new positions (node space), 3 per vertex
 * @param {Float32Array} normals its new normals (node space), 3 per vertex
 * @returns {Float32Array} 4 per vertex
 */
export function turnedTangents(primitive, positions, normals) {
  const rest = /** @type {Accessor} */ (primitive.getAttribute('POSITION'));
  const tangents = /** @type {Accessor} */ (primitive.getAttribute('TANGENT'));
  const count = positions.length / 3;
  const old = Array.from({ length: count }, (_, v) => tangents.getElement(v, [0, 0, 0, 0]));
  const sums = new Float64Array(3 * count);
  const triangles = primitiveTriangles(primitive, count);
  for (let k = 0; k < triangles.length; k += 3) {
    const corners = [triangles[k], triangles[k + 1], triangles[k + 2]];
    const before = frame(corners.map((v) => rest.getElement(v, [0, 0, 0])));
    const after = frame(corners.map((v) => [positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]]));
    if (!before || !after) continue;
    for (const v of corners) {
      const mapped = mapThrough(before, after, old[v]);
      for (let a = 0; a < 3; ++a) sums[3 * v + a] += before.area * mapped[a];
    }
  }
  const out = new Float32Array(4 * count);
  for (let v = 0; v < count; ++v) {
    const n = [normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]];
    const turned = perpendicularUnit([sums[3 * v], sums[3 * v + 1], sums[3 * v + 2]], n) ?? perpendicularUnit(old[v], n) ?? old[v].slice(0, 3);
    out.set([...turned, old[v][3]], 4 * v);
  }
  return out;
}

/** @typedef {{ columns: number[][], inverseRows: number[][], area: number }} Frame  a triangle's two edges and unit normal */

/**
 * A triangle's frame [e1 e2 n] (n its unit normal) and the rows of its inverse; null for a triangle without area.
 * @param {number[][]} p its corners
 * @returns {Frame|null}
 */
function frame(p) {
  const e1 = sub(p[1], p[0]), e2 = sub(p[2], p[0]), normal = cross(e1, e2);
  const doubleArea = Math.hypot(normal[0], normal[1], normal[2]);
  if (!(doubleArea > 0) || !Number.isFinite(doubleArea)) return null;
  const n = normal.map((c) => c / doubleArea);
  const det = dot(e1, cross(e2, n));
  if (!(Math.abs(det) > 0)) return null;
  // The inverse of the matrix with columns a, b, c has the rows b x c, c x a, a x b over the determinant.
  const inverseRows = [cross(e2, n), cross(n, e1), cross(e1, e2)].map((row) => row.map((x) => x / det));
  return { columns: [e1, e2, n], inverseRows, area: doubleArea / 2 };
}

/**
 * F x for F = after.columns * before⁻¹: x in the rest frame's coordinates, rebuilt from the deformed frame.
 * @param {Frame} before @param {Frame} after @param {number[]} x
 * @returns {number[]}
 */
function mapThrough(before, after, x) {
  const c = before.inverseRows.map((row) => dot(row, x));
  return [0, 1, 2].map((a) => c[0] * after.columns[0][a] + c[1] * after.columns[1][a] + c[2] * after.columns[2][a]);
}

/** @param {number[]} x @param {number[]} y */
const sub = (x, y) => [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
/** @param {number[]} x @param {number[]} y */
const dot = (x, y) => x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
/** @param {number[]} x @param {number[]} y */
const cross = (x, y) => [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]];

/**
 * `x` with its component along unit `n` removed, of unit length; null when nothing is left of it.
 * @param {number[]} x @param {number[]} n
 * @returns {number[]|null}
 */
function perpendicularUnit(x, n) {
  const along = dot(x, n);
  const p = [x[0] - along * n[0], x[1] - along * n[1], x[2] - along * n[2]];
  const length = Math.hypot(p[0], p[1], p[2]);
  return length > 1e-12 && Number.isFinite(length) ? p.map((c) => c / length) : null;
}
