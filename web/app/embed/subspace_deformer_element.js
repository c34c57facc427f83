// <subspace-deformer>: the one-tag embed for course pages. Attributes (read once, when the element connects; a
// change afterwards does nothing but warn once in the console, naming the API calls that do it):
//   example="bar"            a built-in example (default: the first one)
//   mesh="a.obj" cage="b.obj" your own model, URLs relative to the page
//   scene="s.json"           a scene file (docs/scene-format.md); mesh/cage paths relative to it
//   compare="arap,subspace,full"  linked views (presence alone = all three; "coordinates": two cage coordinates)
//   coordinates="mvc"|"pmvc"|"harmonic"  the cage's coordinates (default mvc)
//   panel="none"|"closed"|"open"  the lil-gui panel (default: closed)
//   help="none"              no key help line      tools="none"   no tool strip
//   paused                   start with the solver paused: step through it one iteration at a time
//   lesson="arap-vs-subspace" a built-in lesson: its model, handles, views and caption (docs/app.md, lessons)
//   no-cage="ask"|"generate"|"spectral"  a mesh without a cage: the banner offers both (default), or it gets
//                            a generated cage, or deforms in its spectral basis; event 'nocage' { choice, model }
//   method="subspace"|"full"|"arap", and any other setting by name (jacobian="exact", wireframe, ...)
// All are read and checked by the same tables as mount()'s options and the app's URL parameters
// (page_options.js): a bad value is named in the banner and its default used.
// Size it with CSS (default 100% x 420px). Several per page are fine: each has its own workers.
// Scripting API: see docs/embed.md (el.ready, el.setHandles, el.drag, el.solve, el.stats, el.positions ...).
import { InputError } from '../../lib/errors.js';
import { DeformerApp } from '../deformer_app.js';
import { PAGE_TEXT_NAMES, kebabName, pageOptionsFromText } from '../page_options.js';

/**
 * Creates the app inside `element`.
 * @param {HTMLElement} element
 * @param {{ example?: string, mesh?: string, cage?: string, scene?: string|object, compare?: boolean|string|string[],
 *           panel?: boolean|'closed', help?: boolean, noCage?: 'ask'|'generate'|'spectral', settings?: object }} [options]
 * @returns {DeformerApp} with .ready (Promise), .setHandles, .drag, .solve, .stats, .positions, .dispose ...
 */
export function mount(element, options = {}) {
  return new DeformerApp(element, options);
}

// Outside a browser (a server rendering the page imports it too) there is no HTMLElement: the class is then a
// plain one and defineElement() does nothing, so the import does not throw.
const ElementBase = /** @type {typeof HTMLElement} */ (globalThis.HTMLElement ?? class {});

export class SubspaceDeformerElement extends ElementBase {
  /** The running app: null before the element connects and after it has left the document (index.d.ts). */
  app = null;

  /** Every attribute the element reads (HTML lowercases names: maxIterations is maxiterations), to warn of changes. */
  static get observedAttributes() {
    return [...new Set(PAGE_TEXT_NAMES.flatMap((name) => [name.toLowerCase(), kebabName(name)]))];
  }

  #warned = false;

  /**
   * An attribute changed while the app runs: it was read when the element connected, and applying each one would
   * mean reloading or rebinding (a model, a lesson, views) behind the page's back. The console says so, once.
   */
  attributeChangedCallback(name, before, after) {
    if (!this.app || before === after || this.#warned) return;
    this.#warned = true;
    console.warn(`<subspace-deformer>: attribute "${name}" changed after the element started; attributes are read once, when ` +
      'it connects. Use its API instead: setOptions({ ... }) for method and any setting, loadExample(), loadUrls(), loadScene(), ' +
      'loadLesson(), setCompare(), setCoordinates(), stepping.setPaused() (docs/embed.md).');
  }

  connectedCallback() {
    if (this.app) return; // moved within the document: the same app goes on (disconnectedCallback)
    if (!this.style.display) this.style.display = 'block';
    if (!this.style.height && !this.getAttribute('style')?.includes('height')) {
      // A default size that host CSS can override.
      if (getComputedStyle(this).height === '0px' || getComputedStyle(this).height === 'auto') this.style.height = '420px';
    }
    const options = pageOptionsFromText((name) => this.getAttribute(name) ?? this.getAttribute(kebabName(name)));
    this.app = mount(this, { panel: 'closed', ...options });
    this.app.addEventListener('load', (e) => this.dispatchEvent(new CustomEvent('load', { detail: e.model })));
    this.app.addEventListener('nocage', (e) => this.dispatchEvent(new CustomEvent('nocage', { detail: { choice: e.choice, model: e.model } })));
  }

  /**
   * Removed: the app is disposed (its workers stop, a pending solve() or drag() rejects as cancelled). Moved
   * elsewhere in the document (wrap.append(el): a disconnect, then a connect in the same task) it must not be: the
   * pose, handles, skeleton and parts would be lost to a fresh app read from the attributes. So the disposal waits
   * for the microtasks after the current script, and a reconnect before then keeps the app.
   */
  disconnectedCallback() {
    queueMicrotask(() => {
      if (this.isConnected) return;
      this.app?.dispose();
      this.app = null;
    });
  }

  /**
   * Resolves when the first model is loaded and bound (rejects if that failed; the page shows why). A mesh without
   * a cage waits for the banner's choice (or no-cage's): it resolves once the mesh is bound that way.
   */
  get ready() {
    return this.app ? this.app.ready : Promise.reject(new InputError('<subspace-deformer> is not in the document'));
  }
  get stats() {
    return this.app?.stats;
  }

  /** The app, or an InputError when the element is not in the document (no app runs then). */
  #live() {
    if (!this.app) throw new InputError('<subspace-deformer> is not in the document (it starts when it connects)');
    return this.app;
  }
  statsAll() {
    return this.#live().statsAll();
  }
  /** Loads a built-in lesson (docs/app.md, lessons). */
  loadLesson(id) {
    return this.#live().loadLesson(id);
  }
  get lesson() {
    return this.app?.lesson ?? null;
  }
  /** Step-through: paused, setPaused(on), toggle(), next(), nextHalf() (docs/embed.md). */
  get stepping() {
    return this.app?.stepping;
  }
  setHandles(groups, options) {
    return this.#live().setHandles(groups, options);
  }
  setTargets(targets) {
    return this.#live().setTargets(targets);
  }
  drag(index, translation, rotation) {
    return this.#live().drag(index, translation, rotation);
  }
  solve() {
    return this.#live().solve();
  }
  reset() {
    return this.#live().reset();
  }
  resetHandles() {
    return this.#live().resetHandles();
  }
  resolveFromRest() {
    return this.#live().resolveFromRest();
  }
  fitView() {
    return this.#live().fitView();
  }
  positions(view) {
    return this.#live().positions(view);
  }
  cagePositions(view) {
    return this.#live().cagePositions(view);
  }
  restPositions() {
    return this.#live().restPositions();
  }
  indices() {
    return this.#live().indices();
  }
  setOptions(options) {
    return this.#live().setOptions(options);
  }
  setCompare(compare) {
    return this.#live().setCompare(compare);
  }
  setCoordinates(coordinates, resolution) {
    return this.#live().setCoordinates(coordinates, resolution);
  }
  /** The influence view (influence.js): show(column), hide(), setPicking(on). */
  get influence() {
    return this.app?.influence;
  }
  loadExample(name) {
    return this.#live().loadExample(name);
  }
  loadScene(scene) {
    return this.#live().loadScene(scene);
  }
  loadUrls(mesh, cage) {
    return this.#live().loadUrls(mesh, cage);
  }
  loadFiles(files) {
    return this.#live().loadFiles(files);
  }
  generateCage(vertices) {
    return this.#live().generateCage(vertices);
  }
  exportGlb() {
    return this.#live().exportGlb();
  }
  exportObj(what) {
    return this.#live().exportObj(what);
  }
  screenshot() {
    return this.#live().screenshot();
  }
}

export function defineElement(name = 'subspace-deformer') {
  if (globalThis.customElements && !customElements.get(name)) customElements.define(name, SubspaceDeformerElement);
}
