// <subspace-deformer>: the one-tag embed for course pages. Attributes (read when the element connects):
//   example="bar"            a built-in example (default: the first one)
//   mesh="a.obj" cage="b.obj" your own model, URLs relative to the page
//   scene="s.json"           a scene file (docs/scene-format.md); mesh/cage paths relative to it
//   compare="arap,subspace,full"  linked views (presence alone = all three; "coordinates": two cage coordinates)
//   coordinates="mvc"|"pmvc"|"harmonic"  the cage's coordinates (default mvc)
//   panel="none"|"closed"|"open"  the lil-gui panel (default: closed)
//   method="subspace"|"full"|"arap"   help="none"
// Size it with CSS (default 100% x 420px). Several per page are fine: each has its own workers.
// Scripting API: see docs/embed.md (el.ready, el.setHandles, el.drag, el.solve, el.stats, el.positions ...).
import { InputError } from '../../lib/errors.js';
import { DeformerApp } from '../deformer_app.js';

/**
 * Creates the app inside `element`.
 * @param {HTMLElement} element
 * @param {{ example?: string, mesh?: string, cage?: string, scene?: string|object, compare?: boolean|string|string[],
 *           panel?: boolean|'closed', help?: boolean, settings?: object }} [options]
 * @returns {DeformerApp} with .ready (Promise), .setHandles, .drag, .solve, .stats, .positions, .dispose ...
 */
export function mount(element, options = {}) {
  return new DeformerApp(element, options);
}

export class SubspaceDeformerElement extends HTMLElement {
  connectedCallback() {
    if (this.app) return;
    if (!this.style.display) this.style.display = 'block';
    if (!this.style.height && !this.getAttribute('style')?.includes('height')) {
      // A default size that host CSS can override.
      if (getComputedStyle(this).height === '0px' || getComputedStyle(this).height === 'auto') this.style.height = '420px';
    }
    const attr = (name) => this.getAttribute(name) ?? undefined;
    const panel = attr('panel');
    const compare = this.hasAttribute('compare') ? (attr('compare') || true) : false;
    this.app = mount(this, {
      example: attr('example'),
      mesh: attr('mesh'),
      cage: attr('cage'),
      scene: attr('scene'),
      compare,
      panel: panel === 'none' ? false : panel === 'open' ? true : 'closed',
      help: attr('help') !== 'none',
      settings: { ...(attr('method') ? { method: attr('method') } : {}), ...(attr('coordinates') ? { coordinates: attr('coordinates') } : {}) },
    });
    this.app.addEventListener('load', (e) => this.dispatchEvent(new CustomEvent('load', { detail: e.model })));
  }

  disconnectedCallback() {
    this.app?.dispose();
    this.app = null;
  }

  /** Resolves when the first model is loaded and bound (rejects if that failed; the page shows why). */
  get ready() {
    return this.app ? this.app.ready : Promise.reject(new InputError('<subspace-deformer> is not in the document'));
  }
  get stats() {
    return this.app?.stats;
  }
  statsAll() {
    return this.app.statsAll();
  }
  setHandles(groups, options) {
    return this.app.setHandles(groups, options);
  }
  setTargets(targets) {
    return this.app.setTargets(targets);
  }
  drag(index, translation, rotation) {
    return this.app.drag(index, translation, rotation);
  }
  solve() {
    return this.app.solve();
  }
  reset() {
    return this.app.reset();
  }
  resetHandles() {
    return this.app.resetHandles();
  }
  resolveFromRest() {
    return this.app.resolveFromRest();
  }
  fitView() {
    return this.app.fitView();
  }
  positions(view) {
    return this.app.positions(view);
  }
  cagePositions(view) {
    return this.app.cagePositions(view);
  }
  restPositions() {
    return this.app.restPositions();
  }
  indices() {
    return this.app.indices();
  }
  setOptions(options) {
    return this.app.setOptions(options);
  }
  setCompare(compare) {
    return this.app.setCompare(compare);
  }
  setCoordinates(coordinates, resolution) {
    return this.app.setCoordinates(coordinates, resolution);
  }
  /** The influence view (influence.js): show(column), hide(), setPicking(on). */
  get influence() {
    return this.app?.influence;
  }
  loadExample(name) {
    return this.app.loadExample(name);
  }
  loadScene(scene) {
    return this.app.loadScene(scene);
  }
  loadUrls(mesh, cage) {
    return this.app.loadUrls(mesh, cage);
  }
  loadFiles(files) {
    return this.app.loadFiles(files);
  }
  generateCage(vertices) {
    return this.app.generateCage(vertices);
  }
  exportObj(what) {
    return this.app.exportObj(what);
  }
  screenshot() {
    return this.app.screenshot();
  }
}

export function defineElement(name = 'subspace-deformer') {
  if (!customElements.get(name)) customElements.define(name, SubspaceDeformerElement);
}
