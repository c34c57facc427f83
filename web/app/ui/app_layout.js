// The app's DOM: a focusable root (in the host page's element) holding the views' row with the key help, a
// status bar under it (the model's name and size on the left, frames per second on the right: never over a
// view's stats or plot), the banner and the progress bar. The views, the panel and the file input add their
// own elements to it.
import { Banner, ProgressBar } from './overlays.js';
import { injectStyles } from './styles.js';

const KEY_HELP = 'click: pick vertex \u00b7 shift-drag: brush \u00b7 alt-drag: lasso \u00b7 +ctrl: remove\n' +
  'F: add fixed group \u00b7 M: add moving group \u00b7 Del: remove group \u00b7 P: paint volume parts \u00b7 I: cage vertex influence \u00b7 drag the gizmo to deform';

export class AppLayout {
  /**
   * @param {HTMLElement} container
   * @param {{ help?: boolean, onCancel: () => void }} options help: show the key help; onCancel: the progress bar's Cancel
   */
  constructor(container, { help = true, onCancel }) {
    injectStyles(container.ownerDocument);
    this.root = Object.assign(document.createElement('div'), { className: 'sd-app', tabIndex: 0 });
    container.appendChild(this.root);
    this.views = Object.assign(document.createElement('div'), { className: 'sd-views' });
    this.root.appendChild(this.views);
    this.status = Object.assign(document.createElement('div'), { className: 'sd-status' });
    this.modelInfo = Object.assign(document.createElement('span'), { className: 'sd-model' });
    this.fps = Object.assign(document.createElement('span'), { className: 'sd-fps' });
    this.status.append(this.modelInfo, this.fps);
    this.root.appendChild(this.status);
    this.banner = new Banner(this.root);
    this.progress = new ProgressBar(this.root, onCancel);
    this.help = null;
    if (help) {
      this.help = Object.assign(document.createElement('div'), { className: 'sd-help', textContent: KEY_HELP });
      this.help.style.whiteSpace = 'pre';
      this.views.appendChild(this.help);
    }
  }

  /** The status bar's two texts (set only when they change: no layout work while idle). */
  showStatus(model, fps) {
    if (this.modelInfo.textContent !== model) this.modelInfo.textContent = model;
    if (this.fps.textContent !== fps) this.fps.textContent = fps;
  }

  /** The key help needs room: a single view, wide enough not to cover the stats. */
  placeHelp(viewCount) {
    if (this.help) this.help.hidden = viewCount > 1 || this.views.clientWidth < 820;
  }

  dispose() {
    this.root.remove();
  }
}
