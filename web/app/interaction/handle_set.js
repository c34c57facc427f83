// Handle groups and their edit history. A group is a set of rest-mesh vertex indices that is either fixed
// (targets = rest positions; drawn blue) or moving (targets = rest positions moved by a rigid transform
// about the group's rest centroid; drawn orange). The Deformer receives the groups in order and one target
// row per handle vertex (docs/scene-format.md).
//
// Scene form of a group (docs/scene-format.md): { vertices, translate?, rotate?, along? | from? } with
// rotate = { axis: [x,y,z], angle: radians, center: [x,y,z] }. A group with translate or rotate is moving. A group
// dragged in the screen plane keeps the camera's line (handle_lines.js: "along" or "from"): the solver holds it
// only across the view, its depth left to the energy; any other edit of its transform makes it a point target.
import { EventDispatcher, Quaternion, Vector3 } from 'three';
import { InputError } from '../../lib/errors.js';
import { EditTimeline } from './edit_timeline.js';
import { UndoHistory } from './undo_history.js';

const _v = new Vector3();
const _c = new Vector3();
const _t = new Vector3();
const _q = new Quaternion();

/**
 * @typedef {{ vertices: number[], moving: boolean, translate: number[], rotation: number[], center: number[],
 *             line?: import('../../lib/handle_lines.js').HandleLine }} Group
 *   rotation: quaternion [x, y, z, w]; center: rest centroid of the group; line: null or absent for a point target.
 */

export class HandleSet extends EventDispatcher {
  #transforms = 0; // gizmo drags under way

  /** @param {EditTimeline} [timeline] the app's one undo timeline, shared with the skeleton and the parts */
  constructor(timeline = new EditTimeline()) {
    super();
    /** @type {Group[]} */
    this.groups = [];
    this.active = -1; // index of the group the gizmo edits
    this.history = new UndoHistory(timeline);
    timeline.join({ history: this.history, undo: () => this.undo(), redo: () => this.redo(), editing: () => this.transforming });
    this.rest = null; // Float64Array of rest positions
  }

  /** New model: forget groups and history. */
  setRest(restPositions) {
    this.rest = restPositions;
    this.groups = [];
    this.active = -1;
    this.history.clear();
    this.#changed('handles');
  }

  centroid(vertices) {
    _c.set(0, 0, 0);
    for (const v of vertices) _c.add(_v.fromArray(this.rest, 3 * v));
    return _c.divideScalar(Math.max(1, vertices.length)).toArray();
  }

  /** Adds a group (vertices already in a group move to the new one). Returns its index. */
  add(vertices, moving) {
    const unique = [...new Set(vertices)].filter((v) => Number.isInteger(v) && v >= 0 && 3 * v < this.rest.length);
    if (unique.length === 0) return -1;
    this.#record();
    const taken = new Set(unique);
    for (const g of this.groups) g.vertices = g.vertices.filter((v) => !taken.has(v));
    this.groups = this.groups.filter((g) => g.vertices.length > 0);
    const previous = this.groups[this.active];
    this.groups.push({ vertices: unique.sort((a, b) => a - b), moving, translate: [0, 0, 0], rotation: [0, 0, 0, 1], center: this.centroid(unique) });
    // The gizmo goes to a new moving group; a new fixed group leaves it on the moving group it was on.
    this.active = moving || !previous?.moving ? this.groups.length - 1 : this.groups.indexOf(previous);
    this.#changed('handles');
    return this.active;
  }

  remove(index) {
    if (index < 0 || index >= this.groups.length) return;
    this.#record();
    this.groups.splice(index, 1);
    this.active = Math.min(this.active, this.groups.length - 1);
    if (this.active >= 0 && !this.groups[this.active].moving) this.active = this.groups.findIndex((g) => g.moving);
    this.#changed('handles');
  }

  clear() {
    if (this.groups.length === 0) return;
    this.#record();
    this.groups = [];
    this.active = -1;
    this.#changed('handles');
  }

  /** Replaces all groups (API / scenes). `moving` lists group indices that move. */
  setGroups(groups, moving = []) {
    this.#record();
    this.groups = groups.map((vertices, i) => ({
      vertices: [...vertices],
      moving: moving.includes(i),
      translate: [0, 0, 0],
      rotation: [0, 0, 0, 1],
      center: this.centroid(vertices),
    }));
    this.active = this.groups.findIndex((g) => g.moving);
    this.#changed('handles');
  }

  groupOf(vertex) {
    return this.groups.findIndex((g) => g.vertices.includes(vertex));
  }

  setActive(index) {
    if (index === this.active) return;
    this.active = index;
    this.dispatchEvent({ type: 'active' });
  }

  /**
   * Call once before a continuous transform edit (a gizmo drag) so it undoes in one step. Until endTransform the
   * app's undo and redo do nothing (edit_timeline.js): taken mid-drag, the drag's next move would put the pose
   * undone back as a new step, and redo bring back a pose from the middle of the drag.
   */
  beginTransform() {
    this.#record();
    this.#transforms++; // counted: in compare mode two views' gizmos can be dragged at once, by two fingers
  }

  /** Call when that edit ends (the pointer is released): event 'release', and the solvers settle without waiting. */
  endTransform() {
    this.#transforms = Math.max(0, this.#transforms - 1);
    this.dispatchEvent({ type: 'release' });
  }

  /** A gizmo drag is under way (beginTransform .. endTransform). */
  get transforming() {
    return this.#transforms > 0;
  }

  /**
   * Sets a moving group's rigid transform; `record` = push an undo step first (single edits); `line`: the view's
   * line for a drag in the screen plane, null (a point target) for any other edit.
   */
  setTransform(index, translate, rotation = null, record = false, line = null) {
    const g = this.groups[index];
    if (!g) throw new InputError(`no handle group ${index} (there are ${this.groups.length})`);
    if (record) this.#record();
    g.moving = true;
    g.translate = [...translate];
    if (rotation) g.rotation = [...rotation];
    g.line = line;
    this.#changed('targets');
  }

  /** Each group's handle line (null: a point target), in group order. */
  lines() {
    return this.groups.map((g) => g.line ?? null);
  }

  /** Targets: one xyz row per handle vertex, groups in order. */
  targets() {
    const count = this.groups.reduce((n, g) => n + g.vertices.length, 0);
    const out = new Float64Array(3 * count);
    let k = 0;
    for (const g of this.groups) {
      this.#place(g, g.translate, g.rotation, out, 3 * k);
      k += g.vertices.length;
    }
    return out;
  }

  /**
   * Where group `index`'s vertices would go under `translate` and `rotation` (a quaternion; null: the group's own),
   * one xyz row each; nothing changes. A script's drag is checked with it before it is stored (handle_editor.js).
   */
  targetsWith(index, translate, rotation = null) {
    const g = this.groups[index];
    const out = new Float64Array(3 * g.vertices.length);
    this.#place(g, translate, rotation ?? g.rotation, out, 0);
    return out;
  }

  // Group g's vertices moved rigidly about its rest centroid, written into out from `offset`.
  #place(g, translate, rotation, out, offset) {
    _c.fromArray(g.center);
    _t.fromArray(translate);
    _q.fromArray(rotation);
    g.vertices.forEach((v, i) => _v.fromArray(this.rest, 3 * v).sub(_c).applyQuaternion(_q).add(_c).add(_t).toArray(out, offset + 3 * i));
  }

  vertexGroups() {
    return this.groups.map((g) => g.vertices);
  }

  /** Takes back the last handle edit (the app's undo takes back the newest edit of any kind: edit_timeline.js). */
  undo() {
    if (!this.history.canUndo) return false;
    this.#restore(this.history.undo(this.#snapshot()));
    return true;
  }

  redo() {
    if (!this.history.canRedo) return false;
    this.#restore(this.history.redo(this.#snapshot()));
    return true;
  }

  /** Scene JSON form (docs/scene-format.md). */
  toScene() {
    return this.groups.map((g) => {
      const out = { vertices: [...g.vertices] };
      // A fixed group can hold a line too (a scene's "along" without a translate): the solver honours it, so it
      // is saved whether or not the group moves.
      if (g.line) Object.assign(out, g.line);
      if (!g.moving) return out;
      out.translate = [...g.translate];
      _q.fromArray(g.rotation);
      const angle = 2 * Math.acos(Math.min(1, Math.abs(_q.w)));
      if (angle > 1e-12) {
        const s = Math.sin(angle / 2) * Math.sign(_q.w || 1);
        out.rotate = { axis: [_q.x / s, _q.y / s, _q.z / s], angle, center: [...g.center] };
      }
      return out;
    });
  }

  /**
   * Takes a scene's handles (docs/scene-format.md) as web/lib/scene.js parses them (parseScene,
   * parseSceneHandles); throws an Error naming a vertex the mesh does not have. A rotation about another
   * center is stored as the same rotation about the group's centroid plus a translation.
   * @param {import('../../lib/scene.js').SceneHandle[]} handles
   */
  fromScene(handles) {
    const n = this.rest.length / 3;
    const groups = handles.map((h, i) => {
      for (const v of h.vertices) {
        if (v >= n) throw new InputError(`scene: handles[${i}] uses vertex ${v}, but the mesh has ${n} vertices`);
      }
      const g = { vertices: [...h.vertices], moving: h.moving, translate: [...h.translate], rotation: [0, 0, 0, 1],
        center: this.centroid(h.vertices), line: h.line ?? null };
      if (h.rotate) {
        const q = new Quaternion().setFromAxisAngle(_v.fromArray(h.rotate.axis), h.rotate.angle);
        g.rotation = q.toArray();
        if (h.rotate.center) {
          const c = new Vector3().fromArray(h.rotate.center);
          const shift = new Vector3().fromArray(g.center).sub(c).applyQuaternion(q).add(c).sub(new Vector3().fromArray(g.center));
          g.translate = new Vector3().fromArray(g.translate).add(shift).toArray();
        }
      }
      return g;
    });
    this.#record();
    this.groups = groups;
    this.active = groups.findIndex((g) => g.moving);
    this.#changed('handles');
  }

  /** Every group back to no displacement (one undo step). */
  resetTransforms() {
    this.#record();
    for (const g of this.groups) {
      g.translate = [0, 0, 0];
      g.rotation = [0, 0, 0, 1];
      g.line = null;
    }
    this.#changed('targets');
  }

  /** Forgets the undo and redo history (a fresh model's first groups are not an edit). */
  clearHistory() {
    this.history.clear();
  }

  #snapshot() {
    return JSON.stringify({ groups: this.groups, active: this.active });
  }
  #restore(snapshot) {
    const s = JSON.parse(snapshot);
    // Same vertex groups = only targets changed: the solver then keeps its factorization.
    const sameGroups = JSON.stringify(s.groups.map((g) => g.vertices)) === JSON.stringify(this.groups.map((g) => g.vertices)) &&
      s.groups.every((g, i) => g.moving === this.groups[i].moving);
    this.groups = s.groups;
    this.active = s.active;
    this.#changed(sameGroups ? 'targets' : 'handles');
    if (sameGroups) this.dispatchEvent({ type: 'active' });
  }
  #record() {
    this.history.record(this.#snapshot());
  }
  #changed(what) {
    this.dispatchEvent({ type: 'change', what });
  }
}
