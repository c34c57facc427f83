// @ts-check
// Volume parts (docs/method.md section 16): the volume kept per part instead of globally. A partition of
// the triangles, one part index per triangle, from one of these descriptions (scene files' "volumeParts",
// the app's painting, the CLI):
//   [[v, ...], ...] or { vertices: [[v, ...], ...] }  vertex lists: a triangle goes to the part that holds at
//                                                    least two of its vertices (the lowest of three otherwise);
//                                                    unlisted vertices form one more part, the last
//   { triangles: [[t, ...], ...] }                   triangle lists; unlisted triangles form one more part
//   { auto: K }                                      K parts by spectral clustering (method.md section 16)
//   "global"                                         one volume for the whole mesh (without a description, a
//                                                    mesh of several components keeps one per component)
// The partition goes to Deformer.setVolumeParts.
import { InputError, callWasm } from './errors.js';
import { AUTO_PARTS_MIN_VERTICES, assertMesh, assertMinVertices } from './mesh.js';
import { assertAttached } from './typed_arrays.js';

/**
 * @typedef {{ kind: 'vertices'|'triangles', lists: number[][] } | { kind: 'auto', parts: number } | { kind: 'global' }} VolumePartsSpec
 */

/**
 * The most parts a partition may have, from lists or automatic: kMaxVolumeParts of cpp/core/parts/partition.h
 * (each part is a hard constraint of every iteration, costing a solve per iteration in the full space, and
 * automatic parts cost work growing like K^2: 1000 of them took minutes per iteration or to make).
 */
export const MAX_VOLUME_PARTS = 64;

/**
 * A non-empty array of indices (integers >= 0); a sparse array's holes are not indices.
 * @param {unknown} list
 * @returns {list is number[]}
 */
function isIndexList(list) {
  if (!Array.isArray(list) || list.length === 0) return false;
  for (let i = 0; i < list.length; ++i) if (!(Number.isInteger(list[i]) && list[i] >= 0)) return false;
  return true;
}

/** The fields of each normalised kind besides "kind" itself. */
const NORMALISED_FIELDS = new Map([['auto', ['parts']], ['global', []], ['vertices', ['lists']], ['triangles', ['lists']]]);

/**
 * Checks a description's shape (indices are checked against the mesh by volumeParts) and normalises it.
 * A normalised description (what this returns, e.g. parseScene's volumeParts) is accepted as well.
 * @param {unknown} spec
 * @param {string} where the field or argument, for messages
 * @returns {VolumePartsSpec}
 */
export function checkVolumePartsSpec(spec, where) {
  /** @type {(value: unknown, field: string) => number[][]} */
  const lists = (value, field) => {
    if (!Array.isArray(value) || value.length === 0) throw new InputError(`${field} must be a non-empty array of index lists`);
    if (value.length > MAX_VOLUME_PARTS) {
      throw new InputError(`${field} has ${value.length} lists: a partition may have at most ${MAX_VOLUME_PARTS} parts`);
    }
    for (let j = 0; j < value.length; ++j) {
      if (!isIndexList(assertAttached(value[j], `${field}[${j}]`))) throw new InputError(`${field}[${j}] must be a non-empty array of indices (integers >= 0)`);
    }
    return value.map((list) => list.slice());
  };
  if (Array.isArray(spec)) return { kind: 'vertices', lists: lists(spec, where) };
  if (spec === 'global') return { kind: 'global' };
  if (!spec || typeof spec !== 'object') {
    throw new InputError(`${where} must be vertex lists, { vertices: [...] }, { triangles: [...] }, { auto: K } or "global"`);
  }
  const fields = /** @type {Record<string, unknown>} */ (spec);
  if (fields.kind !== undefined) {  // already normalised: check it the same way
    const { kind, ...rest } = fields;
    const own = NORMALISED_FIELDS.get(/** @type {string} */ (kind));
    if (!own) throw new InputError(`${where}.kind must be 'vertices', 'triangles' or 'auto' (got ${JSON.stringify(kind)})`);
    // Another field (a "lists" beside 'global', an "extra") would be dropped silently.
    const extra = Object.keys(rest).find((key) => !own.includes(key));
    if (extra !== undefined) {
      throw new InputError(`${where} has unknown field "${extra}" (kind '${kind}' takes ${own.length ? own.map((key) => `"${key}"`).join(' and ') : 'no other field'})`);
    }
    if (kind === 'auto') return checkVolumePartsSpec({ auto: rest.parts }, where);
    if (kind === 'global') return { kind: 'global' };
    return checkVolumePartsSpec({ [/** @type {string} */ (kind)]: rest.lists }, where);
  }
  const keys = Object.keys(spec);
  if (keys.length !== 1 || !['vertices', 'triangles', 'auto'].includes(keys[0])) {
    throw new InputError(`${where} must have exactly one of "vertices", "triangles" or "auto" (got ${JSON.stringify(keys)})`);
  }
  const { auto } = fields;
  if (auto !== undefined) {
    if (!(typeof auto === 'number' && Number.isInteger(auto) && auto >= 1 && auto <= MAX_VOLUME_PARTS)) {
      throw new InputError(`${where}.auto must be an integer from 1 to ${MAX_VOLUME_PARTS} (got ${JSON.stringify(auto)})`);
    }
    return { kind: 'auto', parts: auto };
  }
  const kind = fields.vertices !== undefined ? 'vertices' : 'triangles';
  return { kind, lists: lists(fields[kind], `${where}.${kind}`) };
}

/**
 * The partition (one part index per triangle) a description gives on a mesh. Throws an InputError for a bad
 * description or an index outside the mesh, a MeshError when an automatic partition meets an invalid mesh.
 * @param {import('./solver_module.js').SolverModule} solver the module from loadSolver() / loadNodeSolver()
 * @param {{ positions: Float64Array, indices: Uint32Array }} mesh
 * @param {unknown} spec see the top of this file
 * @returns {Int32Array}
 */
export function volumeParts(solver, mesh, spec) {
  assertMesh(mesh, 'mesh', 'volumeParts');
  const checked = checkVolumePartsSpec(spec, 'volumeParts');
  if (checked.kind === 'global') return new Int32Array(mesh.indices.length / 3);
  if (checked.kind === 'auto') assertMinVertices(mesh, AUTO_PARTS_MIN_VERTICES, 'volumeParts: the automatic partition');
  if (checked.kind === 'auto') return callWasm(() => solver.autoVolumeParts(mesh.positions, mesh.indices, checked.parts));
  return callWasm(() => solver.volumePartsFromLists(mesh.indices, mesh.positions.length / 3, checked.lists, checked.kind));
}
