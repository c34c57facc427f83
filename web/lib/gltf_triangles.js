// @ts-check
// A glTF primitive's triangles, as the reader takes them (gltf.js) and the writer turns tangents over them
// (gltf_tangents.js): strips and fans unrolled in glTF's orders.

/** @import { Primitive } from '@gltf-transform/core' */

const TRIANGLES = 4, TRIANGLE_STRIP = 5, TRIANGLE_FAN = 6;
/** The modes whose primitives are surfaces (points and lines are not). */
export const TRIANGLE_MODES = [TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN];

/**
 * The triangles of a primitive as vertex indices local to it (strips and fans unrolled, in glTF's orders).
 * @param {Primitive} primitive
 * @param {number} count its vertices
 * @returns {number[]}
 */
export function primitiveTriangles(primitive, count) {
  const indexAccessor = primitive.getIndices();
  const index = indexAccessor ? indexAccessor.getArray() : null;
  const n = index ? index.length : count;
  /** @type {(k: number) => number} */
  const at = (k) => (index ? index[k] : k);
  const mode = primitive.getMode();
  /** @type {number[]} */
  const out = [];
  if (mode === TRIANGLES) for (let k = 0; k + 2 < n; k += 3) out.push(at(k), at(k + 1), at(k + 2));
  if (mode === TRIANGLE_STRIP) {
    for (let k = 0; k + 2 < n; ++k) out.push(...(k % 2 ? [at(k + 1), at(k), at(k + 2)] : [at(k), at(k + 1), at(k + 2)]));
  }
  if (mode === TRIANGLE_FAN) for (let k = 1; k + 1 < n; ++k) out.push(at(0), at(k), at(k + 1));
  return out;
}
