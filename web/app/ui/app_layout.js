// The app's DOM: a focusable root (in the host page's element) holding a row of the tool strip and the views
// (with the one-line key help), the current lesson's bar and a status bar under it (the model's name and size on the left, the
// banner's quiet note about the model, a note when the
// solver runs single-threaded, frames per second on the right: never over a view's stats or plot), the
// banner, the progress bar and the help card. The views, the panel and the file input add their own elements.
//
// The layout follows the app's own width (an embed may be narrow on a wide page): below NARROW_PX ('sd-narrow',
// phones) the panel opens as a bottom sheet of half the height and the views move up above it; wider, the open
// panel sits beside the views. Below WIDE_PX the panel starts closed, so the view gets the screen. Below SHORT_PX
// high ('sd-short', phones in landscape) a touch screen's tool strip is one column of the phones' icons.
import { Banner, ProgressBar } from './overlays.js';
import { HelpOverlay } from './help_overlay.js';
import { injectStyles } from './styles.js';

const KEY_HELP = 'click: pick vertex \u00b7 shift-drag: brush \u00b7 alt-drag: lasso \u00b7 +ctrl: remove \u00b7 B: bone tool\n' +
  'F: add fixed group \u00b7 M: add moving group \u00b7 Del: remove group \u00b7 P: paint volume parts \u00b7 I: cage vertex influence \u00b7 drag the gizmo to deform';
export const NARROW_PX = 600;
// Below this height (a phone in landscape: 390 px and less) a touch screen's tool strip is one column of icons.
export const SHORT_PX = 500;
export const WIDE_PX = 900;
const HELP_GAP_PX = 16; // the key help's right margin and a gap to the plot

export class AppLayout {
  /**
   * @param {HTMLElement} container
   * @param {{ help?: boolean, tools?: boolean, onCancel: () => void }} options help: show the key help line;
   *   tools: room for the tool strip; onCancel: the progress bar's Cancel
   */
  constructor(container, { help = true, tools = true, onCancel }) {
    injectStyles(container.ownerDocument);
    this.root = Object.assign(document.createElement('div'), { className: 'sd-app', tabIndex: 0 });
    container.appendChild(this.root);
    const main = Object.assign(document.createElement('div'), { className: 'sd-main' });
    this.tools = null;
    if (tools) {
      this.tools = Object.assign(document.createElement('div'), { className: 'sd-tools' });
      this.tools.setAttribute('role', 'toolbar');
      main.appendChild(this.tools);
      this.root.classList.add('sd-has-tools');
    }
    this.views = Object.assign(document.createElement('div'), { className: 'sd-views' });
    main.appendChild(this.views);
    this.root.appendChild(main);
    this.lessonBar = Object.assign(document.createElement('div'), { className: 'sd-lesson' });
    this.root.appendChild(this.lessonBar);
    this.status = Object.assign(document.createElement('div'), { className: 'sd-status' });
    this.modelInfo = Object.assign(document.createElement('span'), { className: 'sd-model' });
    const modelNote = Object.assign(document.createElement('button'), { className: 'sd-model-note', type: 'button' });
    this.buildNote = Object.assign(document.createElement('span'), { className: 'sd-build-note' });
    this.fps = Object.assign(document.createElement('span'), { className: 'sd-fps' });
    this.status.append(this.modelInfo, modelNote, this.buildNote, this.fps);
    this.root.appendChild(this.status);
    this.banner = new Banner(this.root, { noteButton: modelNote });
    this.progress = new ProgressBar(this.root, onCancel);
    this.helpCard = new HelpOverlay(this.root);
    this.help = null;
    if (help) {
      this.help = Object.assign(document.createElement('div'), { className: 'sd-help', textContent: KEY_HELP });
      this.help.style.whiteSpace = 'pre';
      this.views.appendChild(this.help);
    }
    this.resizeObserver = new ResizeObserver(() => this.#classify());
    this.resizeObserver.observe(this.root);
    this.#classify();
  }

  /** Narrower than WIDE_PX: the panel starts closed and opens over the views. */
  get compact() {
    return this.root.clientWidth < WIDE_PX;
  }

  #classify() {
    const width = this.root.clientWidth;
    this.root.classList.toggle('sd-narrow', width < NARROW_PX);
    this.root.classList.toggle('sd-short', this.root.clientHeight < SHORT_PX);
    this.root.style.setProperty('--sd-sheet', `${Math.round(0.5 * this.root.clientHeight)}px`);
  }

  /** The status bar's texts (set only when they change: no layout work while idle). */
  showStatus(model, fps, note = { text: '', title: '' }) {
    if (this.modelInfo.textContent !== model) this.modelInfo.textContent = model;
    if (this.fps.textContent !== fps) this.fps.textContent = fps;
    if (this.buildNote.textContent !== note.text) {
      this.buildNote.textContent = note.text;
      this.buildNote.title = note.title;
    }
  }

  /**
   * The key help needs room: a single view, wide enough not to cover the stats, and room beside the convergence
   * plot (bottom left): its two lines are wider than the view left of the plot at 1280x800 with the panel open.
   */
  placeHelp(viewCount) {
    if (!this.help) return;
    this.helpWidth ||= this.help.offsetWidth; // measured once shown (0 while hidden: shown for one tick to measure it)
    const plot = this.views.querySelector('.sd-plot');
    const plotRight = plot?.offsetWidth ? plot.getBoundingClientRect().right - this.views.getBoundingClientRect().left : 0;
    const room = this.views.clientWidth - plotRight - HELP_GAP_PX;
    this.help.hidden = viewCount > 1 || this.views.clientWidth < 820 || room < this.helpWidth;
  }

  dispose() {
    this.resizeObserver.disconnect();
    this.root.remove();
  }
}
