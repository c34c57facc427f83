// @ts-check
// Handle lines, the projection constraint (docs/method.md section 5.2): a handle group held only across the lines
// of a view, its depth left to the energy. A line is { along: [dx, dy, dz] } (an orthographic view: every
// vertex's line runs along that direction) or { from: [x, y, z] } (a perspective view: the line through the eye
// and the vertex's target); null is a point target. Scenes give them as a handle's "along" or "from" field, the
// Deformer takes one per group (setHandleLines), and the app makes them from its camera.
import { InputError } from './errors.js';

/** @typedef {{ along: number[] } | { from: number[] } | null} HandleLine */

const isVector3 = (/** @type {unknown} */ v) => Array.isArray(v) && v.length === 3 && v.every((x) => typeof x === 'number' && Number.isFinite(x));

/**
 * Validates one group's line and returns a copy (null for a point target).
 * @param {unknown} line
 * @param {string} where names the line in messages
 * @returns {HandleLine}
 */
export function checkHandleLine(line, where) {
  if (line === null || line === undefined) return null;
  if (typeof line !== 'object' || Array.isArray(line)) throw new InputError(`${where} must be { along: [dx, dy, dz] }, { from: [x, y, z] } or null`);
  const keys = Object.keys(line);
  if (keys.length !== 1 || !['along', 'from'].includes(keys[0])) {
    throw new InputError(`${where} must have exactly one of "along" (a view direction) or "from" (an eye position)`);
  }
  const key = keys[0];
  const vector = /** @type {Record<string, unknown>} */ (line)[key];
  if (!isVector3(vector)) throw new InputError(`${where}.${key} must be an array of 3 finite numbers`);
  const v = /** @type {number[]} */ (vector);
  if (key === 'along' && !v.some((x) => x !== 0)) throw new InputError(`${where}.along must not be zero`);
  return key === 'along' ? { along: v.slice() } : { from: v.slice() };
}

/**
 * What a method makes of the groups' lines, as warnings of a report: ARAP holds every handle vertex at its target,
 * so lines apply to the subspace and full methods only. One wording for the CLI's report and the app's views.
 * @param {string} method
 * @param {(HandleLine | undefined)[] | null} lines one per group
 * @returns {{ severity: 'warning', code: 'handle_lines_ignored', message: string }[]}
 */
export function handleLineWarnings(method, lines) {
  if (method !== 'arap' || !lines?.some(Boolean)) return [];
  return [{
    severity: 'warning', code: 'handle_lines_ignored',
    message: 'ARAP holds each handle vertex at its target: the handles\' "along"/"from" lines apply to the subspace and full methods',
  }];
}

/**
 * The session's form: 4 numbers per group, kind (0 none, 1 along, 2 from) and the vector.
 * @param {HandleLine[]} lines checked
 * @returns {Float64Array}
 */
export function packHandleLines(lines) {
  const out = new Float64Array(4 * lines.length);
  lines.forEach((line, g) => {
    if (!line) return;
    out[4 * g] = 'along' in line ? 1 : 2;
    out.set('along' in line ? line.along : line.from, 4 * g + 1);
  });
  return out;
}

/**
 * The line a camera sees a dragged handle along: its viewing direction for an orthographic camera, its position
 * for a perspective one.
 * @param {{ isOrthographicCamera?: boolean, position: { x: number, y: number, z: number },
 *           getWorldDirection: (v: any) => { x: number, y: number, z: number } }} camera a three.js camera
 * @param {new () => any} Vector3 three.js' Vector3
 * @returns {HandleLine}
 */
export function lineOfCamera(camera, Vector3) {
  if (camera.isOrthographicCamera) {
    const d = camera.getWorldDirection(new Vector3());
    return { along: [d.x, d.y, d.z] };
  }
  return { from: [camera.position.x, camera.position.y, camera.position.z] };
}
