// Handle editing shared by every view: the handle groups (HandleSet) and the pending selection that clicks,
// the brush and the lasso build before F / M turn it into a group.
//
// Events: { type: 'change', what } with what = 'handles' (groups changed: the solvers need them again),
// 'targets' (only displacements changed), 'active' (the gizmo's group) or 'selection'.
import { Box3, EventDispatcher, Quaternion, Vector3 } from 'three';
import { InputError } from '../../lib/errors.js';
import { describeValue } from '../../lib/options.js';
import { MAX_MESH_COORDINATE, assertTargetsNear, beyondMeshCoordinates } from '../../lib/mesh.js';
import { parseSceneHandles, unitAxis } from '../../lib/scene.js';
import { HandleSet } from './handle_set.js';

export class HandleEditor extends EventDispatcher {
  /** @param {import('./edit_timeline.js').EditTimeline} [timeline] the app's one undo timeline */
  constructor(timeline) {
    super();
    this.handles = new HandleSet(timeline);
    /** @type {Set<number>} vertices picked but not yet in a group */
    this.selection = new Set();
    this.handles.addEventListener('change', (e) => this.#changed(e.what));
    this.handles.addEventListener('active', () => this.#changed('active'));
  }

  /**
   * A new model. Its groups: `keep` (scene form, e.g. the same mesh with a new cage), else the default ends.
   * @param {Float64Array} restPositions
   * @param {{ keep?: object[]|null, defaults?: { axis: number, fixedBelow: number, movingAbove: number } }} [options]
   */
  setModel(restPositions, { keep = null, defaults } = {}) {
    this.selection.clear();
    this.handles.setRest(restPositions);
    const groups = keep ? null : defaultGroups(restPositions, defaults);
    if (keep) this.handles.fromScene(parseSceneHandles(keep));
    else if (groups) this.handles.setGroups(groups, [1]);
    this.handles.clearHistory();
  }

  /** A click on vertex `vertex`: toggles it in the selection, or activates its group when nothing is selected. */
  pick(vertex, op) {
    if (op === 'remove') {
      this.selection.delete(vertex);
    } else {
      const group = this.handles.groupOf(vertex);
      if (group >= 0 && this.selection.size === 0) this.handles.setActive(group);
      else if (this.selection.has(vertex)) this.selection.delete(vertex);
      else this.selection.add(vertex);
    }
    this.#changed('selection');
  }

  /** Brush or lasso: adds or removes many vertices. */
  select(vertices, op) {
    for (const v of vertices) op === 'remove' ? this.selection.delete(v) : this.selection.add(v);
    this.#changed('selection');
  }

  /**
   * A scene's groups, the selection cleared. `freshHistory` (a scene with its own model): no undo step back to the
   * groups the model was loaded with, which were never on screen; else one undo step back to the groups before.
   */
  fromScene(handles, { freshHistory = false } = {}) {
    this.handles.fromScene(handles);
    if (freshHistory) this.handles.clearHistory();
    this.clearSelection();
  }

  clearSelection() {
    this.selection.clear();
    this.#changed('selection');
  }

  /** What a stroke may change (the selection), to put back if it is cancelled (a second finger: a pinch). */
  saveStroke() {
    return new Set(this.selection);
  }

  restoreStroke(saved) {
    this.selection = new Set(saved);
    this.#changed('selection');
  }

  /** Turns the selection into a new group; returns its index, or -1 when nothing is selected. */
  addGroupFromSelection(moving) {
    if (this.selection.size === 0) return -1;
    const vertices = [...this.selection];
    this.selection.clear();
    const index = this.handles.add(vertices, moving);
    if (index < 0) this.#changed('selection');
    return index;
  }

  /**
   * Replaces every group (scripting API), checking the indices against the mesh.
   * @param {number[][]} groups vertex indices
   * @param {number[]} [moving] indices of the moving groups (default: the last group)
   */
  setGroups(groups, moving) {
    if (!Array.isArray(groups)) throw new InputError('setHandles: groups must be arrays of vertex indices');
    const n = this.handles.rest.length / 3;
    const groupOf = new Map(); // the rules of Deformer.setHandles and of a scene's handles: no empty group, no vertex twice
    for (let i = 0; i < groups.length; ++i) { // index loops: a sparse array's holes are named, not skipped
      const g = groups[i];
      if (!Array.isArray(g)) throw new InputError(`setHandles: group ${i} is ${i in groups ? 'not an array of vertex indices' : 'missing (a hole in the array)'}`);
      if (g.length === 0) throw new InputError(`setHandles: group ${i} is empty`);
      for (let k = 0; k < g.length; ++k) {
        const v = g[k];
        if (!Number.isInteger(v) || v < 0 || v >= n) throw new InputError(`setHandles: group ${i} has vertex ${describeValue(v)}, but the mesh has ${n} vertices`);
        if (groupOf.has(v)) throw new InputError(`setHandles: vertex ${v} is in group ${groupOf.get(v)} and group ${i}`);
        groupOf.set(v, i);
      }
    }
    if (moving !== undefined && !(Array.isArray(moving) && moving.every((m) => Number.isInteger(m) && m >= 0 && m < groups.length))) {
      throw new InputError(`setHandles: moving must list group indices from 0 to ${groups.length - 1} (got ${describeValue(moving)})`);
    }
    this.handles.setGroups(groups, moving ?? [groups.length - 1]);
  }

  /**
   * Moves group `index` rigidly (one undo step): translation, optional { axis, angle } about its rest centroid.
   * Everything is checked first (a NaN would be stored and saved as null in a scene; a target beyond 1e30 would
   * overflow the solve): an InputError names it.
   */
  move(index, translation, rotation = null) {
    const count = this.handles.groups.length;
    if (!(Number.isInteger(index) && index >= 0 && index < count)) {
      throw new InputError(`drag: index must be a handle group from 0 to ${count - 1} (got ${describeValue(index)})`);
    }
    checkVector(translation, 'drag: translation');
    let q = null;
    if (rotation !== null && rotation !== undefined) {
      if (typeof rotation !== 'object') throw new InputError('drag: rotation must be { axis: [x, y, z], angle } (radians)');
      checkVector(rotation.axis, 'drag: rotation.axis');
      const unit = unitAxis(rotation.axis); // not three's normalize(): its squared length overflows past 1e154
      if (!unit) throw new InputError('drag: rotation.axis must not be zero');
      if (!Number.isFinite(rotation.angle)) throw new InputError(`drag: rotation.angle must be a finite number (got ${describeValue(rotation.angle)})`);
      q = new Quaternion().setFromAxisAngle(new Vector3(...unit), rotation.angle).toArray();
    }
    // Targets beyond what a mesh may have are refused as a scene's are, before the group changes (the worker
    // would refuse them later, with the group already moved).
    const moved = this.handles.targetsWith(index, translation, q);
    const far = moved.findIndex((x) => !(Math.abs(x) <= MAX_MESH_COORDINATE));
    if (far >= 0) {
      const vertex = this.handles.groups[index].vertices[Math.floor(far / 3)];
      throw new InputError(`drag: handle group ${index} moves vertex ${vertex} to ${beyondMeshCoordinates(Math.abs(moved[far]))}: ` +
        'use a smaller translation, or rescale the model');
    }
    this.handles.setTransform(index, translation, q, true);
  }

  /**
   * Raw targets (setTargets) as a Float64Array, checked: one finite xyz row per handle vertex, groups in order, none
   * beyond MAX_MESH_COORDINATE (1e30).
   */
  checkTargets(targets) {
    if (!Array.isArray(targets) && !ArrayBuffer.isView(targets)) throw new InputError('setTargets: targets must be an array of numbers');
    const count = this.handles.groups.reduce((k, g) => k + g.vertices.length, 0);
    if (targets.length !== 3 * count) throw new InputError(`setTargets: expected ${3 * count} numbers (3 per handle vertex), got ${targets.length}`);
    // Each entry looked at before any conversion: Number() of an object runs its code, or throws.
    for (let i = 0; i < targets.length; ++i) {
      const x = targets[i];
      if (typeof x !== 'number' || !Number.isFinite(x)) {
        throw new InputError(`setTargets: target ${Math.floor(i / 3)} is not 3 finite numbers (got ${describeValue(x)})`);
      }
    }
    const checked = Float64Array.from(targets);
    assertTargetsNear(checked, 'setTargets'); // the library's limit and words (Deformer.setTargets), before any view has them
    return checked;
  }

  /** What the panel shows: group counts and the selection size. */
  summary() {
    const groups = this.handles.groups;
    const fixed = groups.filter((g) => !g.moving).length;
    return { fixed, moving: groups.length - fixed, selected: this.selection.size };
  }

  #changed(what) {
    this.dispatchEvent({ type: 'change', what });
  }
}

/** Throws an InputError unless `value` is an array of 3 finite numbers. */
function checkVector(value, what) {
  if (!Array.isArray(value) || value.length !== 3 || !value.every((x) => typeof x === 'number' && Number.isFinite(x))) {
    throw new InputError(`${what} must be an array of 3 finite numbers (got ${describeValue(value)})`);
  }
}

/**
 * One end fixed, the other end moving: ready to drag. By default the ends of the longest axis; an example may
 * name the axis and the fractions (the bunny: feet fixed, ears moving). Null when an end has no vertex.
 * @param {Float64Array} p rest positions
 * @param {{ axis: number, fixedBelow: number, movingAbove: number }} [spec]
 * @returns {number[][]|null} [fixed, moving]
 */
function defaultGroups(p, spec) {
  const box = new Box3().setFromArray(p);
  const size = box.getSize(new Vector3());
  const axis = spec?.axis ?? (size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2);
  const fixedBelow = spec?.fixedBelow ?? 0.08;
  const movingAbove = spec?.movingAbove ?? 0.92;
  const lo = box.min.getComponent(axis);
  const extent = size.getComponent(axis);
  const fixed = [];
  const moving = [];
  for (let v = 0; v < p.length / 3; ++v) {
    const t = (p[3 * v + axis] - lo) / extent;
    if (t <= fixedBelow) fixed.push(v);
    else if (t >= movingAbove) moving.push(v);
  }
  return fixed.length && moving.length ? [fixed, moving] : null;
}
