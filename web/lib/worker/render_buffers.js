// What the page needs to draw one solver result, computed in the worker so the page only swaps buffers:
// Float32 positions and area-weighted vertex normals of the mesh (the sum of the unnormalized face normals
// of the triangles around a vertex, normalized: what three.js computeVertexNormals gives), and Float32 cage
// positions. All are fresh arrays, handed to the page as transferables (no copy on either side).

/**
 * @param {Float64Array} positions 3 per vertex
 * @param {Uint32Array} indices 3 per triangle
 * @returns {{ positions: Float32Array, normals: Float32Array }}
 */
export function meshRenderBuffers(positions, indices) {
  const p = Float32Array.from(positions);
  const normals = new Float32Array(p.length);
  for (let t = 0; t < indices.length; t += 3) {
    const a = 3 * indices[t];
    const b = 3 * indices[t + 1];
    const c = 3 * indices[t + 2];
    const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
    const vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
    const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    normals[a] += nx; normals[a + 1] += ny; normals[a + 2] += nz;
    normals[b] += nx; normals[b + 1] += ny; normals[b + 2] += nz;
    normals[c] += nx; normals[c + 1] += ny; normals[c + 2] += nz;
  }
  for (let i = 0; i < normals.length; i += 3) {
    const x = normals[i], y = normals[i + 1], z = normals[i + 2];
    const squared = x * x + y * y + z * z;
    // An isolated vertex (no triangle) keeps a zero normal, as in three.js.
    if (squared > 0) {
      const s = 1 / Math.sqrt(squared);
      normals[i] = x * s;
      normals[i + 1] = y * s;
      normals[i + 2] = z * s;
    }
  }
  return { positions: p, normals };
}
