// The views on screen: one SolverView, or one per method in compare mode (or per cage coordinates: a view's
// key, methods.js), side by side with linked cameras. Switching keeps the views whose key stays (their workers
// keep their bound model); new views start unbound and the caller binds the model in them. Framing (framing.js): every view gets the camera the
// narrowest one needs; while the camera stays where a fit put it, a resize frames the same box again.
import { Vector3 } from 'three';
import { isSpectral } from '../../lib/subspace.js';
import { boxOf } from './viewport.js';
import { DEFAULT_DIRECTION, framingBox } from './framing.js';

/** The bounding box of a model's mesh and cage. */
function modelBox(model) {
  return boxOf(model.mesh.positions).union(boxOf(model.cage.positions));
}

export class SolverViews {
  /**
   * @param {HTMLElement} element the views' container
   * @param {{ before: Element|null, create: (key: string) => import('./solver_view.js').SolverView }} options
   *   before: the views go before this child (the key help; null: last); create: makes a wired view for a key
   */
  constructor(element, { before, create }) {
    this.element = element;
    this.before = before;
    this.create = create;
    /** @type {import('./solver_view.js').SolverView[]} */
    this.list = [];
    this.linking = false;
    /** The last fit ({ box, direction }) and whether the camera is still where it put it. */
    this.framed = null;
    this.autoFramed = false;
    this.refitQueued = false;
    this.gizmoUnframed = false;
  }

  get first() {
    return this.list[0];
  }

  get compare() {
    return this.list.length > 1;
  }

  /**
   * Shows one view per key (a method, or 'subspace:<coordinates>'), in order. Leaving compare mode onto a method
   * that had no view keeps a bound view of the app's coordinates and switches its method instead of binding the
   * model again.
   * @param {string[]} keys
   * @param {{ labels?: boolean }} [options] labels: name the method even on a single view
   * @returns {import('./solver_view.js').SolverView[]} views whose method changed (their settings need applying)
   */
  setMethods(keys, { labels = false } = {}) {
    const old = this.list;
    const views = keys.map((key) => {
      const i = old.findIndex((v) => v.key === key);
      return i >= 0 ? old.splice(i, 1)[0] : this.#create(key);
    });
    const switched = [];
    const reusable = old.findIndex((v) => v.coordinates === null);
    if (views.length === 1 && !views[0].coordinates && reusable >= 0 && !views[0].session.model) {
      views[0].dispose();
      const keep = old.splice(reusable, 1)[0];
      keep.setMethod(keys[0]);
      views[0] = keep;
      switched.push(keep);
    }
    for (const v of old) v.dispose();
    this.list = views;
    for (const v of views) {
      this.element.insertBefore(v.element, this.before);
      v.showLabel(views.length > 1 || labels);
      v.session.shareCores(views.length > 1);
    }
    return switched;
  }

  #create(key) {
    const view = this.create(key);
    if (this.first) view.copyCamera(this.first);
    view.viewport.addEventListener('resize', () => this.#refitSoon());
    view.viewport.addEventListener('userCamera', () => (this.autoFramed = false));
    return view;
  }

  /**
   * Shows a newly bound model at rest in `views` (default: all; every view is framed again when all are).
   * @param {{ cageShown?: boolean }} [options] frame the cage too (when not much larger than the model)
   * @returns {number} the diagonal of the model and cage's bounding box
   */
  showModel(model, views = this.list, { cageShown = true } = {}) {
    for (const view of views) view.showModel(model);
    const cages = isSpectral(model) ? [] : [model.cage.positions]; // the spectral basis draws no cage
    // An example may say where its front is (Spot faces -z); a mesh file has no such notion: the default.
    const direction = model.defaultView ? new Vector3(...model.defaultView.direction).normalize() : DEFAULT_DIRECTION;
    if (views === this.list) this.frameAll(framingBox({ meshes: [model.mesh.positions], cages, cageShown }), direction);
    // The model's handle groups come next, in the same task (showHandleChange): frame their gizmo too.
    this.gizmoUnframed = views === this.list;
    queueMicrotask(() => (this.gizmoUnframed = false));
    return modelBox(model).getSize(new Vector3()).length();
  }

  /**
   * Frames what the views show now: every view's mesh, the handles' targets (where the gizmo is) and the
   * cages (framing.js says when), looking along the first view's current direction.
   * @param {{ targets?: ArrayLike<number>, cageShown?: boolean, direction?: Vector3|number[] }} [options]
   */
  fitView({ targets = null, cageShown = true, direction = this.first?.viewport.viewDirection() } = {}) {
    const shown = this.list.filter((v) => v.positions);
    if (!shown.length) return;
    if (Array.isArray(direction)) direction = new Vector3(...direction).normalize();
    const cages = shown.filter((v) => v.viewport.cageView.shown).map((v) => v.cagePositions); // drawn cages only
    const box = framingBox({ meshes: shown.map((v) => v.positions), targets, cages, cageShown });
    this.frameAll(box, direction);
  }

  /** Frames `box` in every view with one camera: the distance the narrowest view needs. */
  frameAll(box, direction = DEFAULT_DIRECTION) {
    if (box.isEmpty() || !this.list.length) return;
    // The gizmo too, with its handles' reach in each view's aspect (a phone's tall view: they would run off it).
    const frames = this.list.map((view) => view.viewport.frameFor(box, direction, (aspect) => view.gizmo.fit(aspect)));
    const widest = frames.reduce((a, b) => (b.distance > a.distance ? b : a));
    this.linking = true; // every view gets the same placement: no camera copying meanwhile
    for (const view of this.list) view.viewport.placeCamera(widest, direction);
    this.linking = false;
    this.framed = { box, direction: direction.clone() };
    this.autoFramed = true;
  }

  /** A view changed size: frame the same box again (next frame, once for all views) unless the user moved the camera. */
  #refitSoon() {
    if (!this.autoFramed || !this.framed || this.refitQueued) return;
    this.refitQueued = true;
    requestAnimationFrame(() => {
      this.refitQueued = false;
      if (this.autoFramed && this.framed) this.frameAll(this.framed.box, this.framed.direction);
    });
  }

  /** A drag of the handles ended (a pointer release): every view settles at once. */
  released() {
    for (const view of this.list) view.session.released();
  }

  /**
   * Shows a handle edit (HandleEditor's 'change': what = 'handles', 'targets', 'active' or 'selection') in every
   * view, and sends new groups or targets to every session.
   */
  showHandleChange(what, handles, selection) {
    for (const view of this.list) {
      if (what === 'handles') view.session.setHandles(handles.vertexGroups(), handles.targets(), handles.lines());
      if (what === 'targets') {
        view.session.setTargets(handles.targets(), handles.lines());
        view.showTargets(handles);
      } else {
        view.showHandles(handles, selection);
      }
    }
    if (this.gizmoUnframed && what === 'handles' && this.first?.gizmo.helper.visible) {
      this.gizmoUnframed = false;
      if (this.autoFramed && this.framed) this.frameAll(this.framed.box, this.framed.direction);
    }
  }

  /** One animation frame: each session sends what changed, each view redraws if needed. Returns redraws per view. */
  frame(now) {
    let rendered = 0;
    for (const view of this.list) {
      view.session.pump();
      if (view.viewport.renderIfNeeded(now)) rendered++;
    }
    return rendered / Math.max(1, this.list.length);
  }

  /**
   * Redraws every view's stats line and plot (where they changed).
   * @param {string} status what to show without a model (loading, or why none is loaded)
   */
  drawStats(model, rates, status) {
    for (const view of this.list) view.drawStats(view.stats(model, rates), model ? true : status);
  }

  /** Gives every other view the camera of `source` (called when the user moves one). */
  linkCameras(source) {
    if (this.linking) return;
    this.linking = true;
    for (const view of this.list) if (view !== source) view.copyCamera(source);
    this.linking = false;
  }

  dispose() {
    for (const view of this.list) view.dispose();
    this.list = [];
  }
}
