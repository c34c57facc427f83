// A coarse stand-in for a large mesh, drawn while the view is in motion on a software renderer.
//
// SwiftShader (and llvmpipe) pay per triangle: bar-fine's 86k triangles redraw at about 22 frames per second
// with nothing else running, whatever the resolution, while 10k triangles redraw at 55-60. Machines without a
// usable GPU (virtual machines, remote desktops, blocklisted drivers, headless browsers) would drag large
// models at 15 fps. So while a drag, an orbit or a solve keeps changing the picture, the viewport draws this
// proxy, and the full mesh again once the view has been still for a moment (viewport.js).
//
// The proxy is vertex clustering on a uniform grid (Rossignac and Borrel 1993) with one twist: each cluster
// is represented by one of its own vertices (the one nearest the cluster's mean), so the proxy's triangles
// index the full mesh's vertices. It shares the full mesh's position and normal buffers and follows every
// solver result with no work at all: only its index buffer is its own.

/** Meshes with more triangles than this get a proxy (on software renderers). */
export const PROXY_MIN_TRIANGLES = 30000;
/** Triangles the proxy aims at: what SwiftShader redraws at ~50 fps on two cores. */
export const PROXY_TARGET_TRIANGLES = 12000;

/**
 * Triangles of a coarse version of the mesh that use only its own vertices, or null when the mesh is too
 * small to need one.
 * @param {ArrayLike<number>} positions xyz per vertex (rest positions: the clustering is done once)
 * @param {Uint32Array} indices three vertex indices per triangle
 * @param {number} [targetTriangles]
 * @returns {Uint32Array|null}
 */
export function proxyIndices(positions, indices, targetTriangles = PROXY_TARGET_TRIANGLES) {
  const triangles = indices.length / 3;
  if (triangles <= Math.max(PROXY_MIN_TRIANGLES, 2 * targetTriangles)) return null;
  // A closed triangle mesh has about twice as many triangles as vertices, and a cell of side h holds about
  // area / h^2 surface patches: aim at targetTriangles / 2 occupied cells, then correct the cell size by the
  // count (at most three times; the triangle count goes like 1 / h^2).
  let cell = Math.sqrt(surfaceArea(positions, indices) / (targetTriangles / 2));
  let result = null;
  for (let attempt = 0; attempt < 4; ++attempt) {
    result = clusterIndices(positions, indices, cell);
    const ratio = result.length / 3 / targetTriangles;
    if (ratio > 0.7 && ratio < 1.4) break;
    cell *= Math.sqrt(Math.max(ratio, 0.05)); // ratio 0: everything collapsed, shrink the cells a lot
  }
  return result.length >= 3 ? result : null;
}

/** Vertex clustering with cell side `cell`: triangles over the cluster representatives, degenerate and repeated ones dropped. */
export function clusterIndices(positions, indices, cell) {
  const representative = clusterRepresentatives(positions, cell);
  const out = [];
  const seen = new Set();
  for (let t = 0; t < indices.length; t += 3) {
    const a = representative[indices[t]], b = representative[indices[t + 1]], c = representative[indices[t + 2]];
    if (a === b || b === c || c === a) continue; // collapsed into an edge or a point
    const key = triangleKey(a, b, c);
    if (seen.has(key)) continue;
    seen.add(key);
    out.push(a, b, c); // keeps the original orientation
  }
  return Uint32Array.from(out);
}

// For every vertex, the vertex that represents its grid cell: the cell member nearest the members' mean.
function clusterRepresentatives(positions, cell) {
  const n = positions.length / 3;
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < n; ++i)
    for (let a = 0; a < 3; ++a) {
      min[a] = Math.min(min[a], positions[3 * i + a]);
      max[a] = Math.max(max[a], positions[3 * i + a]);
    }
  const dims = [0, 1, 2].map((a) => Math.floor((max[a] - min[a]) / cell) + 1);
  // Cells numbered in order of first appearance; per cell the sum of its members' positions.
  const cellNumber = new Map();
  const cellOfVertex = new Uint32Array(n);
  const sums = [];
  for (let i = 0; i < n; ++i) {
    let key = 0;
    for (let a = 2; a >= 0; --a) key = key * dims[a] + Math.floor((positions[3 * i + a] - min[a]) / cell);
    let c = cellNumber.get(key);
    if (c === undefined) {
      c = cellNumber.size;
      cellNumber.set(key, c);
      sums.push(0, 0, 0, 0);
    }
    cellOfVertex[i] = c;
    for (let a = 0; a < 3; ++a) sums[4 * c + a] += positions[3 * i + a];
    sums[4 * c + 3] += 1;
  }
  const best = new Int32Array(cellNumber.size).fill(-1);
  const bestDistance = new Float64Array(cellNumber.size).fill(Infinity);
  for (let i = 0; i < n; ++i) {
    const c = cellOfVertex[i];
    let d = 0;
    for (let a = 0; a < 3; ++a) d += (positions[3 * i + a] - sums[4 * c + a] / sums[4 * c + 3]) ** 2;
    if (d < bestDistance[c]) {
      bestDistance[c] = d;
      best[c] = i;
    }
  }
  const representative = new Uint32Array(n);
  for (let i = 0; i < n; ++i) representative[i] = best[cellOfVertex[i]];
  return representative;
}

// The same key for the three rotations of a triangle (orientation-preserving), different for its mirror.
function triangleKey(a, b, c) {
  if (a < b && a < c) return `${a},${b},${c}`;
  if (b < c) return `${b},${c},${a}`;
  return `${c},${a},${b}`;
}

function surfaceArea(positions, indices) {
  let area = 0;
  for (let t = 0; t < indices.length; t += 3) {
    const i = 3 * indices[t], j = 3 * indices[t + 1], k = 3 * indices[t + 2];
    const ux = positions[j] - positions[i], uy = positions[j + 1] - positions[i + 1], uz = positions[j + 2] - positions[i + 2];
    const vx = positions[k] - positions[i], vy = positions[k + 1] - positions[i + 1], vz = positions[k + 2] - positions[i + 2];
    area += 0.5 * Math.hypot(uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx);
  }
  return area;
}
