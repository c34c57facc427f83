// The binding benchmarks' case, the same as cpp/tools/bench_mvc.cpp's: the vertices of a capsule (length 2,
// radius 0.45, along x) inside a 7 x 7 subdivided box cage [-1.7, 1.7] x [-0.7, 0.7]^2 (296 vertices, 588
// triangles), built here because no binding of the procedural shapes is exposed. bent: both bent through half a
// turn (cpp/core/mesh/shapes.h bend_along_x, radius 3.4 / pi), a U whose arms face each other: a concave cage.

/** The box cage, optionally bent. */
export function boxCage({ bent = false } = {}) {
  const s = 7, half = [1.7, 0.7, 0.7];
  const positions = [], indices = [], ids = new Map();
  const vertex = (p) => {
    const key = p.map((x) => Math.round(x * 1e9)).join(',');
    if (!ids.has(key)) { ids.set(key, positions.length / 3); positions.push(...p); }
    return ids.get(key);
  };
  const face = (origin, u, v) => {
    const id = [];
    for (let j = 0; j <= s; ++j) for (let i = 0; i <= s; ++i) id.push(vertex([0, 1, 2].map((a) => origin[a] + (u[a] * i + v[a] * j) / s)));
    for (let j = 0; j < s; ++j) for (let i = 0; i < s; ++i) {
      const a = id[j * (s + 1) + i], b = id[j * (s + 1) + i + 1], c = id[(j + 1) * (s + 1) + i + 1], d = id[(j + 1) * (s + 1) + i];
      indices.push(a, b, c, a, c, d);
    }
  };
  const lo = half.map((h) => -h), d = half.map((h) => 2 * h);
  const ex = [d[0], 0, 0], ey = [0, d[1], 0], ez = [0, 0, d[2]];
  const add = (p, q) => p.map((x, k) => x + q[k]);
  face(lo, ey, ex); face(add(lo, ez), ex, ey); face(lo, ex, ez); face(add(lo, ey), ez, ex); face(lo, ez, ey); face(add(lo, ex), ey, ez);
  const cage = { positions: new Float64Array(positions), indices: new Uint32Array(indices) };
  if (bent) bend(cage.positions);
  return cage;
}

/** About n capsule vertices (same parameters as capsule_points in bench_mvc.cpp), optionally bent. */
export function capsulePoints(n, { bent = false } = {}) {
  const segments = Math.max(8, Math.floor(Math.sqrt(n / 2)));
  const rings = Math.max(2, Math.floor(segments / 4));
  const cylinder = Math.max(1, Math.floor((n - 2) / segments) - 2 * rings + 1);
  const length = 2, radius = 0.45, profile = [];
  for (let k = 1; k <= rings; ++k) { const phi = (Math.PI / 2) * k / rings; profile.push([-length / 2 - radius * Math.cos(phi), radius * Math.sin(phi)]); }
  for (let k = 1; k < cylinder; ++k) profile.push([-length / 2 + length * k / cylinder, radius]);
  for (let k = rings; k >= 1; --k) { const phi = (Math.PI / 2) * k / rings; profile.push([length / 2 + radius * Math.cos(phi), radius * Math.sin(phi)]); }
  const out = [-length / 2 - radius, 0, 0];
  for (const [x, r] of profile) for (let s = 0; s < segments; ++s) { const t = 2 * Math.PI * s / segments; out.push(x, r * Math.cos(t), r * Math.sin(t)); }
  out.push(length / 2 + radius, 0, 0);
  const points = new Float64Array(out);
  if (bent) bend(points);
  return points;
}

// bend_along_x (shapes.h) with radius 3.4 / pi: the cage's length becomes half a circle.
function bend(positions) {
  const radius = 3.4 / Math.PI;
  for (let i = 0; i < positions.length; i += 3) {
    const angle = positions[i] / radius, r = radius - positions[i + 1];
    positions[i] = r * Math.sin(angle);
    positions[i + 1] = radius - r * Math.cos(angle);
  }
}
