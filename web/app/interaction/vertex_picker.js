// Vertex selection on one viewport, by mouse, pen or touch. What a one-finger (left-button) press does is the
// current tool (settings.tool, the tool strip): 'pick' taps the mesh vertex nearest to the touched surface
// point (a drag orbits), 'brush' paints every vertex within a world-space radius of the surface under the
// pointer, 'lasso' selects every front-facing vertex inside the drawn outline, 'orbit' only turns the camera.
// With a mouse, Shift-drag brushes and Alt-drag lassos in any tool; erase (the tool strip) or Ctrl removes
// instead of adding. On a touch screen, in the pick tool, press and hold still, then drag: a brush stroke.
// Two fingers always zoom and pan: a second finger during a stroke cancels it (the selection goes back to what
// it was) and hands both fingers to OrbitControls (touch_handover.js). A press on the gizmo is the gizmo's.
// Brush and lasso strokes take the pointer before OrbitControls and the gizmo see it (capture phase).
//
// Events: { type: 'pick', vertex, op } for a tap or click; { type: 'select', vertices, op } for brush and
// lasso, op = 'add' | 'remove'; { type: 'stroke', phase: 'start' | 'end' | 'cancel' } around strokes (on 'cancel'
// the listener restores the selection it had at 'start').
import { EventDispatcher, Raycaster, Vector2, Vector3 } from 'three';
import { handOverToOrbit, isHandedOver } from './touch_handover.js';
import { BrushCursor } from './brush_cursor.js';

const _ndc = new Vector2();
const _v = new Vector3();
const _n = new Vector3();
const _eye = new Vector3();
const _d = new Vector3();
const raycaster = new Raycaster();

const TAP_SLOP_PX = 6; // a press that moves further is a drag (orbit), not a tap
const TAP_MS = 600;
const LONG_PRESS_MS = 450; // pick tool, touch or pen: holding this long without moving starts a brush stroke

export class VertexPicker extends EventDispatcher {
  /**
   * @param {import('../view/viewport.js').Viewport} viewport
   * @param {{ gizmoAt?: (event: PointerEvent) => boolean, brushRadius?: () => number,
   *           tool?: () => { tool: string, erase: boolean } }} options
   *   gizmoAt: whether a press there belongs to the gizmo; brushRadius: world-space radius of the brush;
   *   tool: the current tool and erase mode (settings)
   */
  constructor(viewport, { gizmoAt = () => false, brushRadius = () => 0.05, tool = () => ({ tool: 'pick', erase: false }) } = {}) {
    super();
    this.viewport = viewport;
    this.gizmoAt = gizmoAt;
    this.brushRadius = brushRadius;
    this.tool = tool;
    this.enabled = true;
    this.stroke = null; // { mode: 'brush' | 'lasso', op, pointerId, longPress }
    this.down = null; // a press that may become a tap (or a long press)
    this.lasso = [];
    this.touches = new Map(); // touch pointers down on the canvas: id -> { clientX, clientY }
    this.longPressTimer = 0;
    this.svg = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
    this.svg.setAttribute('class', 'sd-lasso');
    this.polyline = document.createElementNS('http://www.w3.org/2000/svg', 'polyline');
    this.svg.appendChild(this.polyline);
    this.cursor = new BrushCursor(this.svg);
    viewport.element.appendChild(this.svg);

    this.listeners = { pointerdown: (e) => this.onDown(e), pointermove: (e) => this.onMove(e), pointerup: (e) => this.onUp(e),
      pointercancel: (e) => this.onUp(e) };
    for (const [type, listener] of Object.entries(this.listeners)) viewport.element.addEventListener(type, listener, true);
  }

  dispose() {
    clearTimeout(this.longPressTimer);
    for (const [type, listener] of Object.entries(this.listeners)) this.viewport.element.removeEventListener(type, listener, true);
    this.svg.remove();
  }

  #local(event) {
    const rect = this.viewport.canvas.getBoundingClientRect();
    return { x: event.clientX - rect.left, y: event.clientY - rect.top, w: rect.width, h: rect.height };
  }

  /** The surface hit under a pointer event, or null. */
  hit(event) {
    const mesh = this.viewport.meshView.mesh;
    if (!mesh) return null;
    this.viewport.meshView.updateBounds();
    const p = this.#local(event);
    _ndc.set((p.x / p.w) * 2 - 1, -(p.y / p.h) * 2 + 1);
    raycaster.setFromCamera(_ndc, this.viewport.camera);
    const hits = raycaster.intersectObject(mesh, false);
    return hits[0] ?? null;
  }

  onDown(event) {
    if (!this.enabled || event.button !== 0 || event.target !== this.viewport.canvas || isHandedOver(event)) return;
    if (event.pointerType === 'touch') this.touches.set(event.pointerId, { clientX: event.clientX, clientY: event.clientY });
    if (this.touches.size > 1) {
      this.#secondFinger(event);
      return;
    }
    const { tool, erase } = this.tool();
    const op = erase !== (event.ctrlKey || event.metaKey) ? 'remove' : 'add';
    const gizmo = this.gizmoAt(event);
    const byKey = event.shiftKey ? 'brush' : event.altKey ? 'lasso' : null;
    const mode = byKey ?? (!gizmo && (tool === 'brush' || tool === 'lasso') ? tool : null);
    if (mode) {
      event.stopPropagation();
      event.preventDefault();
      this.#startStroke(event, mode, op);
      return;
    }
    this.down = { x: event.clientX, y: event.clientY, t: performance.now(), op, gizmo, pointerId: event.pointerId, pick: tool === 'pick' };
    if (tool === 'pick' && !gizmo && event.pointerType !== 'mouse') this.#armLongPress(event);
  }

  onMove(event) {
    if (this.touches.has(event.pointerId)) this.touches.set(event.pointerId, { clientX: event.clientX, clientY: event.clientY });
    const down = this.down;
    if (down && down.pointerId === event.pointerId && Math.hypot(event.clientX - down.x, event.clientY - down.y) > TAP_SLOP_PX) {
      clearTimeout(this.longPressTimer); // a drag: it orbits
    }
    const stroke = this.stroke;
    if (!stroke || stroke.pointerId !== event.pointerId) return;
    event.stopPropagation();
    if (stroke.mode === 'brush') {
      this.#paint(event);
    } else {
      this.lasso.push(this.#local(event));
      this.#drawLasso();
    }
  }

  onUp(event) {
    this.touches.delete(event.pointerId);
    clearTimeout(this.longPressTimer);
    const stroke = this.stroke;
    if (stroke && stroke.pointerId === event.pointerId) {
      // OrbitControls still tracks the pointer of a long press (it began as an orbit): it must see the release.
      if (!stroke.longPress) event.stopPropagation();
      if (event.type === 'pointercancel') this.#cancelStroke();
      else this.#endStroke(event);
      return;
    }
    const down = this.down;
    if (!down || down.pointerId !== event.pointerId) return;
    this.down = null;
    if (!down.pick || down.gizmo || this.gizmoAt(event) || event.type === 'pointercancel') return;
    const moved = Math.hypot(event.clientX - down.x, event.clientY - down.y);
    if (moved > TAP_SLOP_PX || performance.now() - down.t > TAP_MS) return; // that was an orbit drag
    const hit = this.hit(event);
    if (!hit) return;
    this.dispatchEvent({ type: 'pick', vertex: nearestCorner(hit, this.viewport.meshView.positions), op: down.op });
  }

  #startStroke(event, mode, op, { longPress = false } = {}) {
    this.down = null;
    this.stroke = { mode, op, pointerId: event.pointerId, longPress };
    try {
      this.viewport.canvas.setPointerCapture(event.pointerId);
    } catch {
      // a synthetic or already released pointer: the stroke still works while the pointer is over the canvas
    }
    this.dispatchEvent({ type: 'stroke', phase: 'start' });
    if (mode === 'brush') this.#paint(event);
    else this.lasso = [this.#local(event)];
    this.#drawLasso();
  }

  #endStroke(event) {
    if (this.stroke.mode === 'lasso') this.#finishLasso();
    this.dispatchEvent({ type: 'stroke', phase: 'end' });
    this.#clearStroke(event.pointerId);
  }

  /**
   * A new model: a stroke under way ends where it is, and a press waits for no tap (the pointer still held down
   * must not go on painting or selecting on the new mesh). Its later moves and its release do nothing.
   */
  endStroke() {
    this.down = null;
    clearTimeout(this.longPressTimer);
    if (!this.stroke) return;
    this.dispatchEvent({ type: 'stroke', phase: 'end' });
    this.#clearStroke(this.stroke.pointerId);
  }

  /** Ends the current stroke without its effect: the listener restores the selection of 'start'. */
  #cancelStroke() {
    if (!this.stroke) return;
    this.dispatchEvent({ type: 'stroke', phase: 'cancel' });
    this.#clearStroke(this.stroke.pointerId);
  }

  #clearStroke(pointerId) {
    if (this.stroke.longPress) this.viewport.controls.enabled = true;
    this.stroke = null;
    this.lasso = [];
    this.cursor.hide();
    this.#drawLasso();
    if (this.viewport.canvas.hasPointerCapture(pointerId)) this.viewport.canvas.releasePointerCapture(pointerId);
  }

  /** Pick tool, touch or pen: a press held still becomes a brush stroke (as Shift-drag with a mouse). */
  #armLongPress(event) {
    clearTimeout(this.longPressTimer);
    const pointerId = event.pointerId;
    this.longPressTimer = setTimeout(() => {
      const down = this.down;
      if (!down || down.pointerId !== pointerId || this.touches.size > 1 || !this.hitAt(down.x, down.y)) return;
      this.viewport.controls.enabled = false; // the press began as an orbit: the camera stays where it is now
      this.#startStroke({ pointerId, clientX: down.x, clientY: down.y }, 'brush', down.op, { longPress: true });
      globalThis.navigator?.vibrate?.(15);
    }, LONG_PRESS_MS);
  }

  /** Whether the mesh is under a client position. */
  hitAt(clientX, clientY) {
    return this.hit({ clientX, clientY }) !== null;
  }

  /**
   * A second finger: no tap, and a stroke in progress is cancelled and both fingers go to OrbitControls (pinch
   * zoom and two-finger pan), which has not seen the first one: it was the stroke's.
   */
  #secondFinger(event) {
    clearTimeout(this.longPressTimer);
    this.down = null;
    const stroke = this.stroke;
    if (!stroke) return;
    const first = this.touches.get(stroke.pointerId);
    const longPress = stroke.longPress; // OrbitControls already holds the first finger of a long press
    this.#cancelStroke();
    if (first && !longPress) handOverToOrbit(this.viewport.canvas, stroke.pointerId, first);
    else if (!first) this.touches.delete(event.pointerId);
  }

  #paint(event) {
    const hit = this.hit(event);
    if (!hit) {
      this.cursor.hide();
      return;
    }
    const radius = this.brushRadius();
    this.cursor.show(this.#local(event), radius, hit.distance, this.viewport.camera);
    const positions = this.viewport.meshView.positions;
    const r2 = radius ** 2;
    const p = hit.point;
    const vertices = [];
    for (let v = 0, n = positions.length / 3; v < n; ++v) {
      const dx = positions[3 * v] - p.x;
      const dy = positions[3 * v + 1] - p.y;
      const dz = positions[3 * v + 2] - p.z;
      if (dx * dx + dy * dy + dz * dz <= r2) vertices.push(v);
    }
    if (vertices.length === 0) vertices.push(nearestCorner(hit, positions));
    this.dispatchEvent({ type: 'select', vertices, op: this.stroke.op });
  }

  #finishLasso() {
    const polygon = this.lasso;
    if (polygon.length < 3) return;
    const { w, h } = polygon[0];
    const camera = this.viewport.camera;
    const geometry = this.viewport.meshView.geometry;
    if (!geometry) return;
    if (this.viewport.meshView.material.flatShading) geometry.computeVertexNormals(); // flat mode skips them per update
    const positions = geometry.attributes.position.array;
    const normals = geometry.attributes.normal.array;
    camera.getWorldPosition(_eye);
    const vertices = [];
    for (let v = 0, n = positions.length / 3; v < n; ++v) {
      _v.fromArray(positions, 3 * v);
      _n.fromArray(normals, 3 * v);
      // Front-facing only, so the lasso does not grab the far side of the model.
      if (_n.dot(_d.subVectors(_eye, _v)) <= 0) continue;
      _v.project(camera);
      if (_v.z > 1) continue;
      const x = ((_v.x + 1) / 2) * w;
      const y = ((1 - _v.y) / 2) * h;
      if (insidePolygon(x, y, polygon)) vertices.push(v);
    }
    this.dispatchEvent({ type: 'select', vertices, op: this.stroke.op });
  }

  #drawLasso() {
    this.polyline.setAttribute('points', this.lasso.map((p) => `${p.x},${p.y}`).join(' '));
  }
}

/** The corner of the hit triangle closest to the hit point. */
export function nearestCorner(hit, positions) {
  let best = hit.face.a;
  let bestD = Infinity;
  for (const v of [hit.face.a, hit.face.b, hit.face.c]) {
    const d = _v.fromArray(positions, 3 * v).distanceToSquared(hit.point);
    if (d < bestD) {
      bestD = d;
      best = v;
    }
  }
  return best;
}

/** Even-odd point-in-polygon test in screen coordinates. */
export function insidePolygon(x, y, polygon) {
  let inside = false;
  for (let i = 0, j = polygon.length - 1; i < polygon.length; j = i++) {
    const a = polygon[i];
    const b = polygon[j];
    if (a.y > y !== b.y > y && x < ((b.x - a.x) * (y - a.y)) / (b.y - a.y) + a.x) inside = !inside;
  }
  return inside;
}
