// The scenes of the report's section 3, rebuilt on our models with reproducible geometric queries (handle
// regions are the vertices within a radius of an extreme point; motions are fractions of the bounding-box
// diagonal D or height H). Real models come from ../shared/data (not shipped); without it, built-in
// procedural models stand in.

/** Bounding box, its diagonal and the extreme vertices per axis. */
export function bounds(positions) {
  const n = positions.length / 3;
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  const argLo = [0, 0, 0], argHi = [0, 0, 0];
  for (let i = 0; i < n; ++i) {
    for (let a = 0; a < 3; ++a) {
      const v = positions[3 * i + a];
      if (v < lo[a]) { lo[a] = v; argLo[a] = i; }
      if (v > hi[a]) { hi[a] = v; argHi[a] = i; }
    }
  }
  const size = hi.map((h, a) => h - lo[a]);
  return { lo, hi, size, diagonal: Math.hypot(...size), argLo, argHi };
}

export const point = (positions, i) => [positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]];

/** Vertices within `radius` of point p, ascending. */
export function verticesNear(positions, p, radius) {
  const out = [];
  for (let i = 0; i < positions.length / 3; ++i) {
    const d = Math.hypot(positions[3 * i] - p[0], positions[3 * i + 1] - p[1], positions[3 * i + 2] - p[2]);
    if (d <= radius) out.push(i);
  }
  return out;
}

/** Vertices whose coordinate `axis` is below lo + fraction * size. */
export function verticesBelow(positions, axis, threshold) {
  const out = [];
  for (let i = 0; i < positions.length / 3; ++i) if (positions[3 * i + axis] <= threshold) out.push(i);
  return out;
}

const scale = (v, s) => v.map((x) => x * s);

export function centroid(positions, vertices) {
  const c = [0, 0, 0];
  for (const v of vertices) for (let a = 0; a < 3; ++a) c[a] += positions[3 * v + a] / vertices.length;
  return c;
}

// Bar (along x): fix the left end, rotate the right end by 120 degrees about z around the left end, so
// it ends up above and behind (toward -x) where it started.
function barRotation(positions, b) {
  const left = verticesBelow(positions, 0, b.lo[0] + 0.06 * b.size[0]);
  const right = [];
  for (let v = 0; v < positions.length / 3; ++v) if (positions[3 * v] >= b.hi[0] - 0.06 * b.size[0]) right.push(v);
  const center = centroid(positions, left);
  return {
    handles: [{ vertices: left }, { vertices: right, rotate: { axis: [0, 0, 1], degrees: 120, center } }],
    query: `fixed: the left 6% of the bar (${left.length} vertices); moved: the right 6% (${right.length} vertices), rotated by 120 degrees about z around the left end's centroid (up and back)`,
  };
}

// Each builder gets the rest positions and returns { handles: [{ vertices, translate? }], query }:
// `query` says in words how the regions were chosen (for the README).
export const SCENES = [
  {
    id: 'two_handle_pull',
    figure: 3,
    title: 'Two-handle pull (report fig. 3): subspace vs full space',
    model: { name: 'armadillo', mesh: 'armadillo.obj', cage: 'armadillo_cage.obj' },
    fallback: { example: 'bar' },
    series: ['subspace-fast', 'subspace-exact', 'full-fast', 'full-exact', 'arap'],
    build(positions, real) {
      const b = bounds(positions);
      if (real) {
        // Armadillo stands along +y; its hands are the extreme points in x.
        const r = 0.025 * b.diagonal;
        const left = verticesNear(positions, point(positions, b.argLo[0]), r);
        const right = verticesNear(positions, point(positions, b.argHi[0]), r);
        return {
          handles: [{ vertices: left }, { vertices: right, translate: scale([-1, 0, 0.15], 0.3 * b.diagonal) }],
          query: `fixed: vertices within 0.025 D of the lowest-x point (left hand, ${left.length} vertices); ` +
            `moved: within 0.025 D of the highest-x point (right hand, ${right.length} vertices) by 0.3 D toward -x (slightly forward)`,
        };
      }
      const left = verticesBelow(positions, 0, b.lo[0] + 0.06 * b.size[0]);
      const right = verticesNear(positions, point(positions, b.argHi[0]), 0.08 * b.diagonal);
      return {
        handles: [{ vertices: left }, { vertices: right, translate: [0, 0, -0.3 * b.diagonal] }],
        query: `fixed: the left 6% of the bar (${left.length} vertices); moved: within 0.08 D of the right tip (${right.length} vertices) sideways by 0.3 D`,
      };
    },
  },
  {
    id: 'two_vertex_pull',
    figure: 3,
    title: 'Two-vertex pull (report fig. 3, exactly two constrained vertices): subspace vs full space',
    model: { name: 'armadillo', mesh: 'armadillo.obj', cage: 'armadillo_cage.obj' },
    fallback: { example: 'bar' },
    series: ['subspace-fast', 'subspace-exact', 'full-fast', 'full-exact'],
    build(positions, real) {
      // The report constrains one vertex per side; the same motion as two_handle_pull.
      const b = bounds(positions);
      const left = b.argLo[0], right = b.argHi[0];
      const translate = real ? scale([-1, 0, 0.15], 0.3 * b.diagonal) : [0, 0, -0.3 * b.diagonal];
      return {
        handles: [{ vertices: [left] }, { vertices: [right], translate }],
        query: `fixed: the single lowest-x vertex ${left}; moved: the single highest-x vertex ${right} by the same motion as two_handle_pull`,
      };
    },
  },
  {
    id: 'large_rotation',
    figure: 4,
    title: 'Large rotation (report fig. 4): subspace vs ARAP',
    model: { name: 'gargoyle', mesh: 'gargoyle.obj', cage: 'gargoyle_cage_v67.obj' },
    view: { yaw: Math.PI / 2 },  // the motion is in y-z: look along x
    fallback: { example: 'bar' },
    series: ['subspace-fast', 'subspace-exact', 'full-fast', 'arap', 'arap-sliced'],
    build(positions, real) {
      // The moved handle's target is the handle rotated rigidly about the fixed end: a pure rotation of the
      // whole model satisfies it exactly, so the best answers need a large global rotation.
      const b = bounds(positions);
      if (real) {
        const base = verticesNear(positions, point(positions, b.argLo[1]), 0.06 * b.diagonal);
        const top = verticesNear(positions, point(positions, b.argHi[1]), 0.04 * b.diagonal);
        const center = centroid(positions, base);
        return {
          handles: [{ vertices: base }, { vertices: top, rotate: { axis: [1, 0, 0], degrees: -75, center } }],
          query: `fixed: vertices within 0.06 D of the lowest point (base, ${base.length} vertices); ` +
            `moved: within 0.04 D of the highest point (top, ${top.length} vertices), rotated by 75 degrees backwards (toward -z) about the x axis through the base's centroid`,
        };
      }
      return barRotation(positions, b);
    },
  },
  {
    id: 'large_rotation_bar',
    figure: 4,
    title: 'Large rotation on the built-in bar (report fig. 4): subspace vs ARAP',
    model: null,
    fallback: { example: 'bar' },
    series: ['subspace-fast', 'subspace-exact', 'full-fast', 'arap', 'arap-sliced'],
    build(positions) {
      return barRotation(positions, bounds(positions));
    },
  },
  {
    id: 'extreme_pull',
    figure: 5,
    title: 'Extreme pull with fixed feet (report fig. 5): volume, subspace vs ARAP',
    model: { name: 'moomoo', mesh: 'moomoo.obj', cage: 'moomoo_cage.obj' },
    fallback: { example: 'sphere' },
    series: ['subspace-fast', 'subspace-novolume', 'arap', 'arap-sliced'],
    build(positions, real) {
      const b = bounds(positions);
      if (real) {
        // Moomoo stands on +y with its head toward -x: the feet are the lowest 4% of the height; the front
        // feet are those on the head's side of the feet's mean x. The snout is the lowest-x point.
        const feet = verticesBelow(positions, 1, b.lo[1] + 0.04 * b.size[1]);
        const meanX = feet.reduce((s, v) => s + positions[3 * v], 0) / feet.length;
        const front = feet.filter((v) => positions[3 * v] < meanX);
        const snout = verticesNear(positions, point(positions, b.argLo[0]), 0.03 * b.diagonal);
        return {
          handles: [{ vertices: front }, { vertices: snout, translate: [-0.25 * b.diagonal, 0.25 * b.diagonal, 0] }],
          query: `fixed: the front feet (lowest 4% of the height, x below the feet's mean; ${front.length} vertices); ` +
            `moved: within 0.03 D of the lowest-x point (snout, ${snout.length} vertices) up and forward (-x) by 0.25 D each`,
        };
      }
      const bottom = verticesBelow(positions, 1, b.lo[1] + 0.1 * b.size[1]);
      const top = verticesNear(positions, point(positions, b.argHi[1]), 0.1 * b.diagonal);
      return {
        handles: [{ vertices: bottom }, { vertices: top, translate: [-0.3 * b.diagonal, 0.3 * b.diagonal, 0] }],
        query: `fixed: the lowest 10% of the sphere (${bottom.length} vertices); moved: within 0.1 D of the top (${top.length} vertices) up and sideways by 0.3 D each`,
      };
    },
  },
];
