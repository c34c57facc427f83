// Vertex selection on one viewport. Click = the mesh vertex nearest to the clicked surface point;
// Shift-drag = brush (paints every vertex within a world-space radius of the surface under the cursor);
// Alt-drag = lasso (every front-facing vertex inside the drawn outline). Add Ctrl to remove instead of add.
// A plain drag still orbits: brush and lasso take the pointer before OrbitControls sees it (capture phase).
//
// Events: { type: 'pick', vertex, op } for a click; { type: 'select', vertices, op } for brush and lasso,
// op = 'add' | 'remove'.
import { EventDispatcher, Raycaster, Vector2, Vector3 } from 'three';

const _ndc = new Vector2();
const _v = new Vector3();
const _n = new Vector3();
const _eye = new Vector3();
const _d = new Vector3();
const raycaster = new Raycaster();

export class VertexPicker extends EventDispatcher {
  /**
   * @param {import('../view/viewport.js').Viewport} viewport
   * @param {{ isGizmoActive?: () => boolean, brushRadius?: () => number }} options
   *   brushRadius: world-space radius of the brush.
   */
  constructor(viewport, { isGizmoActive = () => false, brushRadius = () => 0.05 } = {}) {
    super();
    this.viewport = viewport;
    this.isGizmoActive = isGizmoActive;
    this.brushRadius = brushRadius;
    this.enabled = true;
    this.mode = null; // 'brush' | 'lasso' during a drag
    this.down = null;
    this.lasso = [];
    this.svg = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
    this.svg.setAttribute('class', 'sd-lasso');
    this.polyline = document.createElementNS('http://www.w3.org/2000/svg', 'polyline');
    this.svg.appendChild(this.polyline);
    viewport.element.appendChild(this.svg);

    this.onDown = this.onDown.bind(this);
    this.onMove = this.onMove.bind(this);
    this.onUp = this.onUp.bind(this);
    const el = viewport.element;
    el.addEventListener('pointerdown', this.onDown, true);
    el.addEventListener('pointermove', this.onMove, true);
    el.addEventListener('pointerup', this.onUp, true);
    el.addEventListener('pointercancel', this.onUp, true);
  }

  dispose() {
    const el = this.viewport.element;
    el.removeEventListener('pointerdown', this.onDown, true);
    el.removeEventListener('pointermove', this.onMove, true);
    el.removeEventListener('pointerup', this.onUp, true);
    el.removeEventListener('pointercancel', this.onUp, true);
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
    if (!this.enabled || event.button !== 0 || event.target !== this.viewport.canvas) return;
    const op = event.ctrlKey || event.metaKey ? 'remove' : 'add';
    if (event.shiftKey || event.altKey) {
      // Brush / lasso: keep the pointer from OrbitControls and TransformControls.
      event.stopPropagation();
      event.preventDefault();
      this.viewport.canvas.setPointerCapture(event.pointerId);
      this.mode = event.shiftKey ? 'brush' : 'lasso';
      this.op = op;
      if (this.mode === 'brush') this.#paint(event);
      else this.lasso = [this.#local(event)];
      this.#drawLasso();
      return;
    }
    this.down = { x: event.clientX, y: event.clientY, t: performance.now(), op, gizmo: this.isGizmoActive() };
  }

  onMove(event) {
    if (this.mode === 'brush') {
      event.stopPropagation();
      this.#paint(event);
    } else if (this.mode === 'lasso') {
      event.stopPropagation();
      this.lasso.push(this.#local(event));
      this.#drawLasso();
    }
  }

  onUp(event) {
    if (this.mode) {
      event.stopPropagation();
      if (this.mode === 'lasso') this.#finishLasso();
      this.mode = null;
      this.lasso = [];
      this.#drawLasso();
      if (this.viewport.canvas.hasPointerCapture(event.pointerId)) this.viewport.canvas.releasePointerCapture(event.pointerId);
      return;
    }
    const down = this.down;
    this.down = null;
    if (!down || down.gizmo || event.type === 'pointercancel') return;
    const moved = Math.hypot(event.clientX - down.x, event.clientY - down.y);
    if (moved > 4 || performance.now() - down.t > 600) return; // that was an orbit drag
    const hit = this.hit(event);
    if (!hit) return;
    this.dispatchEvent({ type: 'pick', vertex: nearestCorner(hit, this.viewport.meshView.positions), op: down.op });
  }

  #paint(event) {
    const hit = this.hit(event);
    if (!hit) return;
    const positions = this.viewport.meshView.positions;
    const r2 = this.brushRadius() ** 2;
    const p = hit.point;
    const vertices = [];
    for (let v = 0, n = positions.length / 3; v < n; ++v) {
      const dx = positions[3 * v] - p.x;
      const dy = positions[3 * v + 1] - p.y;
      const dz = positions[3 * v + 2] - p.z;
      if (dx * dx + dy * dy + dz * dz <= r2) vertices.push(v);
    }
    if (vertices.length === 0) vertices.push(nearestCorner(hit, positions));
    this.dispatchEvent({ type: 'select', vertices, op: this.op });
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
    this.dispatchEvent({ type: 'select', vertices, op: this.op });
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
