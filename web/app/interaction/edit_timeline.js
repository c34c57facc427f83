// The app's one undo timeline (docs/app.md): the handle groups, the skeleton and the painted volume parts each
// keep their own history (undo_history.js), and this orders them. Each step is stamped when its edit is made;
// undo takes back the newest step of any history, redo brings back the oldest undone one (every undone step is
// newer than every step still done, so that is the last one undone). A new edit in any history clears the redo
// of all of them: redo never brings back a step undone before it (a bone undone, then a handle moved, must not
// come back over the handle's edit). An edit that never happens (a stroke cancelled by a second finger, a bone the
// workers refuse) ends none: the redo its step cleared is kept until then, and comes back when the step is dropped.
// While an edit is under way (a gizmo drag, from its press to its release) undo and redo do nothing: the drag is one
// step, taken back once it has ended.

/**
 * @typedef {{ history: import('./undo_history.js').UndoHistory, undo: () => boolean, redo: () => boolean,
 *             busy?: () => boolean, editing?: () => boolean }} Track
 *   undo, redo: take back or bring back the history's own step; busy: an edit is on its way (the skeleton's
 *   waits for its workers), so this history's next step is the newest (for undo only: first()); editing: an edit
 *   is still being made (a gizmo drag): no undo or redo until it ends
 */

export class EditTimeline {
  #clock = 0;
  /** @type {Track[]} */
  #tracks = [];
  /** The redo the newest step cleared, per history, until a later step: { stamp, redo: Map<history, steps> }. */
  #cleared = null;

  /** @param {Track} track */
  join(track) {
    this.#tracks.push(track);
  }

  /** A new step of `history`: its stamp. Every history's redo is cleared (a new edit ends them all). */
  stamp(history) {
    const redo = new Map();
    for (const h of new Set([history, ...this.#tracks.map((track) => track.history)])) {
      redo.set(h, h.redoStack);
      h.clearRedo();
    }
    this.#cleared = { stamp: ++this.#clock, redo };
    return this.#clock;
  }

  /**
   * The step `stamp` never happened (its history dropped it): the redo its stamp cleared comes back, unless a later
   * step was stamped or something was undone since (the redo then is another).
   */
  unstamp(stamp) {
    const cleared = this.#cleared;
    if (cleared?.stamp !== stamp || this.#clock !== stamp) return;
    this.#cleared = null;
    if ([...cleared.redo.keys()].some((history) => history.canRedo)) return;
    for (const [history, steps] of cleared.redo) history.redoStack = steps;
  }

  /**
   * The track whose step undo (or redo) takes next, or null. A busy track wins the undo (it is meant for the edit on
   * its way) but not the redo: that edit will end every redo anyway, and if it turns out to change nothing, another
   * history's redo must still be there, so the redo goes by the stamps alone.
   */
  first(way) {
    let best = null;
    let bestKey = way === 'undo' ? -Infinity : Infinity;
    for (const track of this.#tracks) {
      const busy = way === 'undo' && (track.busy?.() ?? false);
      const key = way === 'undo' ? (busy ? Infinity : track.history.undoStamp) : track.history.redoStamp;
      if (way === 'undo' ? key > bestKey : key < bestKey) [best, bestKey] = [track, key];
    }
    return best;
  }

  /** Takes back the newest edit of any history; returns whether there was one (none while an edit is being made). */
  undo() {
    return !this.editing && (this.first('undo')?.undo() ?? false);
  }

  redo() {
    return !this.editing && (this.first('redo')?.redo() ?? false);
  }

  /** Whether an edit is still being made (a gizmo drag under way): undo and redo wait for its end. */
  get editing() { return this.#tracks.some((t) => t.editing?.() ?? false); }

  get canUndo() { return this.#tracks.some((t) => t.history.canUndo); }
  get canRedo() { return this.#tracks.some((t) => t.history.canRedo); }
}
