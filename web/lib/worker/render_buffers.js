// What the page needs to draw one solver result, computed in the worker so the page only swaps buffers:
// Float32 positions and vertex normals of the mesh (normals.js: area-weighted as three.js computeVertexNormals
// gives them, shared across the copies of a welded point unless the file's own normals differ there), and
// Float32 cage positions. All are fresh arrays, handed to the page as transferables (no copy on either side).
import { layoutNormals } from '../normals.js';

/**
 * @param {Float64Array} positions 3 per vertex
 * @param {Uint32Array} indices 3 per triangle
 * @param {{ solverOfFile?: Int32Array, restNormals?: Float32Array|null, groups?: Int32Array }} [layout] the
 *   model's welded points and its file's normals, or their smoothing groups (normals.js); none: every vertex
 *   its own
 * @returns {{ positions: Float32Array, normals: Float32Array }}
 */
export function meshRenderBuffers(positions, indices, layout = {}) {
  return { positions: Float32Array.from(positions), normals: layoutNormals(positions, indices, layout) };
}
