// The skeleton being built in the app, as data (docs/app.md, the bone tool): joints in the model's rest
// coordinates, bones as pairs of joints, and what the bone tool has in hand: the chain's tip (the joint the
// next placed joint is joined to by a bone; -1: the next joint starts a new chain) and the selected bone.
// A joint that no bone uses yet (the first joint of a chain) is kept here but not sent to the solver: value()
// gives only the joints that bones use, renumbered, with the map back to these joints.
//
// Each joint also keeps where it was drawn when it was placed (`shown`: the point between the two surface hits
// on the deformed mesh), so that a joint no bone uses yet is drawn where it was tapped; joints of bones are
// drawn where the solver's reports put them.
import { InputError } from '../../lib/errors.js';

/** A joint's rest position as a plain [x, y, z] of finite numbers, or an InputError naming what is wrong. */
function point(p, what) {
  if (!Array.isArray(p) || p.length !== 3 || !p.every(Number.isFinite)) throw new InputError(`${what} must be [x, y, z] of finite numbers`);
  return [p[0], p[1], p[2]];
}

export class SkeletonState {
  constructor() {
    this.clear();
  }

  /** No joints, no bones, nothing in hand. */
  clear() {
    /** @type {number[][]} rest positions */
    this.joints = [];
    /** @type {number[][]} where each joint was drawn when placed (deformed space) */
    this.shown = [];
    /** @type {number[][]} pairs of joint indices */
    this.bones = [];
    this.tip = -1;
    this.selectedBone = -1;
  }

  get empty() {
    return this.joints.length === 0;
  }

  /** Everything, to put back later (undo). */
  snapshot() {
    return { joints: this.joints.map((p) => [...p]), shown: this.shown.map((p) => [...p]), bones: this.bones.map((b) => [...b]),
      tip: this.tip, selectedBone: this.selectedBone };
  }

  restore(snapshot) {
    this.joints = snapshot.joints.map((p) => [...p]);
    this.shown = snapshot.shown.map((p) => [...p]);
    this.bones = snapshot.bones.map((b) => [...b]);
    this.tip = snapshot.tip < this.joints.length ? snapshot.tip : -1;
    this.selectedBone = snapshot.selectedBone < this.bones.length ? snapshot.selectedBone : -1;
  }

  /** Whether the joints and bones (not what is in hand) equal a snapshot's. */
  sameStructure(snapshot) {
    return JSON.stringify([this.joints, this.bones]) === JSON.stringify([snapshot.joints, snapshot.bones]);
  }

  /**
   * A new joint at rest position `rest` (drawn at `shown` until a report moves it), joined by a bone to the
   * chain's tip if there is one; it becomes the tip. Returns its index.
   */
  addJoint(rest, shown = rest) {
    const j = this.joints.length;
    this.joints.push(point(rest, 'a joint'));
    this.shown.push(point(shown, 'a joint\'s drawn position'));
    if (this.tip >= 0) this.bones.push([this.tip, j]);
    this.tip = j;
    this.selectedBone = -1;
    return j;
  }

  /** The next joint continues from joint `j`; tapping the tip again ends the chain (the next joint starts a new one). */
  continueFrom(j) {
    this.tip = this.tip === j ? -1 : j;
    this.selectedBone = -1;
  }

  /** Selects bone `b` (again: deselects it); nothing else in hand. */
  selectBone(b) {
    this.selectedBone = this.selectedBone === b ? -1 : b;
    this.tip = -1;
  }

  /** Nothing in hand: the next joint starts a new chain. */
  newChain() {
    this.tip = -1;
    this.selectedBone = -1;
  }

  /** Whether deleteSelected() has something to delete. */
  get hasSelection() {
    return this.selectedBone >= 0 || this.tip >= 0;
  }

  /**
   * Deletes the selected bone, or the tip joint with its bones; joints left without any bone go too. Returns
   * whether something was deleted.
   */
  deleteSelected() {
    if (this.selectedBone >= 0) {
      this.bones.splice(this.selectedBone, 1);
      this.selectedBone = -1;
      this.#dropUnused();
      return true;
    }
    if (this.tip < 0) return false;
    const j = this.tip;
    this.bones = this.bones.filter((b) => b[0] !== j && b[1] !== j);
    this.tip = -1;
    this.#dropUnused([j]);
    return true;
  }

  // Removes the joints no bone uses (and `also`), renumbering the bones and the tip.
  #dropUnused(also = []) {
    const used = new Set(this.bones.flat());
    const drop = new Set([...also, ...this.joints.keys()].filter((j) => !used.has(j)));
    const renumber = [];
    let next = 0;
    for (let j = 0; j < this.joints.length; ++j) renumber.push(drop.has(j) ? -1 : next++);
    this.joints = this.joints.filter((_, j) => !drop.has(j));
    this.shown = this.shown.filter((_, j) => !drop.has(j));
    this.bones = this.bones.map(([a, b]) => [renumber[a], renumber[b]]);
    this.tip = this.tip >= 0 ? renumber[this.tip] : -1;
  }

  /**
   * What the solver keeps (the contract's skeleton: { joints, bones }) with the joints no bone uses left out
   * and the others renumbered in order; null without bones. `map[k]` is the joint of this state that the
   * value's joint k is.
   * @returns {{ value: { joints: number[][], bones: number[][] }|null, map: number[] }}
   */
  value() {
    if (!this.bones.length) return { value: null, map: [] };
    const used = [...new Set(this.bones.flat())].sort((a, b) => a - b);
    const index = new Map(used.map((j, k) => [j, k]));
    return {
      value: { joints: used.map((j) => [...this.joints[j]]), bones: this.bones.map(([a, b]) => [index.get(a), index.get(b)]) },
      map: used,
    };
  }

  /** Takes a skeleton value (a scene's; null: none): its joints are drawn at rest until a report comes. */
  fromValue(skeleton) {
    this.clear();
    if (!skeleton) return;
    const joints = skeleton.joints.map((p, j) => point(p, `skeleton joint ${j}`));
    for (const [k, bone] of skeleton.bones.entries()) {
      if (!Array.isArray(bone) || bone.length !== 2 || !bone.every((j) => Number.isInteger(j) && j >= 0 && j < joints.length) || bone[0] === bone[1]) {
        throw new InputError(`skeleton bone ${k} must be two different joint indices below ${joints.length}`);
      }
    }
    this.joints = joints;
    this.shown = joints.map((p) => [...p]);
    this.bones = skeleton.bones.map((b) => [...b]);
  }
}
