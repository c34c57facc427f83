// The tool strip: every action of the keys and modifiers as a button sized for a finger, so that a phone or a
// tablet needs no keyboard (docs/app.md, "Touch and pen"). What a one-finger press in a view does (orbit, pick,
// brush, lasso, bone, erase: settings.tool and settings.erase); making a fixed or moving group of the selection;
// the gizmo's mode; undo and redo; fit view; stepping the solver; the help; the control panel.
// Like the panel it calls only the app's public API and follows the app's events ('options', 'handles',
// 'panel', 'stepping', 'dispose'); the app never calls into it.
import { icon } from './icons.js';

/** The buttons, in order; null is a gap between groups. kind: 'tool' (one of settings.tool), 'toggle', 'action'. */
const BUTTONS = [
  { id: 'orbit', kind: 'tool', label: 'orbit', title: 'Orbit: one finger (or the left button) turns the view; taps select nothing. Two fingers zoom and pan in every tool.' },
  { id: 'pick', kind: 'tool', label: 'pick', title: 'Pick: tap a vertex to select it (again to deselect; a vertex of a group makes that group active); drag to orbit; press and hold, then drag, to brush' },
  { id: 'brush', kind: 'tool', label: 'brush', title: 'Brush: drag over the mesh to select every vertex under the brush (Shift-drag with a mouse; radius: panel, Handles)' },
  { id: 'lasso', kind: 'tool', label: 'lasso', title: 'Lasso: draw around vertices to select the front-facing ones inside (Alt-drag with a mouse)' },
  { id: 'bone', kind: 'tool', label: 'bone', title: 'Bone: tap inside a limb to place a joint (midway through it), tap again further on for a bone; tap a joint to continue from it, a bone to select it (Del deletes; B)' },
  { id: 'erase', kind: 'toggle', label: 'erase', title: 'Erase: pick, brush and lasso remove from the selection instead of adding (Ctrl with a mouse)' },
  null,
  { id: 'fixed', kind: 'action', label: 'fixed', title: 'Make a fixed group of the selection (F)' },
  { id: 'moving', kind: 'action', label: 'moving', title: 'Make a moving group of the selection (M): then drag its gizmo' },
  { id: 'gizmo', kind: 'action', label: 'move', title: 'The gizmo: translate or rotate the moving group (T / R)' },
  null,
  { id: 'undo', kind: 'action', label: 'undo', title: 'Undo the last handle edit (Ctrl+Z)' },
  { id: 'redo', kind: 'action', label: 'redo', title: 'Redo (Ctrl+Shift+Z)' },
  { id: 'fit', kind: 'action', label: 'fit', title: 'Fit view: frame the model, its handles and the cage (V)' },
  null,
  { id: 'stepping', kind: 'toggle', label: 'pause', title: 'Pause the solver, then advance it one iteration at a time and see what each does (S)' },
  { id: 'next', kind: 'action', label: 'step', title: 'One iteration in every view, shown in the view: the step, the line search, lambda, the energies (N)' },
  { id: 'half', kind: 'action', label: 'local', title: 'ARAP: half an iteration: the local step (best rotations) or the global step (positions for them)' },
  { id: 'help', kind: 'toggle', label: 'help', title: 'What every touch, click and key does' },
  { id: 'panel', kind: 'toggle', label: 'panel', title: 'The control panel: model, solver, handles, volume parts, display, export, stats' },
];
const TOOL_IDS = BUTTONS.filter((b) => b?.kind === 'tool').map((b) => b.id);

export class ToolStrip {
  /**
   * @param {import('../deformer_app.js').DeformerApp} app
   * @param {HTMLElement} element the strip's container (AppLayout.tools)
   * @param {{ help: import('./help_overlay.js').HelpOverlay, panel: boolean }} options help: the overlay the
   *   help button shows; panel: whether the app has a control panel (else no panel button)
   */
  constructor(app, element, { help, panel }) {
    this.app = app;
    this.element = element;
    this.help = help;
    this.buttons = {};
    for (const spec of BUTTONS) {
      if (!spec) {
        element.appendChild(Object.assign(document.createElement('span'), { className: 'sd-tool-gap' }));
      } else if (spec.id !== 'panel' || panel) {
        this.buttons[spec.id] = this.#button(spec);
      }
    }
    help.onClose = () => this.#update();
    this.listeners = {
      options: () => this.#update(),
      handles: () => this.#update(),
      skeleton: () => this.#update(),
      panel: () => this.#update(),
      stepping: () => this.#update(),
      trace: () => this.#update(),
      compare: () => this.#update(),
      load: () => this.#update(),
      dispose: () => this.dispose(),
    };
    for (const [type, listener] of Object.entries(this.listeners)) app.addEventListener(type, listener);
    this.#update();
  }

  #button({ id, label, title }) {
    const button = Object.assign(document.createElement('button'), { type: 'button', className: 'sd-tool', title });
    button.dataset.action = id;
    button.setAttribute('aria-label', title.split(':')[0]);
    const text = Object.assign(document.createElement('span'), { className: 'sd-tool-label', textContent: label });
    button.append(icon({ gizmo: 'translate', stepping: 'pause', next: 'step', half: 'rotate' }[id] ?? id), text);
    // A press on a button is not a press in the view: no focus stealing, no orbit, no double-tap zoom.
    button.addEventListener('click', () => this.#run(id));
    this.element.appendChild(button);
    return button;
  }

  #run(id) {
    const app = this.app;
    const settings = app.settings;
    const quietly = (promise) => promise?.catch?.(() => {}); // failures are shown in the page
    if (TOOL_IDS.includes(id)) app.setOptions({ tool: id });
    else if (id === 'erase') app.setOptions({ erase: !settings.erase });
    else if (id === 'fixed' || id === 'moving') app.addGroupFromSelection(id === 'moving');
    else if (id === 'gizmo') app.setOptions({ gizmoMode: settings.gizmoMode === 'translate' ? 'rotate' : 'translate' });
    else if (id === 'undo') app.undo();
    else if (id === 'redo') app.redo();
    else if (id === 'fit') app.fitView();
    else if (id === 'stepping') quietly(app.stepping.toggle());
    else if (id === 'next') quietly(app.stepping.next());
    else if (id === 'half') quietly(app.stepping.nextHalf());
    else if (id === 'help') this.help.toggle();
    else if (id === 'panel') app.setPanelOpen(!app.panelOpen);
    this.#update();
  }

  /** Pressed and enabled states from the app's state. */
  #update() {
    const app = this.app;
    const { tool, erase, gizmoMode } = app.settings;
    const b = this.buttons;
    for (const id of TOOL_IDS) pressed(b[id], tool === id);
    pressed(b.erase, erase);
    const selected = app.selection.size > 0;
    b.fixed.disabled = !selected;
    b.moving.disabled = !selected;
    const rotate = gizmoMode === 'rotate';
    b.gizmo.replaceChild(icon(rotate ? 'rotate' : 'translate'), b.gizmo.firstChild);
    b.gizmo.lastChild.textContent = rotate ? 'rotate' : 'move';
    b.undo.disabled = !app.handles.undoStack.length && !app.skeleton.canUndo;
    b.redo.disabled = !app.handles.redoStack.length && !app.skeleton.canRedo;
    const paused = app.stepping.paused;
    pressed(b.stepping, paused);
    b.stepping.lastChild.textContent = paused ? 'run' : 'pause';
    b.stepping.replaceChild(icon(paused ? 'play' : 'pause'), b.stepping.firstChild);
    b.next.hidden = !paused;
    b.half.hidden = !paused || !app.stepping.hasArap;
    b.half.lastChild.textContent = app.stepping.nextPhase;
    pressed(b.help, this.help.shown);
    if (b.panel) pressed(b.panel, app.panelOpen);
  }

  dispose() {
    for (const [type, listener] of Object.entries(this.listeners)) this.app.removeEventListener(type, listener);
    this.element.replaceChildren();
  }
}

function pressed(button, on) {
  button.setAttribute('aria-pressed', String(!!on));
  button.classList.toggle('sd-on', !!on);
}
