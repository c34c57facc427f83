// The app's one undo timeline (docs/app.md): the handle groups, the skeleton and the painted volume parts each
// keep their own history (undo_history.js), and this orders them. Each step is stamped when its edit is made;
// undo takes back the newest step of any history, redo brings back the oldest undone one (every undone step is
// newer than every step still done, so that is the last one undone). A new edit in any history clears the redo
// of all of them: redo never brings back a step undone before it (a bone undone, then a handle moved, must not
// come back over the handle's edit).

/**
 * @typedef {{ history: import('./undo_history.js').UndoHistory, undo: () => boolean, redo: () => boolean,
 *             busy?: () => boolean }} Track
 *   undo, redo: take back or bring back the history's own step; busy: an edit is on its way (the skeleton's
 *   waits for its workers), so this history's next step is the newest
 */

export class EditTimeline {
  #clock = 0;
  /** @type {Track[]} */
  #tracks = [];

  /** @param {Track} track */
  join(track) {
    this.#tracks.push(track);
  }

  /** A new step of `history`: its stamp. Every other history's redo is cleared (a new edit ends them all). */
  stamp(history) {
    for (const track of this.#tracks) if (track.history !== history) track.history.clearRedo();
    return ++this.#clock;
  }

  /** The track whose step undo (or redo) takes next, or null. */
  first(way) {
    let best = null;
    let bestKey = way === 'undo' ? -Infinity : Infinity;
    for (const track of this.#tracks) {
      const busy = track.busy?.() ?? false;
      const key = way === 'undo' ? (busy ? Infinity : track.history.undoStamp) : (busy ? -Infinity : track.history.redoStamp);
      if (way === 'undo' ? key > bestKey : key < bestKey) [best, bestKey] = [track, key];
    }
    return best;
  }

  /** Takes back the newest edit of any history; returns whether there was one. */
  undo() {
    return this.first('undo')?.undo() ?? false;
  }

  redo() {
    return this.first('redo')?.redo() ?? false;
  }

  get canUndo() { return this.#tracks.some((t) => t.history.canUndo); }
  get canRedo() { return this.#tracks.some((t) => t.history.canRedo); }
}
