// @ts-check
// A skeleton (docs/method.md section 5.4): joints inside the mesh (rest coordinates) and bones, pairs of joint
// indices. The solver keeps every bone's length and keeps it straight as hard constraints beside the volume; the
// joints follow the mesh. Scenes give it as a top-level "skeleton": { "joints": [[x, y, z], ...],
// "bones": [[0, 1], ...] }, the Deformer takes it with setSkeleton, the app draws and edits it with its bone tool.
import { InputError } from './errors.js';

/** @typedef {{ joints: number[][], bones: number[][] }} Skeleton */
/**
 * A bone in a report: its length now, (length - rest length) / rest length, its seven samples' largest distance
 * from the segment / rest length, the length's multiplier, and whether its middle sample is held on the segment
 * (heldSamples 1, straightHard true; 0 and false where the subspace cannot hold it beside the other constraints, and
 * under ARAP, which ignores the skeleton: there lambda is 0 too).
 * @typedef {{ length: number, lengthError: number, straightnessError: number, lambda: number, heldSamples: number,
 *   straightHard: boolean }} BoneReport
 */
/** The deformed joints, each bone's report, and whether the method keeps the skeleton (false under ARAP).
 * @typedef {{ joints: Float64Array, bones: BoneReport[], kept: boolean }} SkeletonReport */

/** The most joints a skeleton may have (each bone costs hard constraints every iteration). */
export const MAX_JOINTS = 256;

const isPoint = (/** @type {unknown} */ p) => Array.isArray(p) && p.length === 3 && p.every((x) => typeof x === 'number' && Number.isFinite(x));

/**
 * Checks a skeleton's shape and returns a copy; null or undefined: no skeleton. Whether the joints lie inside the
 * mesh, and the bones' lengths, are checked by the solver (an error with code 'invalid_skeleton').
 * @param {unknown} spec
 * @param {string} where names it in messages
 * @returns {Skeleton|null}
 */
export function checkSkeleton(spec, where) {
  if (spec === null || spec === undefined) return null;
  if (typeof spec !== 'object' || Array.isArray(spec)) throw new InputError(`${where} must be { joints: [[x, y, z], ...], bones: [[a, b], ...] } or null`);
  const { joints, bones, ...rest } = /** @type {Record<string, unknown>} */ (spec);
  const unknown = Object.keys(rest);
  if (unknown.length) throw new InputError(`${where}: unknown field "${unknown[0]}" (a skeleton has "joints" and "bones")`);
  if (!Array.isArray(joints) || joints.length < 2) throw new InputError(`${where}.joints must be an array of at least 2 points [x, y, z]`);
  if (joints.length > MAX_JOINTS) throw new InputError(`${where}.joints: ${joints.length} joints, more than ${MAX_JOINTS}`);
  joints.forEach((p, j) => {
    if (!isPoint(p)) throw new InputError(`${where}.joints[${j}] must be [x, y, z], 3 finite numbers`);
  });
  if (!Array.isArray(bones) || bones.length === 0) throw new InputError(`${where}.bones must be a non-empty array of joint pairs [a, b]`);
  bones.forEach((b, k) => {
    const isPair = Array.isArray(b) && b.length === 2 && b.every((j) => Number.isInteger(j) && j >= 0 && j < joints.length);
    if (!isPair) throw new InputError(`${where}.bones[${k}] must be [a, b], two joint indices from 0 to ${joints.length - 1}`);
  });
  return { joints: joints.map((p) => p.slice()), bones: bones.map((b) => b.slice()) };
}

/**
 * The session's form: 3 numbers per joint and 2 indices per bone.
 * @param {Skeleton} skeleton checked
 * @returns {{ joints: Float64Array, bones: Int32Array }}
 */
export function packSkeleton(skeleton) {
  return { joints: Float64Array.from(skeleton.joints.flat()), bones: Int32Array.from(skeleton.bones.flat()) };
}

/**
 * What a method makes of a skeleton, as warnings of a report: ARAP does not keep bones (the Gauss-Newton methods do),
 * so a skeleton under ARAP is only measured. One wording for the CLI's report and the app's views, as
 * handleLineWarnings is for handle lines.
 * @param {string} method
 * @param {unknown} skeleton what the solve holds (a Skeleton, or the session's SkeletonReport), or null for none
 * @returns {{ severity: 'warning', code: 'skeleton_ignored', message: string }[]}
 */
export function skeletonWarnings(method, skeleton) {
  if (method !== 'arap' || !skeleton) return [];
  return [{ severity: 'warning', code: 'skeleton_ignored', message: 'ARAP does not keep the skeleton\'s bones: they apply to the subspace and full methods' }];
}
