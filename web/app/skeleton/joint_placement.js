// Where a tap of the bone tool puts a joint: midway between the surface the view ray hits first and the next
// surface along it, i.e. inside the mesh, halfway through the limb under the finger. The ray is cast against
// the mesh as drawn (deformed); each of the two hits is carried back to the rest mesh through its triangle
// (the same barycentric coordinates on the rest triangle), and the joint's rest position is the midpoint of
// those two rest points, since joints live in the model's rest coordinates (the solver's skeleton). Pure
// arithmetic on the vertex arrays (no three.js), every triangle tested (Moller-Trumbore): a tap costs one
// pass over the triangles, about a millisecond per 100k.

/**
 * Every crossing of the ray origin + t direction (t > 0) with a triangle, nearest first.
 * @param {ArrayLike<number>} origin [x, y, z]
 * @param {ArrayLike<number>} direction [x, y, z], any length (t is in its units)
 * @param {ArrayLike<number>} positions xyz per vertex
 * @param {ArrayLike<number>} indices three per triangle
 * @returns {{ t: number, face: number, u: number, v: number }[]} u, v: barycentric weights of corners 1 and 2
 */
export function rayHits(origin, direction, positions, indices) {
  const [ox, oy, oz] = origin;
  const [dx, dy, dz] = direction;
  const hits = [];
  for (let f = 0; f < indices.length / 3; ++f) {
    const a = 3 * indices[3 * f], b = 3 * indices[3 * f + 1], c = 3 * indices[3 * f + 2];
    const e1x = positions[b] - positions[a], e1y = positions[b + 1] - positions[a + 1], e1z = positions[b + 2] - positions[a + 2];
    const e2x = positions[c] - positions[a], e2y = positions[c + 1] - positions[a + 1], e2z = positions[c + 2] - positions[a + 2];
    const px = dy * e2z - dz * e2y, py = dz * e2x - dx * e2z, pz = dx * e2y - dy * e2x;
    const det = e1x * px + e1y * py + e1z * pz;
    if (det === 0) continue; // the ray is parallel to the triangle
    const inv = 1 / det;
    const sx = ox - positions[a], sy = oy - positions[a + 1], sz = oz - positions[a + 2];
    const u = (sx * px + sy * py + sz * pz) * inv;
    if (u < 0 || u > 1) continue;
    const qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
    const v = (dx * qx + dy * qy + dz * qz) * inv;
    if (v < 0 || u + v > 1) continue;
    const t = (e2x * qx + e2y * qy + e2z * qz) * inv;
    if (t > 0) hits.push({ t, face: f, u, v });
  }
  return hits.sort((p, q) => p.t - q.t);
}

/** The point of a hit's triangle at its barycentric coordinates, on `positions` (the rest mesh, or the drawn one). */
function pointOf(hit, positions, indices) {
  const w = [1 - hit.u - hit.v, hit.u, hit.v];
  const out = [0, 0, 0];
  for (let k = 0; k < 3; ++k) {
    const i = 3 * indices[3 * hit.face + k];
    for (let d = 0; d < 3; ++d) out[d] += w[k] * positions[i + d];
  }
  return out;
}

/**
 * The joint a tap places: midway between the first surface hit along the ray and the next one behind it (a
 * crossing at the same depth, through an edge or a corner shared by triangles, counts once).
 * @param {ArrayLike<number>} origin the eye (or, orthographic, a point on the ray)
 * @param {ArrayLike<number>} direction the view ray's direction
 * @param {{ shown: ArrayLike<number>, rest: ArrayLike<number>, indices: ArrayLike<number> }} mesh the drawn
 *   (deformed) positions, the rest positions, the triangles (one vertex layout for both)
 * @returns {{ rest: number[], shown: number[], depth: number }|{ rest: null, reason: string }} rest: the joint's
 *   rest position; shown: the same point on the drawn mesh; depth: the limb's thickness along the ray
 */
export function jointOnRay(origin, direction, { shown, rest, indices }) {
  const hits = rayHits(origin, direction, shown, indices);
  if (!hits.length) return { rest: null, reason: 'the tap is not on the mesh' };
  const first = hits[0];
  const scale = Math.abs(first.t) + 1;
  const second = hits.find((h) => h.t - first.t > 1e-9 * scale);
  if (!second) return { rest: null, reason: 'no surface behind the one tapped (the mesh is open there)' };
  const p = pointOf(first, rest, indices);
  const q = pointOf(second, rest, indices);
  const a = pointOf(first, shown, indices);
  const b = pointOf(second, shown, indices);
  const length = Math.hypot(...direction);
  return {
    rest: p.map((x, d) => (x + q[d]) / 2),
    shown: a.map((x, d) => (x + b[d]) / 2),
    depth: (second.t - first.t) * length,
  };
}

/**
 * Where a rest point sits between two surface points: along the axis (x, y or z) on which the mesh is thinnest
 * around it, the nearest surface on each side and the fraction of the way from the one to the other. The point's
 * place on the deformed mesh is then the same fraction between those two surface points as deformed
 * (anchoredPoint): how a joint is drawn while no solver report places it (a chain's first joint, or bones the
 * solvers do not keep), so it follows the mesh as the joints the solver keeps do.
 * @returns {{ a: object, b: object, s: number }|null} null: no surface on both sides (a point outside the mesh)
 */
export function anchorPoint(p, rest, indices) {
  let best = null;
  for (let axis = 0; axis < 3; ++axis) {
    const d = [0, 0, 0];
    d[axis] = 1;
    const ahead = rayHits(p, d, rest, indices)[0];
    const behind = rayHits(p, d.map((x) => -x), rest, indices)[0];
    if (!ahead || !behind) continue;
    const span = ahead.t + behind.t;
    if (!best || span < best.span) best = { a: behind, b: ahead, s: behind.t / span, span };
  }
  return best && { a: best.a, b: best.b, s: best.s };
}

/** An anchored point (anchorPoint) on `positions` (the mesh as drawn, the same triangles). */
export function anchoredPoint({ a, b, s }, positions, indices) {
  const p = pointOf(a, positions, indices);
  const q = pointOf(b, positions, indices);
  return p.map((x, d) => x + s * (q[d] - x));
}
