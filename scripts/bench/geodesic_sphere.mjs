// A unit sphere of about `vertices` vertices with nearly equal triangles (an icosahedron whose faces are divided
// into frequency^2 triangles, projected onto the sphere: 10 f^2 + 2 vertices), as OBJ text: the large models of
// big.mjs, generated so the project ships no big files.

const T = (1 + Math.sqrt(5)) / 2;
const CORNERS = [[-1, T, 0], [1, T, 0], [-1, -T, 0], [1, -T, 0], [0, -1, T], [0, 1, T], [0, -1, -T], [0, 1, -T],
  [T, 0, -1], [T, 0, 1], [-T, 0, -1], [-T, 0, 1]];
const FACES = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6],
  [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]];

/** The frequency whose sphere has the vertex count closest to `vertices`. */
export function frequencyFor(vertices) {
  return Math.max(1, Math.round(Math.sqrt((vertices - 2) / 10)));
}

/** { obj, vertices, triangles } of the sphere of frequency f. */
export function geodesicSphereObj(f) {
  const positions = [];
  const index = new Map(); // a grid point's key -> vertex index (points on shared edges and corners once)
  const vertex = (face, i, j) => {
    const [a, b, c] = FACES[face];
    const k = f - i - j; // barycentric weights (i, j, k) / f of corners a, b, c
    const weights = [[a, i], [b, j], [c, k]].filter(([, w]) => w > 0);
    const key = weights.length === 1 ? `v${weights[0][0]}`
      : weights.length === 2 ? `e${weights.map(([v, w]) => `${v}:${w}`).sort().join(',')}`
        : `f${face}:${i}:${j}`;
    let id = index.get(key);
    if (id === undefined) {
      const p = [0, 0, 0];
      for (const [v, w] of weights) for (let d = 0; d < 3; ++d) p[d] += (w / f) * CORNERS[v][d];
      const r = Math.hypot(...p);
      id = positions.length;
      positions.push(p.map((x) => x / r));
      index.set(key, id);
    }
    return id;
  };
  const triangles = [];
  for (let face = 0; face < FACES.length; ++face) {
    for (let i = 0; i < f; ++i) {
      for (let j = 0; j < f - i; ++j) {
        triangles.push([vertex(face, i, j), vertex(face, i + 1, j), vertex(face, i, j + 1)]);
        if (i + j + 1 < f) triangles.push([vertex(face, i + 1, j), vertex(face, i + 1, j + 1), vertex(face, i, j + 1)]);
      }
    }
  }
  const lines = positions.map((p) => `v ${p[0].toFixed(7)} ${p[1].toFixed(7)} ${p[2].toFixed(7)}`);
  for (const t of triangles) lines.push(`f ${t[0] + 1} ${t[1] + 1} ${t[2] + 1}`);
  return { obj: `${lines.join('\n')}\n`, vertices: positions.length, triangles: triangles.length };
}
