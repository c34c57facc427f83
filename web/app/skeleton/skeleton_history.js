// Undo and redo of the skeleton's edits (joints and bones added or deleted), in one timeline with the handle
// edits: Ctrl+Z (the tool strip's undo) takes back whichever was made last. The handle groups keep their own
// stacks (interaction/handle_set.js); each skeleton step remembers the top of the handles' stack when it was
// made (the snapshot object itself, so the handles' 200-step cap does not matter), and it is the newest edit
// exactly while that is still the top. Redo the same way with the redo stacks.

const MAX_STEPS = 200;

export class SkeletonHistory {
  constructor() {
    this.clear();
  }

  clear() {
    /** @type {{ snapshot: object, mark: unknown }[]} */
    this.undoStack = [];
    this.redoStack = [];
  }

  /**
   * Call before an edit: `snapshot` is the state before it; `handles` the handle set (its stacks).
   * @param {object} snapshot
   * @param {{ undoStack: unknown[], redoStack: unknown[] }} handles
   */
  record(snapshot, handles) {
    this.undoStack.push({ snapshot, mark: handles.undoStack.at(-1) });
    if (this.undoStack.length > MAX_STEPS) this.undoStack.shift();
    this.redoStack = [];
  }

  /** Forgets the last record (an edit the solver refused: it never happened). */
  drop() {
    this.undoStack.pop();
  }

  /** Whether the next undo is the skeleton's: its last edit came after the handles' last (or they have none). */
  undoesFirst(handles) {
    const step = this.undoStack.at(-1);
    return !!step && (step.mark === handles.undoStack.at(-1) || !handles.undoStack.length);
  }

  redoesFirst(handles) {
    const step = this.redoStack.at(-1);
    return !!step && (step.mark === handles.redoStack.at(-1) || !handles.redoStack.length);
  }

  /** The snapshot to go back to; `current` (the state now) goes on the redo stack. */
  undo(current, handles) {
    const step = this.undoStack.pop();
    this.redoStack.push({ snapshot: current, mark: handles.redoStack.at(-1) });
    return step.snapshot;
  }

  redo(current, handles) {
    const step = this.redoStack.pop();
    this.undoStack.push({ snapshot: current, mark: handles.undoStack.at(-1) });
    return step.snapshot;
  }
}
