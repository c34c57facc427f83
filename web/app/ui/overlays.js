// In-page messages: an error/info banner (with optional action buttons), a quiet note about the model in the
// status bar, and a progress bar with Cancel.
export class Banner {
  /**
   * @param {HTMLElement} parent
   * @param {{ noteButton?: HTMLButtonElement }} [options] noteButton: where note() shows (in the status bar)
   */
  constructor(parent, { noteButton } = {}) {
    this.element = document.createElement('div');
    this.element.className = 'sd-banner';
    this.element.hidden = true;
    this.element.setAttribute('role', 'alert');
    parent.appendChild(this.element);
    this.noteButton = noteButton ?? null;
    if (this.noteButton) {
      this.noteButton.hidden = true;
      this.noteButton.onclick = () => this.show(this.noteButton.title, { kind: 'info' });
    }
  }

  /**
   * A quiet note about the model (what loading did to it: seams welded, holes capped): one line in the status
   * bar, never over the model, its whole `text` in the tooltip and, on a press, in the banner. '' removes it.
   * @param {string} text
   * @param {string} [summary] the line (default: text)
   */
  note(text, summary = text) {
    if (!this.noteButton) return;
    this.noteButton.hidden = !text;
    this.noteButton.title = text;
    this.noteButton.textContent = text ? `note: ${summary}` : '';
  }

  get noteText() {
    return this.noteButton?.hidden === false ? this.noteButton.title : '';
  }

  /**
   * @param {string} text
   * @param {{ kind?: 'error'|'warning'|'info', actions?: { label: string, run: (value?: number) => void,
   *           input?: { label: string, value: number, min: number, max: number, step?: number } }[] }} [options]
   *   An action with `input` gets a number field before its button; run() receives its value (clamped).
   */
  show(text, { kind = 'error', actions = [] } = {}) {
    this.element.replaceChildren();
    this.element.classList.toggle('sd-info', kind === 'info');
    this.element.classList.toggle('sd-warning', kind === 'warning');
    this.element.dataset.kind = kind;
    const message = document.createElement('div');
    message.className = 'sd-message';
    message.textContent = text;
    this.element.appendChild(message);
    for (const action of actions) {
      let field = null;
      if (action.input) {
        const { label, value, min, max, step = 1 } = action.input;
        const wrap = document.createElement('label');
        wrap.className = 'sd-banner-input';
        field = Object.assign(document.createElement('input'), { type: 'number', value: String(value), min: String(min), max: String(max), step: String(step) });
        wrap.append(document.createTextNode(`${label} `), field);
        this.element.appendChild(wrap);
      }
      const button = document.createElement('button');
      button.textContent = action.label;
      button.onclick = () => {
        let value;
        if (field) {
          const { value: fallback, min, max } = action.input;
          const n = Math.round(Number(field.value));
          value = Number.isFinite(n) ? Math.max(min, Math.min(max, n)) : fallback;
        }
        this.hide();
        action.run(value);
      };
      this.element.appendChild(button);
    }
    const close = document.createElement('button');
    close.className = 'sd-close';
    close.textContent = '\u00d7';
    close.title = 'Dismiss';
    close.onclick = () => this.hide();
    this.element.appendChild(close);
    this.element.hidden = false;
  }

  get text() {
    return this.element.hidden ? '' : this.element.querySelector('.sd-message')?.textContent ?? '';
  }

  hide() {
    this.element.hidden = true;
  }
}

export class ProgressBar {
  constructor(parent, onCancel) {
    this.element = document.createElement('div');
    this.element.className = 'sd-progress';
    this.element.hidden = true;
    this.text = document.createElement('div');
    const bar = document.createElement('div');
    bar.className = 'sd-progress-bar';
    this.fill = document.createElement('div');
    bar.appendChild(this.fill);
    const cancel = document.createElement('button');
    cancel.textContent = 'Cancel';
    cancel.onclick = () => onCancel();
    this.element.append(this.text, bar, cancel);
    parent.appendChild(this.element);
    this.timer = 0;
  }

  /** Shown only if the work lasts more than a moment, so quick loads do not flash. */
  start(label) {
    this.label = label;
    this.set(0, '');
    clearTimeout(this.timer);
    this.timer = setTimeout(() => (this.element.hidden = false), 250);
  }

  set(fraction, phase) {
    this.fill.style.width = `${Math.round(100 * Math.max(0, Math.min(1, fraction)))}%`;
    this.text.textContent = `${this.label}${phase ? ` \u2014 ${phase}` : ''} ${Math.round(100 * fraction)}%`;
  }

  done() {
    clearTimeout(this.timer);
    this.element.hidden = true;
  }
}
