// The skeleton in the app (issue 30; docs/method.md section 5.4, the skeleton constraint): joints inside the
// mesh and bones between them, kept rigid and straight by every view's solver. Built with the bone tool (bone_tool.js),
// loaded from a scene's "skeleton" and saved in scenes; drawn in every view (skeleton_view.js), following the
// deformed mesh through the solver's reports. The skeleton goes to every view's worker (setSkeleton) and again
// after every new binding of the same mesh (a new basis or cage, new compare views), as the volume parts do; a
// new mesh starts without one. A skeleton a worker refuses (a joint outside the mesh: an error with code
// 'invalid_skeleton') is named in the banner and the edit is taken back (the solver keeps the previous one).
//
// After every change it calls dispatch({ type: 'skeleton', joints, bones, tip, selectedBone, enabled }).
import { InputError } from '../../lib/errors.js';
import { SkeletonState } from './skeleton_state.js';
import { EditTimeline } from '../interaction/edit_timeline.js';
import { UndoHistory } from '../interaction/undo_history.js';
import { BoneTool } from './bone_tool.js';
import { anchorPoint } from './joint_placement.js';

/**
 * The banner's text for a refused skeleton: its message, said to be the skeleton's once (the solver's own messages
 * already begin with "skeleton:").
 * @param {Error} error
 */
function skeletonMessage(error) {
  return /^skeleton\b/.test(error.message) ? error.message : `skeleton: ${error.message}`;
}

export class Skeleton {
  /**
   * @param {{ views: import('../view/solver_views.js').SolverViews, banner: { show: Function },
   *           timeline?: EditTimeline, dispatch: (event: object) => void }} parts
   *   views: the views on screen (their `list` is read at each call); timeline: the app's one undo timeline, which
   *   the skeleton's edits share with the handles' and the parts' (edit_timeline.js)
   */
  constructor({ views, banner, timeline = new EditTimeline(), dispatch }) {
    Object.assign(this, { views, banner, timeline, dispatch });
    this.state = new SkeletonState();
    this.history = new UndoHistory(timeline);
    // An edit waiting for its workers is the newest: an undo meanwhile is meant for it.
    this.#track = { history: this.history, undo: () => this.#travel('undo'), redo: () => this.#travel('redo'), busy: () => this.#pending > 0 };
    timeline.join(this.#track);
    /** Whether the solvers keep the bones ("use bones" in the panel); off, the bones stay drawn but are not sent. */
    this.enabled = true;
    this.sent = JSON.stringify(null); // what the workers were last sent (answered or not), as text; null: unknown
    this.request = 0; // the latest send: older answers are dropped
  }

  /** The skeleton as a scene writes it ({ joints, bones }; docs/scene-format.md), or null without bones. */
  get sceneSpec() {
    return this.enabled ? this.state.value().value : null; // bones only drawn ("use bones" off) are not saved
  }

  get joints() { return this.state.joints.length; }
  get bones() { return this.state.bones.length; }

  /** The first view's last report ({ joints, bones: [{ lengthError, straightnessError, lambda, straightHard }] }), or null. */
  get report() {
    return this.views.list[0]?.skeletonView.report ?? null;
  }

  /** A new view: draws the skeleton and takes its taps while the bone tool is on (`active`). */
  attach(view, active) {
    view.boneTool = new BoneTool(view, { active, tap: (what) => this.#tap(what) });
    this.#draw([view]);
  }

  /** A model was bound: the same mesh keeps its skeleton (sent to the new workers), a new one starts without. */
  async onLoad(model, sameMesh) {
    if (!sameMesh) {
      this.state.clear();
      this.history.clear();
      this.sent = JSON.stringify(null);
      for (const view of this.views.list) view.skeletonView.follow(null);
    } else {
      this.sent = JSON.stringify(null); // new workers have none: send the bones again, if any
      await this.#send().catch(() => {});
    }
    this.#changed();
  }

  /**
   * Replaces the skeleton (a scene's, or a script's: { joints: [[x, y, z], ...], bones: [[a, b], ...] }, null for
   * none) in one undo step (`freshHistory`, a scene with its own model: with no undo history). Resolves with the first view's report; rejects (and names it in the banner) when a
   * solver refuses it, the previous skeleton kept. Its bones are kept ("use bones" on): a saved scene leaves out bones
   * not kept, and "use bones" unticked in the skeleton lesson, as its caption says, must not carry into its restart.
   */
  use(skeleton, { freshHistory = false } = {}) {
    return this.#edit(() => {
      try {
        this.state.fromValue(skeleton ?? null);
      } catch (error) {
        this.banner.show(skeletonMessage(error));
        throw error;
      }
    }).then(() => (freshHistory ? this.history.clear() : null)) // a scene's own model: no undo to a model without it
      .then(() => (skeleton && !this.enabled ? this.setEnabled(true) : this.#changed())).then(() => this.report);
  }

  /** Bones kept by the solvers (true) or only drawn (false). */
  async setEnabled(on) {
    this.enabled = !!on;
    await this.#send().catch(() => {});
    this.#changed();
  }

  /** The bone tool lets go: the next joint starts a new chain. */
  newChain() {
    this.state.newChain();
    this.#changed();
  }

  /** Deletes the selected bone, or the chain's tip joint with its bones (Del in the bone tool). */
  deleteSelected() {
    return this.#edit(() => this.state.deleteSelected()).then(() => this.report, () => this.report);
  }

  /** No joints, no bones (one undo step). */
  clear() {
    return this.#edit(() => this.state.clear()).then(() => this.report, () => this.report);
  }

  /** Adds a joint at rest position `rest` (drawn at `shown`), joined to the chain's tip; resolves with its index. */
  addJoint(rest, shown = rest) {
    return this.#edit(() => this.state.addJoint(rest, shown));
  }

  /** The next joint continues from joint `j` (again: the chain ends). */
  continueFrom(j) {
    if (!(Number.isInteger(j) && j >= 0 && j < this.state.joints.length)) throw new InputError(`skeleton: no joint ${j}`);
    this.state.continueFrom(j);
    this.#changed();
  }

  selectBone(b) {
    if (!(Number.isInteger(b) && b >= 0 && b < this.state.bones.length)) throw new InputError(`skeleton: no bone ${b}`);
    this.state.selectBone(b);
    this.#changed();
  }

  /** Undoes the last skeleton edit if it is the newest edit of the timeline; returns whether it did. */
  undo() {
    return this.timeline.first('undo') === this.#track && this.#travel('undo');
  }

  redo() {
    return this.timeline.first('redo') === this.#track && this.#travel('redo');
  }

  #track;

  // While an edit waits its turn or the workers' answer, the undo or redo waits behind it: it is meant for that edit,
  // and if the workers refused it there is nothing left to take back.
  #travel(way) {
    const travel = () => {
      if (!(way === 'undo' ? this.history.canUndo : this.history.canRedo)) return false;
      this.state.restore(this.history[way](this.state.snapshot()));
      this.#send().catch(() => {});
      this.#changed();
      return true;
    };
    if (this.#pending === 0) return travel();
    this.#queue = this.#queue.then(() => {
      if (!this.#lastRefused) travel();
    });
    return true;
  }

  get canUndo() { return this.history.canUndo; }
  get canRedo() { return this.history.canRedo; }

  #tap(what) {
    if (what.joint !== undefined) this.continueFrom(what.joint);
    else if (what.bone !== undefined) this.selectBone(what.bone);
    else if (what.place) this.addJoint(what.place.rest, what.place.shown).catch(() => {});
    else if (what.miss) this.banner.show(`bone tool: ${what.miss}`, { kind: 'info' });
    else this.newChain();
  }

  // An edit of the joints and bones, one at a time (taps faster than the workers answer wait their turn):
  // `change()` edits the state; then one undo step, unless the solvers refuse it. Resolves with what change returned.
  #edit(change) {
    const run = async () => {
      try {
        const before = this.state.snapshot();
        const result = change();
        await this.#commit(before);
        return result;
      } finally {
        --this.#pending;
      }
    };
    ++this.#pending;
    const next = this.#queue.then(run, run);
    this.#queue = next.catch(() => {});
    return next;
  }

  #queue = Promise.resolve();
  #pending = 0; // edits queued or waiting for the workers
  #lastRefused = false; // whether the workers refused the last edit

  // An edit made (`before`: the state before it): one undo step, unless the solvers refuse it.
  async #commit(before) {
    this.#lastRefused = false;
    if (this.state.sameStructure(before)) {
      this.#changed();
      return;
    }
    const stamp = this.history.record(before);
    this.#changed();
    try {
      await this.#send();
    } catch (error) {
      this.#lastRefused = true;
      this.history.drop(stamp); // and the redo the edit would have ended comes back
      this.state.restore(before);
      this.sent = null; // a later view may have refused it after the first took it: every view gets the old one again
      this.#send().catch(() => {});
      this.#changed();
      throw error;
    }
  }

  // Sends the skeleton (or null: disabled, no bones) to every view's worker, the first one first (it checks it).
  async #send() {
    const { value } = this.state.value();
    const skeleton = this.enabled ? value : null;
    const text = JSON.stringify(skeleton);
    // Compared with what was last sent, not with what was last answered: an undo and a redo at once would
    // otherwise find the redo's skeleton still "sent" while the undo's is on its way, and send nothing.
    if (text === this.sent) return;
    this.sent = text;
    const request = ++this.request;
    const views = this.views.list.filter((view) => view.session.client);
    try {
      for (const view of views) {
        const reply = await view.session.request('setSkeleton', { skeleton });
        if (request !== this.request) return; // a later send goes to every view
        view.skeletonView.follow(reply?.skeleton ?? null);
        view.session.partsChanged(); // solve again with the new constraint
      }
    } catch (error) {
      const refused = error.code === 'invalid_skeleton';
      if (request === this.request) this.sent = null; // some views may have it, some not: the next send goes to all
      // A refusal is named and thrown even when a later send (the bones switched off, new workers) went out since:
      // the edit that made it never happened. Any other failure of a superseded send is the later send's to report.
      if (request !== this.request && !refused) return;
      this.banner.show(skeletonMessage(error));
      throw error;
    }
  }

  #draw(views = this.views.list) {
    const { map } = this.state.value();
    const { shown, bones, tip, selectedBone } = this.state;
    const anchors = this.#anchors();
    for (const view of views) view.skeletonView.show({ shown, bones, tip, selectedBone, map, anchors });
  }

  // Each joint's anchor in the rest mesh (joint_placement.js), kept per position until the mesh changes.
  #anchors() {
    const mesh = this.views.list[0]?.model?.mesh;
    if (!mesh) return [];
    if (this.#anchored.mesh !== mesh.positions) this.#anchored = { mesh: mesh.positions, byPoint: new Map() };
    const byPoint = this.#anchored.byPoint;
    return this.state.joints.map((p) => {
      const key = p.join(',');
      if (!byPoint.has(key)) byPoint.set(key, anchorPoint(p, mesh.positions, mesh.indices));
      return byPoint.get(key);
    });
  }

  #anchored = { mesh: null, byPoint: new Map() };

  #changed() {
    this.#draw();
    const s = this.state;
    this.dispatch({ type: 'skeleton', joints: s.joints.length, bones: s.bones.length, tip: s.tip, selectedBone: s.selectedBone, enabled: this.enabled });
  }
}
