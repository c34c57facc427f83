// The app's keys: F / M make a fixed / moving group of the selection, Del removes the active group, Esc
// clears the selection, Ctrl+Z / Ctrl+Shift+Z (or Ctrl+Y) undo and redo handle edits, T / R switch the gizmo
// between translate and rotate, C shows or hides the cage, V (or Home) fits the view, P turns volume-parts
// painting on or off (the brush and lasso then paint parts), S pauses or resumes the solver and N advances it
// by one iteration (step-through), I turns cage-vertex picking for the influence view on or off (a click near a
// cage vertex then colours the mesh by its weight), B turns the bone tool on or off (skeleton/bone_tool.js; with it
// on, Del deletes the selected bone or joint and Esc starts a new chain).
//
// They work whenever the focus or the pointer is in the app: after a brush or lasso stroke (which keeps
// the pointer from the page, so nothing else would focus the app), after a click on a panel button, or with
// the pointer over a view and the focus anywhere on the host page. They never take keys typed into a
// text or number field, a select or an editable element (the panel's fields, the banner's cage size, the
// host page's forms), and with several apps on a page the one holding the focus gets them, else the one
// under the pointer. connect() / disconnect() / dispose() as three.js controls do. They never hold the app:
// they read the app's state (app_state.js) and send intents (app_intents.js), as the tool strip does.

/** Elements whose keys are their own: text-like inputs, selects, text areas, editable content. */
const NOT_TEXT = new Set(['button', 'checkbox', 'radio', 'range', 'color', 'file', 'submit', 'reset', 'image']);
export function isTextEntry(element) {
  if (!element || element.nodeType !== 1) return false;
  const tag = element.tagName;
  if (tag === 'TEXTAREA' || tag === 'SELECT' || element.isContentEditable) return true;
  return tag === 'INPUT' && !NOT_TEXT.has(String(element.type).toLowerCase());
}

export class KeyboardShortcuts {
  /**
   * @param {HTMLElement} element the app's root (focusable)
   * @param {{ state: import('../app_state.js').AppState, intents: ReturnType<typeof import('../app_intents.js').appIntents> }} app
   *   state: the settings the keys toggle; intents: what they do
   */
  constructor(element, { state, intents }) {
    this.element = element;
    this.state = state;
    this.intents = intents;
    this.document = element.ownerDocument;
    this.hover = false;
    /** [target, event type, listener, capture] for connect() / disconnect() */
    this.bindings = [
      // Capture: the picker stops brush and lasso presses before they bubble, and they must still focus.
      [element, 'pointerdown', (e) => this.onPointerDown(e), true],
      [element, 'pointerenter', () => (this.hover = true), false],
      [element, 'pointerleave', () => (this.hover = false), false],
      // Capture: lil-gui stops keys from its rows (buttons included) before they bubble to the document.
      [this.document, 'keydown', (e) => this.onKeyDown(e), true],
    ];
    this.connect();
  }

  connect() {
    for (const [target, type, listener, capture] of this.bindings) target.addEventListener(type, listener, capture);
  }

  disconnect() {
    for (const [target, type, listener, capture] of this.bindings) target.removeEventListener(type, listener, capture);
  }

  dispose() {
    this.disconnect();
  }

  onPointerDown(event) {
    // A press on a control keeps its own focus (a text field must get its caret); anywhere else the app
    // takes it, so that keys follow a brush or lasso stroke and a click in a view.
    if (!event.target.closest?.('input, select, textarea, button, [contenteditable]')) this.element.focus({ preventScroll: true });
  }

  /** Whether a key event is this app's: focus in the app, or the pointer over it with the focus in no other app. */
  owns(event) {
    if (event.defaultPrevented || isTextEntry(event.target)) return false;
    const active = this.document.activeElement;
    if (this.element.contains(active)) return true;
    return this.hover && !active?.closest?.('.sd-app');
  }

  onKeyDown(event) {
    if (event.altKey || !this.owns(event)) return;
    if (this.#handle(event.key.toLowerCase(), event.ctrlKey || event.metaKey, event.shiftKey)) event.preventDefault();
  }

  /** Runs the key's action; false when the key is not one of the app's. */
  #handle(key, mod, shift) {
    const intents = this.intents;
    if (mod) {
      if (key === 'z') shift ? intents.redo() : intents.undo();
      else if (key === 'y') intents.redo();
      else return false;
      return true;
    }
    const { settings } = this.state.current;
    const bones = settings.tool === 'bone';
    if (key === 'f' || key === 'm') intents.addGroupFromSelection(key === 'm');
    else if (bones && (key === 'delete' || key === 'backspace')) intents.deleteSelectedBone();
    else if (bones && key === 'escape') intents.newBoneChain();
    else if (key === 'b') intents.setOptions({ tool: bones ? 'pick' : 'bone' });
    else if (key === 'delete' || key === 'backspace') intents.removeActiveGroup();
    else if (key === 'escape') intents.clearSelection();
    else if (key === 't' || key === 'r') intents.setOptions({ gizmoMode: key === 't' ? 'translate' : 'rotate' });
    else if (key === 'c') intents.setOptions({ showCage: !settings.showCage });
    else if (key === 'v' || key === 'home') intents.fitView();
    else if (key === 'p') intents.togglePainting();
    else if (key === 's') intents.toggleStepping();
    else if (key === 'n') intents.nextStep();
    else if (key === 'i') intents.togglePicking();
    else return false;
    return true;
  }
}
