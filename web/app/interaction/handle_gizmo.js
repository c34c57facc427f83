// A TransformControls gizmo on the active moving handle group of one viewport: translating or rotating it
// (about the group's rest centroid) sets the group's rigid transform in the shared HandleSet, which the
// solver follows. Events: dragstart / drag / dragend (three.js DragControls shape).
//
// A drag belongs to the pointer that started it (TransformControls alone follows every pointer on the canvas: a
// second finger took the handle over and its lift ended the drag), so the gizmo feeds TransformControls the
// events itself. The camera controls never see the drag's press. A drag ends as a release (one undo step, the
// solvers settle, the camera controls back) when its pointer lifts, when another pointer lands (a second finger:
// both fingers then go to OrbitControls, which zooms and pans, as during a brush stroke: touch_handover.js), and
// when its group is gone or no longer the gizmo's (Del, clear, a new model) or the gizmo is disposed.
import { EventDispatcher, Object3D, Vector3 } from 'three';
import { TransformControls } from 'three/addons/controls/TransformControls.js';
import { lineOfCamera } from '../../lib/handle_lines.js';
import { handOverToOrbit, isHandedOver } from './touch_handover.js';

const _t = new Vector3();
const _c = new Vector3();

export class HandleGizmo extends EventDispatcher {
  /**
   * @param {import('../view/viewport.js').Viewport} viewport
   * @param {import('./handle_set.js').HandleSet} handles
   */
  constructor(viewport, handles) {
    super();
    this.viewport = viewport;
    this.handles = handles;
    this.pivot = new Object3D();
    viewport.scene.add(this.pivot);
    this.controls = new TransformControls(viewport.camera, viewport.canvas);
    this.controls.disconnect(); // its listeners follow every pointer: the gizmo's own (#listen) hand it one
    viewport.canvas.style.touchAction = 'none'; // which disconnect() cleared
    this.controls.attach(this.pivot);
    this.helper = this.controls.getHelper();
    this.baseSize = 0.8;
    this.fit(viewport.camera.aspect);
    viewport.addEventListener('resize', () => this.fit(viewport.camera.aspect));
    viewport.scene.add(this.helper);
    this.dragging = false;
    this.controls.addEventListener('change', () => viewport.invalidate());

    this.controls.addEventListener('dragging-changed', (event) => {
      viewport.controls.enabled = !event.value;
      this.dragging = event.value;
      if (event.value) {
        this.#group = handles.groups[handles.active];
        handles.beginTransform();
        this.dispatchEvent({ type: 'dragstart' });
      } else {
        handles.endTransform();
        this.dispatchEvent({ type: 'dragend' });
      }
    });
    this.controls.addEventListener('objectChange', () => {
      const i = handles.active;
      const g = handles.groups[i];
      if (!g || !this.dragging) return;
      _t.copy(this.pivot.position).sub(_c.fromArray(g.center));
      // The centre of the translate gizmo drags in the screen plane: the solver then holds the group only across
      // the camera's lines and chooses its depth (handle_lines.js). Axis and plane drags and rotations keep
      // point targets.
      const screen = this.controls.mode === 'translate' && this.controls.axis === 'XYZ';
      handles.setTransform(i, _t.toArray(), this.pivot.quaternion.toArray(), false, screen ? lineOfCamera(viewport.camera, Vector3) : null);
      this.dispatchEvent({ type: 'drag' });
    });
    this.#listen();
    this.sync();
  }

  #group = null; // the group being dragged
  #pointer = null; // the pointer dragging it: { id, type, clientX, clientY }
  #touches = new Set(); // touch pointers down on the canvas
  #listeners = null;

  // Capture on the canvas: before OrbitControls (which listens there too) sees a press.
  #listen() {
    this.#listeners = { pointerdown: (e) => this.#press(e), pointermove: (e) => this.#move(e),
      pointerup: (e) => this.#lift(e), pointercancel: (e) => this.#lift(e),
      lostpointercapture: (e) => this.#lift(e) }; // the canvas moved or lost the pointer: its release may never come
    for (const [type, listener] of Object.entries(this.#listeners)) this.viewport.canvas.addEventListener(type, listener, true);
  }

  #press(event) {
    if (isHandedOver(event)) return; // a finger given to OrbitControls is the camera's
    if (event.pointerType === 'touch') this.#touches.add(event.pointerId);
    if (this.dragging) {
      if (event.pointerId !== this.#pointer.id) this.#secondPointer(event);
      return;
    }
    // A finger landing beside another is part of a pinch, never a drag.
    if (event.button !== 0 || this.#touches.size > 1 || !this.hitTest(event)) return;
    this.#pointer = { id: event.pointerId, type: event.pointerType, clientX: event.clientX, clientY: event.clientY };
    this.controls.pointerDown(this.#ndc(event, 0)); // dragging-changed: the camera controls off before they see it
    if (!this.dragging) return;
    try {
      this.viewport.canvas.setPointerCapture(event.pointerId); // moves and the release outside the canvas too
    } catch {
      // a synthetic pointer: the drag still follows it over the canvas
    }
  }

  #move(event) {
    if (!this.controls.enabled) return;
    if (!this.dragging) {
      if (event.pointerType !== 'touch') this.controls.pointerHover(this.#ndc(event, 0)); // a mouse or pen hovers
      return;
    }
    if (event.pointerId !== this.#pointer.id) return;
    Object.assign(this.#pointer, { clientX: event.clientX, clientY: event.clientY });
    this.controls.pointerMove(this.#ndc(event, -1));
  }

  #lift(event) {
    this.#touches.delete(event.pointerId);
    if (this.dragging && event.pointerId === this.#pointer.id) this.release();
  }

  /** Another pointer lands during a drag: the drag ends there, and a second finger pinches with the first. */
  #secondPointer(event) {
    const first = this.#pointer;
    this.release();
    if (event.pointerType === 'touch' && first.type === 'touch' && this.#touches.has(first.id)) handOverToOrbit(this.viewport.canvas, first.id, first);
  }

  /** Ends a drag under way as its pointer's release does: one undo step, the solvers settle, the camera controls back. */
  release() {
    if (!this.dragging) return;
    const canvas = this.viewport.canvas;
    if (canvas.hasPointerCapture(this.#pointer.id)) canvas.releasePointerCapture(this.#pointer.id);
    this.#group = null;
    this.controls.pointerUp(null); // dragging-changed(false)
  }

  /** A pointer event's position in the view's normalised device coordinates, as TransformControls takes it. */
  #ndc(event, button) {
    const rect = this.viewport.canvas.getBoundingClientRect();
    return { x: ((event.clientX - rect.left) / rect.width) * 2 - 1, y: -((event.clientY - rect.top) / rect.height) * 2 + 1, button };
  }

  /** True while the pointer is over (or dragging) a gizmo axis: clicks then belong to the gizmo. */
  get active() {
    return this.dragging || (this.helper.visible && this.controls.axis !== null);
  }

  /**
   * Whether a press at this pointer event's position belongs to the gizmo. A mouse hovers first, so the
   * gizmo knows its axis already; a finger or pen arrives without hovering, so the gizmo is hit-tested here.
   */
  hitTest(event) {
    if (this.dragging) return true;
    if (!this.helper.visible || !this.controls.enabled) return false;
    this.controls.pointerHover(this.#ndc(event, 0));
    return this.controls.axis !== null;
  }

  /** Larger handles for fingers (a coarse pointer) than for a mouse. */
  setTouchSize(coarse) {
    this.baseSize = coarse ? 1 : 0.8;
    this.fit(this.viewport.camera.aspect);
  }

  setMode(mode) {
    this.controls.setMode(mode);
  }

  /**
   * Sizes the handles for the view's aspect and says how far they reach. TransformControls draws them at a
   * fixed fraction of the view's height, so a tall narrow view (a phone in portrait) gets smaller ones (down to
   * half), or they would be wider than the view. Returns the pivot and the reach from it as fractions of the
   * view's half-width and half-height (x, y), or null while the gizmo is hidden.
   * @param {number} aspect width / height
   */
  fit(aspect) {
    const size = this.baseSize * Math.min(1, Math.max(0.5, aspect));
    if (this.controls.size !== size) this.controls.setSize(size);
    if (!this.helper.visible) return null;
    // TransformControls: handles scaled by size / 4 of 1.9 tan(fov / 2) times the distance; the translate arrows
    // end 0.6 from the pivot, the rotate gizmo's outer ring 0.75.
    const y = (1.9 / 4) * size * (this.controls.mode === 'rotate' ? 0.75 : 0.6);
    return { point: this.pivot.position.clone(), x: y / aspect, y };
  }

  /** Places the gizmo on the active moving group (hidden when there is none); a drag of another group ends. */
  sync() {
    const g = this.handles.groups[this.handles.active];
    const visible = !!g && g.moving;
    if (this.dragging && (!visible || g !== this.#group)) this.release();
    this.helper.visible = visible;
    this.controls.enabled = visible;
    if (!visible) return;
    this.pivot.position.fromArray(g.center).add(_t.fromArray(g.translate));
    this.pivot.quaternion.fromArray(g.rotation);
    this.pivot.updateMatrixWorld();
    this.viewport.invalidate();
  }

  dispose() {
    this.release();
    for (const [type, listener] of Object.entries(this.#listeners)) this.viewport.canvas.removeEventListener(type, listener, true);
    this.controls.detach();
    this.controls.dispose();
    this.viewport.scene.remove(this.helper, this.pivot);
  }
}
