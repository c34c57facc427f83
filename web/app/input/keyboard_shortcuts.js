// The app's keys, on its root element: F / M make a fixed / moving group of the selection, Del removes the
// active group, Esc clears the selection, Ctrl+Z / Ctrl+Shift+Z (or Ctrl+Y) undo and redo handle edits,
// T / R switch the gizmo between translate and rotate, C shows or hides the cage. Keys typed into the panel
// or a form field are theirs. A pointer press in the app focuses it, so the keys reach it.
// connect() / disconnect() / dispose() as three.js controls do.

export class KeyboardShortcuts {
  /**
   * @param {HTMLElement} element the app's root (focusable)
   * @param {import('../deformer_app.js').DeformerApp} app the public API the keys call
   */
  constructor(element, app) {
    this.element = element;
    this.app = app;
    /** [event type, listener] on the element, for connect() / disconnect() */
    this.bindings = [['pointerdown', (e) => this.onPointerDown(e)], ['keydown', (e) => this.onKeyDown(e)]];
    this.connect();
  }

  connect() {
    for (const [type, listener] of this.bindings) this.element.addEventListener(type, listener);
  }

  disconnect() {
    for (const [type, listener] of this.bindings) this.element.removeEventListener(type, listener);
  }

  dispose() {
    this.disconnect();
  }

  onPointerDown(event) {
    if (!event.target.closest?.('input, select, textarea, button')) this.element.focus({ preventScroll: true });
  }

  onKeyDown(event) {
    if (event.target !== this.element && event.target.closest?.('.lil-gui, input, select, textarea')) return;
    if (this.#handle(event.key.toLowerCase(), event.ctrlKey || event.metaKey, event.shiftKey)) event.preventDefault();
  }

  /** Runs the key's action; false when the key is not one of the app's. */
  #handle(key, mod, shift) {
    const app = this.app;
    if (mod) {
      if (key === 'z') shift ? app.redo() : app.undo();
      else if (key === 'y') app.redo();
      else return false;
      return true;
    }
    if (key === 'f' || key === 'm') app.addGroupFromSelection(key === 'm');
    else if (key === 'delete' || key === 'backspace') app.removeActiveGroup();
    else if (key === 'escape') app.clearSelection();
    else if (key === 't' || key === 'r') app.setOptions({ gizmoMode: key === 't' ? 'translate' : 'rotate' });
    else if (key === 'c') app.setOptions({ showCage: !app.settings.showCage });
    else return false;
    return true;
  }
}
