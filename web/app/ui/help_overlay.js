// The help: what every touch, click and key does, as a card over the views that the tool strip's help button
// opens (the one-line key help under a wide view does not fit small screens or touch). A touch screen gets the
// touch section first.
const TOUCH = [
  ['one finger', 'what the tool strip\'s tool says: orbit, pick (tap a vertex), brush or lasso'],
  ['two fingers', 'pinch to zoom, move to pan (in every tool; a second finger cancels a brush or lasso stroke)'],
  ['press and hold, then drag', 'brush (pick tool)'],
  ['erase', 'pick, brush and lasso remove from the selection'],
  ['bone', 'tap inside a limb: a joint midway through it; tap on: bones; tap a joint to continue from it, a bone to select it'],
  ['fixed / moving', 'the selection becomes a fixed group, or a moving group with a gizmo'],
  ['the gizmo', 'drag an arrow, a plane square or its centre; move / rotate switches its mode'],
  ['pause, step', 'the solver waits; each step is one iteration, its line search and energies shown in the view'],
  ['influence', 'panel Influence, "click a cage vertex": a tap near one colours the mesh by its weight (negative: blue)'],
];
const MOUSE = [
  ['drag / right drag / wheel', 'orbit / pan / zoom'],
  ['click', 'pick a vertex (click again to deselect)'],
  ['Shift-drag / Alt-drag', 'brush / lasso; add Ctrl to remove'],
  ['F / M', 'fixed / moving group of the selection'],
  ['Del / Esc', 'remove the active group / clear the selection'],
  ['T / R', 'gizmo: translate / rotate'],
  ['Ctrl+Z / Ctrl+Shift+Z', 'undo / redo handle edits'],
  ['V, C, P', 'fit view, cage on/off, paint volume parts'],
  ['S / N', 'pause the solver / one iteration'],
  ['B, then click the mesh', 'bone tool: joints inside, bones between them (Del deletes the selected, Esc: new chain)'],
  ['I, then click a cage vertex', 'colour the mesh by that vertex\'s weight (negative: blue)'],
];

export class HelpOverlay {
  /** @param {HTMLElement} parent the app's root */
  constructor(parent) {
    this.element = Object.assign(document.createElement('div'), { className: 'sd-help-card', hidden: true });
    this.element.setAttribute('role', 'dialog');
    this.element.setAttribute('aria-label', 'Help');
    const close = Object.assign(document.createElement('button'), { type: 'button', className: 'sd-close', textContent: '\u00d7', title: 'Close' });
    close.onclick = () => this.hide();
    const touchFirst = globalThis.matchMedia?.('(pointer: coarse)').matches ?? false;
    const sections = [['Touch and pen', TOUCH], ['Mouse and keys', MOUSE]];
    if (!touchFirst) sections.reverse();
    this.element.append(close, ...sections.map(([title, rows]) => section(title, rows)));
    // Modal: a backdrop over the views takes presses while the card is up (a drag must not go on underneath); a
    // press on it closes the card, as Escape does.
    this.backdrop = Object.assign(document.createElement('div'), { className: 'sd-help-backdrop', hidden: true });
    this.backdrop.addEventListener('pointerdown', (event) => {
      event.stopPropagation();
      event.preventDefault();
      this.hide();
    });
    parent.append(this.backdrop, this.element);
    // Keys belong to the card while it is up (no shortcut acts underneath); Escape closes it.
    globalThis.addEventListener('keydown', (event) => {
      if (!this.shown) return;
      event.stopPropagation();
      if (event.key === 'Escape') this.hide();
    }, { capture: true });
    this.onClose = () => {};
  }

  get shown() {
    return !this.element.hidden;
  }

  toggle() {
    if (this.shown) this.hide();
    else this.element.hidden = this.backdrop.hidden = false;
  }

  hide() {
    this.element.hidden = this.backdrop.hidden = true;
    this.onClose();
  }
}

function section(title, rows) {
  const wrap = document.createElement('section');
  wrap.appendChild(Object.assign(document.createElement('h3'), { textContent: title }));
  const list = document.createElement('dl');
  for (const [what, does] of rows) {
    list.append(Object.assign(document.createElement('dt'), { textContent: what }), Object.assign(document.createElement('dd'), { textContent: does }));
  }
  wrap.appendChild(list);
  return wrap;
}
