// The tool strip: every action of the keys and modifiers as a button sized for a finger, so that a phone or a
// tablet needs no keyboard (docs/app.md, "Touch and pen"). What a one-finger press in a view does (orbit, pick,
// brush, lasso, bone, erase: settings.tool and settings.erase); making a fixed or moving group of the selection;
// the gizmo's mode; undo and redo; fit view; stepping the solver; the help; the control panel.
// It never holds the app: it shows the app's state (app_state.js: settings, handles, stepping, panelOpen), follows
// its one change event, and sends intents (app_intents.js); the app calls only dispose().
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
   * @param {HTMLElement} element the strip's container (AppLayout.tools)
   * @param {{ state: import('../app_state.js').AppState, intents: ReturnType<typeof import('../app_intents.js').appIntents>,
   *           help: import('./help_overlay.js').HelpOverlay, panel: boolean }} options state: what the buttons show;
   *   intents: what they do; help: the overlay the help button shows; panel: whether the app has a control panel
   *   (else no panel button)
   */
  constructor(element, { state, intents, help, panel }) {
    this.state = state;
    this.intents = intents;
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
    this.unsubscribe = state.subscribe(() => this.#update());
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
    const intents = this.intents;
    const { settings, panelOpen } = this.state.current;
    if (TOOL_IDS.includes(id)) intents.setOptions({ tool: id });
    else if (id === 'erase') intents.setOptions({ erase: !settings.erase });
    else if (id === 'fixed' || id === 'moving') intents.addGroupFromSelection(id === 'moving');
    else if (id === 'gizmo') intents.setOptions({ gizmoMode: settings.gizmoMode === 'translate' ? 'rotate' : 'translate' });
    else if (id === 'undo') intents.undo();
    else if (id === 'redo') intents.redo();
    else if (id === 'fit') intents.fitView();
    else if (id === 'stepping') intents.toggleStepping();
    else if (id === 'next') intents.nextStep();
    else if (id === 'half') intents.nextHalfStep();
    else if (id === 'help') this.help.toggle();
    else if (id === 'panel') intents.setPanelOpen(!panelOpen);
    this.#update();
  }

  /** Pressed and enabled states from the app's state. */
  #update() {
    const { settings: { tool, erase, gizmoMode }, handles, stepping, panelOpen } = this.state.current;
    const b = this.buttons;
    for (const id of TOOL_IDS) pressed(b[id], tool === id);
    pressed(b.erase, erase);
    b.fixed.disabled = handles.selected === 0;
    b.moving.disabled = handles.selected === 0;
    const rotate = gizmoMode === 'rotate';
    b.gizmo.replaceChild(icon(rotate ? 'rotate' : 'translate'), b.gizmo.firstChild);
    b.gizmo.lastChild.textContent = rotate ? 'rotate' : 'move';
    b.undo.disabled = !handles.canUndo;
    b.redo.disabled = !handles.canRedo;
    const paused = stepping.paused;
    pressed(b.stepping, paused);
    b.stepping.lastChild.textContent = paused ? 'run' : 'pause';
    b.stepping.replaceChild(icon(paused ? 'play' : 'pause'), b.stepping.firstChild);
    b.next.hidden = !paused;
    b.half.hidden = !paused || !stepping.hasArap;
    b.half.lastChild.textContent = stepping.nextPhase;
    pressed(b.help, this.help.shown);
    if (b.panel) pressed(b.panel, panelOpen);
  }

  dispose() {
    this.unsubscribe();
    this.element.replaceChildren();
  }
}

function pressed(button, on) {
  button.setAttribute('aria-pressed', String(!!on));
  button.classList.toggle('sd-on', !!on);
}
