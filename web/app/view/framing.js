// Framing a view: which box to show (the model as it is now, the handles' targets where the gizmo sits, and
// the cage when it is not much larger than the model) and where to put a perspective camera so that the box
// fits the view's own aspect with a margin. Used at load, by "fit view" (key V, the panel), when compare
// mode changes the views' widths and when a view is resized while the camera is still where a fit put it.
import { Box3, Vector3 } from 'three';

/** The three-quarter front direction a model is first seen from. */
export const DEFAULT_DIRECTION = new Vector3(-0.35, -0.4, -1).normalize();
/** Fraction of the half-width and half-height kept free around the framed box. */
export const FRAME_MARGIN = 0.1;
// A cage whose box is this much larger than the model's (a loose cage, or a subspace cage drifting far
// from its mesh) is left out of the frame: framing it would shrink the model to a few pixels.
const CAGE_FRAME_LIMIT = 1.5;

const _right = new Vector3();
const _up = new Vector3();
const _q = new Vector3();
const _size = new Vector3();

function boxOfArray(positions, box = new Box3()) {
  for (let i = 0; positions && i < positions.length; i += 3) box.expandByPoint(_q.set(positions[i], positions[i + 1], positions[i + 2]));
  return box;
}

function diagonal(box) {
  return box.isEmpty() ? 0 : box.getSize(_size).length();
}

/**
 * The box a view should show.
 * @param {{ meshes: ArrayLike<number>[], targets?: ArrayLike<number>, cages?: ArrayLike<number>[], cageShown?: boolean }} parts
 *   meshes: each view's current mesh positions (xyz); targets: the handles' targets; cages: each view's cage
 * @returns {Box3}
 */
export function framingBox({ meshes, targets = null, cages = [], cageShown = true }) {
  const box = new Box3();
  for (const positions of meshes) boxOfArray(positions, box);
  boxOfArray(targets, box);
  if (cageShown) {
    const model = diagonal(box);
    for (const positions of cages) {
      const cage = boxOfArray(positions);
      if (diagonal(cage) <= CAGE_FRAME_LIMIT * model) box.union(cage);
    }
  }
  return box;
}

/**
 * The camera placement that frames `box` for a perspective camera (its fov and aspect), looking along
 * `direction`: the closest distance at which every corner of the box projects within 1 - margin of the
 * view's centre, horizontally and vertically.
 * @param {Box3} box
 * @param {{ fov: number, aspect: number, up: Vector3 }} camera
 * @param {Vector3} direction unit viewing direction
 * @param {number} [margin]
 * @param {{ point: Vector3, x: number, y: number }|null} [keep] a point that must also stay in view with room
 *   around it: x, y of the half-width and half-height (the gizmo on its pivot, HandleGizmo.fit)
 * @returns {{ center: Vector3, distance: number, radius: number }}
 */
export function frameBox(box, camera, direction, margin = FRAME_MARGIN, keep = null) {
  const center = box.getCenter(new Vector3());
  const radius = Math.max(0.5 * diagonal(box), 1e-9);
  _right.crossVectors(direction, camera.up);
  if (_right.lengthSq() < 1e-12) _right.set(1, 0, 0); // looking straight up or down
  _right.normalize();
  _up.crossVectors(_right, direction);
  const tanV = Math.tan((camera.fov * Math.PI) / 360) * (1 - margin);
  const tanH = tanV * camera.aspect;
  // A corner q (relative to the centre) is at depth distance + q.direction from the camera; it projects
  // inside when |q.right| <= depth tanH and |q.up| <= depth tanV.
  let distance = 1e-9;
  for (let i = 0; i < 8; ++i) {
    _q.set(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z).sub(center);
    const along = _q.dot(direction);
    distance = Math.max(distance, Math.abs(_q.dot(_right)) / tanH - along, Math.abs(_q.dot(_up)) / tanV - along);
  }
  if (keep) {
    const tan = Math.tan((camera.fov * Math.PI) / 360);
    const room = (reach) => tan * Math.max(0.05, 1 - reach - 0.5 * margin); // the arrow tips may use half the margin
    _q.copy(keep.point).sub(center);
    const along = _q.dot(direction);
    distance = Math.max(distance, Math.abs(_q.dot(_right)) / (room(keep.x) * camera.aspect) - along, Math.abs(_q.dot(_up)) / room(keep.y) - along);
  }
  // Never inside the box's bounding sphere: the near plane must stay in front of the model.
  distance = Math.max(distance, 1.05 * radius);
  return { center, distance, radius };
}
