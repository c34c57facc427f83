// What a bone-tool tap lands on, on screen: a joint (the nearest drawn joint within a radius), else a bone
// (the nearest drawn stick within a smaller radius). Joints and bones sit inside the mesh, where a ray finds
// nothing to hit, so they are picked by screen distance, as cage vertices are (influence/cage_vertex_picking.js).
// Pure: it takes the joints already projected to the view's pixels (null for one behind the camera).

/**
 * The joint nearest to (x, y) within `radius` pixels, or -1.
 * @param {({ x: number, y: number }|null)[]} points each joint on screen
 */
export function jointNear(points, x, y, radius) {
  let best = -1;
  let bestD = radius * radius;
  points.forEach((p, j) => {
    if (!p) return;
    const d = (p.x - x) ** 2 + (p.y - y) ** 2;
    if (d <= bestD) {
      bestD = d;
      best = j;
    }
  });
  return best;
}

/** Squared distance from (x, y) to the segment from p to q. */
export function segmentDistance2(p, q, x, y) {
  const ux = q.x - p.x, uy = q.y - p.y;
  const length2 = ux * ux + uy * uy;
  const s = length2 > 0 ? Math.min(1, Math.max(0, ((x - p.x) * ux + (y - p.y) * uy) / length2)) : 0;
  return (p.x + s * ux - x) ** 2 + (p.y + s * uy - y) ** 2;
}

/**
 * The bone whose stick passes nearest to (x, y) within `radius` pixels, or -1.
 * @param {({ x: number, y: number }|null)[]} points each joint on screen
 * @param {number[][]} bones pairs of joints
 */
export function boneNear(points, bones, x, y, radius) {
  let best = -1;
  let bestD = radius * radius;
  bones.forEach(([a, b], k) => {
    if (!points[a] || !points[b]) return;
    const d = segmentDistance2(points[a], points[b], x, y);
    if (d <= bestD) {
      bestD = d;
      best = k;
    }
  });
  return best;
}
