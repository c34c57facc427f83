// One kind of edit's undo and redo (the handle groups', the skeleton's, the painted parts'): stacks of what the
// state was before each edit, each step stamped by the app's one timeline (edit_timeline.js) with when the edit
// was made, so the timeline can tell which history took the newest step. What a snapshot is, its owner decides.

export class UndoHistory {
  /**
   * @param {import('./edit_timeline.js').EditTimeline} timeline the app's one timeline (it stamps each step)
   * @param {{ max?: number }} [options] max: the most steps kept (the oldest go first)
   */
  constructor(timeline, { max = 200 } = {}) {
    this.timeline = timeline;
    this.max = max;
    this.clear();
  }

  clear() {
    /** @type {{ snapshot: unknown, stamp: number }[]} */
    this.undoStack = [];
    this.redoStack = [];
  }

  /**
   * Call before an edit: `snapshot` is the state before it. A new edit clears every history's redo, this one's too
   * (the timeline does, and keeps them until drop() or the next edit). Returns the step's stamp.
   */
  record(snapshot) {
    const stamp = this.timeline.stamp(this);
    this.undoStack.push({ snapshot, stamp });
    if (this.undoStack.length > this.max) this.undoStack.shift();
    return stamp;
  }

  /**
   * Forgets a recorded step (an edit that never happened: refused, or cancelled by a second finger; default the
   * last). The redo its record cleared comes back: an edit that never happened must not end the user's redo.
   */
  drop(stamp = this.undoStamp) {
    const at = this.undoStack.findLastIndex((step) => step.stamp === stamp);
    if (at >= 0) this.undoStack.splice(at, 1);
    this.timeline.unstamp(stamp);
  }

  clearRedo() {
    this.redoStack = [];
  }

  get canUndo() { return this.undoStack.length > 0; }
  get canRedo() { return this.redoStack.length > 0; }

  /** When the step undo would take back was made (-Infinity: none). */
  get undoStamp() { return this.undoStack.at(-1)?.stamp ?? -Infinity; }
  /** When the step redo would bring back was made (Infinity: none). */
  get redoStamp() { return this.redoStack.at(-1)?.stamp ?? Infinity; }

  /** The step undo (or redo) would take, { snapshot, stamp }, or undefined. */
  peek(way) {
    return (way === 'undo' ? this.undoStack : this.redoStack).at(-1);
  }

  /** The snapshot to go back to; `current` (the state now) goes on the redo stack with the step's stamp. */
  undo(current) {
    const step = this.undoStack.pop();
    this.redoStack.push({ snapshot: current, stamp: step.stamp });
    return step.snapshot;
  }

  redo(current) {
    const step = this.redoStack.pop();
    this.undoStack.push({ snapshot: current, stamp: step.stamp });
    return step.snapshot;
  }
}
