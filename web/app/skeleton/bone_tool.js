// The bone tool in one view (settings.tool 'bone', the tool strip's bone button, key B): a tap or click on a
// joint makes it the chain's tip (the next joint continues from it; the tip again ends the chain), on a bone
// selects it, and anywhere else on the mesh places a new joint midway between the surface under the pointer
// and the next surface behind it (joint_placement.js), joined to the tip by a bone. A tap beside the mesh lets
// go of what is in hand. Drags still orbit, two fingers zoom and pan, and a press on the gizmo is the gizmo's.
// It only reads the pointer (the camera controls see every event too) and tells the skeleton what was tapped.
import { Raycaster, Vector2, Vector3 } from 'three';
import { jointOnRay } from './joint_placement.js';
import { boneNear, jointNear } from './skeleton_picking.js';

const TAP_SLOP_PX = 6;
const TAP_MS = 600;
const RADIUS = { joint: { mouse: 12, pen: 14, touch: 24 }, bone: { mouse: 8, pen: 10, touch: 18 } };
const raycaster = new Raycaster();
const _ndc = new Vector2();
const _p = new Vector3();

export class BoneTool {
  /**
   * @param {import('../view/solver_view.js').SolverView} view
   * @param {{ active: () => boolean, tap: (what: object) => void }} options active: whether the bone tool is
   *   the current tool; tap: called with { joint } | { bone } | { place: { rest, shown } } | { miss: reason } | { empty: true }
   */
  constructor(view, { active, tap }) {
    this.view = view;
    this.active = active;
    this.tap = tap;
    this.down = null;
    const canvas = view.viewport.canvas;
    this.listeners = {
      pointerdown: (event) => {
        const own = this.active() && event.isPrimary && event.button === 0 && !view.gizmo.hitTest(event);
        this.down = own ? { x: event.clientX, y: event.clientY, t: performance.now(), id: event.pointerId } : null;
      },
      pointerup: (event) => {
        const down = this.down;
        this.down = null;
        if (!down || event.pointerId !== down.id || !this.active()) return;
        if (Math.hypot(event.clientX - down.x, event.clientY - down.y) > TAP_SLOP_PX || performance.now() - down.t > TAP_MS) return;
        this.tap(this.at(event.clientX, event.clientY, event.pointerType));
      },
      pointercancel: () => (this.down = null),
    };
    for (const [type, listener] of Object.entries(this.listeners)) canvas.addEventListener(type, listener, true);
  }

  /** What a tap at client position (x, y) means (see the constructor's `tap`). */
  at(clientX, clientY, pointerType = 'mouse') {
    const viewport = this.view.viewport;
    const rect = viewport.canvas.getBoundingClientRect();
    const x = clientX - rect.left, y = clientY - rect.top;
    const points = this.#onScreen(rect);
    const joint = jointNear(points, x, y, RADIUS.joint[pointerType] ?? RADIUS.joint.mouse);
    if (joint >= 0) return { joint };
    const bone = boneNear(points, this.view.skeletonView.bones, x, y, RADIUS.bone[pointerType] ?? RADIUS.bone.mouse);
    if (bone >= 0) return { bone };
    const model = this.view.model;
    const shown = viewport.meshView.positions;
    if (!model || !shown) return { empty: true };
    _ndc.set((x / rect.width) * 2 - 1, -(y / rect.height) * 2 + 1);
    raycaster.setFromCamera(_ndc, viewport.camera);
    const { origin, direction } = raycaster.ray;
    const placed = jointOnRay(origin.toArray(), direction.toArray(), { shown, rest: model.mesh.positions, indices: model.mesh.indices });
    if (placed.rest) return { place: placed };
    return placed.reason.startsWith('the tap is not') ? { empty: true } : { miss: placed.reason };
  }

  // The drawn joints in the canvas' pixels (null: behind the camera).
  #onScreen(rect) {
    const camera = this.view.viewport.camera;
    camera.updateMatrixWorld();
    return this.view.skeletonView.points.map((p) => {
      _p.fromArray(p).project(camera);
      if (_p.z < -1 || _p.z > 1) return null;
      return { x: ((_p.x + 1) / 2) * rect.width, y: ((1 - _p.y) / 2) * rect.height };
    });
  }

  dispose() {
    for (const [type, listener] of Object.entries(this.listeners)) this.view.viewport.canvas.removeEventListener(type, listener, true);
  }
}
