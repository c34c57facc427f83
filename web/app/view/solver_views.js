// The views on screen: one SolverView, or one per method in compare mode, side by side with linked cameras.
// Switching keeps the views whose method stays (their workers keep their bound model); new views start
// unbound and the caller binds the model in them.
import { Vector3 } from 'three';
import { boxOf } from './viewport.js';

/** The bounding box of a model's mesh and cage. */
function modelBox(model) {
  return boxOf(model.mesh.positions).union(boxOf(model.cage.positions));
}

export class SolverViews {
  /**
   * @param {HTMLElement} element the views' container
   * @param {{ before: Element, create: (method: string) => import('./solver_view.js').SolverView }} options
   *   before: the views go before this child (the fps line); create: makes a wired view for a method
   */
  constructor(element, { before, create }) {
    this.element = element;
    this.before = before;
    this.create = create;
    /** @type {import('./solver_view.js').SolverView[]} */
    this.list = [];
    this.linking = false;
  }

  get first() {
    return this.list[0];
  }

  get compare() {
    return this.list.length > 1;
  }

  /**
   * Shows one view per method, in order. Leaving compare mode onto a method that had no view keeps a bound
   * view and switches its method instead of binding the model again.
   * @param {string[]} methods
   * @param {{ labels?: boolean }} [options] labels: name the method even on a single view
   * @returns {import('./solver_view.js').SolverView[]} views whose method changed (their settings need applying)
   */
  setMethods(methods, { labels = false } = {}) {
    const old = this.list;
    const views = methods.map((method) => {
      const i = old.findIndex((v) => v.method === method);
      return i >= 0 ? old.splice(i, 1)[0] : this.#create(method);
    });
    const switched = [];
    if (views.length === 1 && old.length && !views[0].session.model) {
      views[0].dispose();
      const keep = old.shift();
      keep.setMethod(methods[0]);
      views[0] = keep;
      switched.push(keep);
    }
    for (const v of old) v.dispose();
    this.list = views;
    for (const v of views) {
      this.element.insertBefore(v.element, this.before);
      v.showLabel(views.length > 1 || labels);
    }
    return switched;
  }

  #create(method) {
    const view = this.create(method);
    if (this.first) view.copyCamera(this.first);
    return view;
  }

  /**
   * Shows a newly bound model at rest in `views` (default: all), framed with its cage.
   * @returns {number} the diagonal of the model and cage's bounding box
   */
  showModel(model, views = this.list) {
    const box = modelBox(model);
    for (const view of views) view.showModel(model, box);
    return box.getSize(new Vector3()).length();
  }

  /**
   * Shows a handle edit (HandleEditor's 'change': what = 'handles', 'targets', 'active' or 'selection') in every
   * view, and sends new groups or targets to every session.
   */
  showHandleChange(what, handles, selection) {
    for (const view of this.list) {
      if (what === 'handles') view.session.setHandles(handles.vertexGroups(), handles.targets());
      if (what === 'targets') {
        view.session.setTargets(handles.targets());
        view.showTargets(handles);
      } else {
        view.showHandles(handles, selection);
      }
    }
  }

  /** Frames the model in every view (e.g. after the views' sizes changed), then links the cameras to the first. */
  fit(model) {
    const box = modelBox(model);
    for (const view of this.list) view.viewport.fit(box);
    if (this.first) this.linkCameras(this.first);
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

  /** Redraws every view's stats line and plot (where they changed). */
  drawStats(model, rates) {
    for (const view of this.list) view.drawStats(view.stats(model, rates), !!model);
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
