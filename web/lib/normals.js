// @ts-check
// Vertex normals of a mesh in its file's layout (normals of the deformed surface for drawing and for writing a
// file back), one per file vertex. Copies of one welded point (a UV seam, a flat-shaded export, non-indexed
// geometry: mesh_layout.h) must not each see only their own triangles, or every seam would show in the
// shading; but where the file's own normals differ between copies (a hard edge, flat shading) they must stay
// apart. So each file vertex gets the area-weighted normal (the sum of its triangles' unnormalised normals,
// as three.js computeVertexNormals) over every triangle at its welded point whose copy there has the same rest
// normal (within about 1.8 degrees: quantised normals differ by that much); without rest normals, over every
// triangle at the point.

import { InputError } from './errors.js';
import { assertAttached } from './typed_arrays.js';

/** Two rest normals at one point are one smoothing group when their cosine is above this. */
const SAME_NORMAL_COS = 0.9995;

/**
 * @param {ArrayLike<number>} positions 3 per file vertex
 * @param {ArrayLike<number>} indices 3 per triangle (file numbering)
 * @param {{ solverOfFile?: Int32Array, restNormals?: Float32Array|null, groups?: Int32Array }} [options]
 *   solverOfFile: the welded point of each file vertex (-1: none; none given: each vertex its own);
 *   restNormals: the file's normals in the same space (NaN where it has none); groups: normalGroups() of the
 *   same, computed once for a model that is drawn many times
 * @returns {Float32Array} unit normals (zero where no triangle is: a vertex used by none keeps its rest
 *   normal when it has one)
 */
export function layoutNormals(positions, indices, { solverOfFile, restNormals, groups } = {}) {
  for (const [what, array] of Object.entries({ positions, indices, solverOfFile, restNormals, groups })) assertAttached(array, `layoutNormals: ${what}`);
  const n = positions.length / 3;
  const group = checkNormalGroups(groups, n, 'layoutNormals: groups') ?? normalGroups(n, { solverOfFile, restNormals });
  const sums = new Float64Array(3 * groupCount(group));
  for (let t = 0; t < indices.length; t += 3) {
    const a = 3 * indices[t], b = 3 * indices[t + 1], c = 3 * indices[t + 2];
    const ux = positions[b] - positions[a], uy = positions[b + 1] - positions[a + 1], uz = positions[b + 2] - positions[a + 2];
    const vx = positions[c] - positions[a], vy = positions[c + 1] - positions[a + 1], vz = positions[c + 2] - positions[a + 2];
    const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    for (let k = 0; k < 3; ++k) {
      const g = 3 * group[indices[t + k]];
      sums[g] += nx;
      sums[g + 1] += ny;
      sums[g + 2] += nz;
    }
  }
  const out = new Float32Array(3 * n);
  for (let v = 0; v < n; ++v) {
    const g = 3 * group[v];
    const length = Math.hypot(sums[g], sums[g + 1], sums[g + 2]);
    if (length > 0) for (let a = 0; a < 3; ++a) out[3 * v + a] = sums[g + a] / length;
    else if (restNormals && !Number.isNaN(restNormals[3 * v])) out.set(restNormals.subarray(3 * v, 3 * v + 3), 3 * v);
  }
  return out;
}

/**
 * Returns `groups` (null passes) after checking it holds one integer group id per vertex, each in [0, n): n
 * vertices make at most n groups (normalGroups numbers them from 0), and the id sizes the per-group sums, so a
 * larger one would ask for gigabytes (1e9) or overflow (2^31 - 1). Throws an InputError naming `what`.
 * @template {ArrayLike<number>|null|undefined} T @param {T} groups @param {number} n @param {string} what @returns {T}
 */
export function checkNormalGroups(groups, n, what) {
  if (groups === null || groups === undefined) return groups;
  assertAttached(groups, what);
  if (!ArrayBuffer.isView(groups) && !Array.isArray(groups)) throw new InputError(`${what} must be an Int32Array of group ids`);
  if (groups.length !== n) throw new InputError(`${what}: ${groups.length} entries for ${n} vertices (one group id per vertex)`);
  for (let v = 0; v < n; ++v) {
    const g = groups[v];
    if (!Number.isInteger(g) || g < 0 || g >= n) throw new InputError(`${what}: vertex ${v} has group ${g}, outside [0, ${n})`);
  }
  return groups;
}

/** @param {Int32Array} group @returns {number} */
function groupCount(group) {
  let max = -1;
  for (const g of group) if (g > max) max = g;
  return max + 1;
}

/**
 * The smoothing group of each file vertex: the copies of one welded point whose rest normals agree (all of them
 * without rest normals); numbered from 0.
 * @param {number} n file vertices
 * @param {{ solverOfFile?: Int32Array, restNormals?: Float32Array|null }} [layout]
 * @returns {Int32Array}
 */
export function normalGroups(n, { solverOfFile, restNormals } = {}) {
  const group = new Int32Array(n);
  if (!solverOfFile) {
    for (let v = 0; v < n; ++v) group[v] = v;
    return group;
  }
  /** @type {Map<number, { group: number, normal: Float32Array|null }[]>} welded point -> [{ group, normal }] */
  const groupsAt = new Map();
  let next = 0;
  for (let v = 0; v < n; ++v) {
    const point = solverOfFile[v];
    if (point < 0) {
      group[v] = next++;
      continue;
    }
    const normal = restNormals && !Number.isNaN(restNormals[3 * v]) ? restNormals.subarray(3 * v, 3 * v + 3) : null;
    const known = groupsAt.get(point) ?? [];
    const same = known.find((g) => (g.normal === null && normal === null) ||
      (g.normal !== null && normal !== null && g.normal[0] * normal[0] + g.normal[1] * normal[1] + g.normal[2] * normal[2] > SAME_NORMAL_COS));
    if (same) {
      group[v] = same.group;
    } else {
      group[v] = next++;
      known.push({ group: group[v], normal });
      groupsAt.set(point, known);
    }
  }
  return group;
}
