// The influence view's legend in one viewport: what is shown (which cage vertex or spectral column, with which
// coordinates), the colour scale with its numbers, how many vertices got a negative weight, and, where volume parts
// are painted, that their colours are under the influence's (painting goes on unseen until it is hidden).
import { LEGEND_GRADIENTS, legendNumber } from './influence_colors.js';

export class InfluenceLegend {
  /** @param {HTMLElement} parent the viewport's element */
  constructor(parent) {
    this.element = Object.assign(document.createElement('div'), { className: 'sd-influence' });
    this.element.hidden = true;
    parent.appendChild(this.element);
  }

  /**
   * @param {{ title: string, scale: { min: number, max: number }, range: { min: number, max: number },
   *           negative: number, vertices: number }|null} legend null hides it. range: this view's own weights.
   * @param {{ partsHidden?: boolean }} [options] partsHidden: painted volume parts are hidden under the influence's colours
   */
  show(legend, { partsHidden = false } = {}) {
    this.element.hidden = !legend;
    if (!legend) return;
    const { title, scale, range, negative, vertices } = legend;
    const bar = document.createElement('div');
    bar.className = 'sd-influence-bar';
    if (scale.min < 0) bar.append(Object.assign(document.createElement('span'), { className: 'sd-influence-negative' }));
    bar.append(Object.assign(document.createElement('span'), { className: 'sd-influence-positive' }));
    for (const part of bar.children) part.style.background = LEGEND_GRADIENTS[part.className.endsWith('negative') ? 'negative' : 'positive'];
    // The numbers under the bar's two parts: the most negative weight under the blue part's left end, 0 and the
    // largest weight at the ends of the other.
    const ticks = document.createElement('div');
    ticks.className = 'sd-influence-ticks';
    const part = (className, numbers) => {
      const span = Object.assign(document.createElement('span'), { className });
      for (const x of numbers) span.append(Object.assign(document.createElement('span'), { textContent: legendNumber(x) }));
      return span;
    };
    if (scale.min < 0) ticks.append(part('sd-influence-negative', [scale.min]));
    ticks.append(part('sd-influence-positive', [0, scale.max]));
    const share = vertices ? (100 * negative) / vertices : 0;
    const note = negative
      ? `${negative.toLocaleString('en-US')} vertices (${share.toFixed(1)}%) negative, down to ${legendNumber(range.min)}`
      : `no negative weight (smallest ${legendNumber(range.min)})`;
    this.element.replaceChildren(
      Object.assign(document.createElement('div'), { className: 'sd-influence-title', textContent: title }),
      bar, ticks,
      Object.assign(document.createElement('div'), { className: `sd-influence-note${negative ? ' sd-negative' : ''}`, textContent: note }),
    );
    if (partsHidden) {
      const hidden = 'the painted volume parts are hidden under these colours: "hide influence" (panel Influence) shows them';
      this.element.append(Object.assign(document.createElement('div'), { className: 'sd-influence-note sd-parts-hidden', textContent: hidden }));
    }
  }

  dispose() {
    this.element.remove();
  }
}
