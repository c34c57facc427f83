// How a new view joins the app's shared parts (compare mode makes one per method): the settings of its method
// and display, the shared handle groups, where its picks and strokes go (the handle selection, or the volume
// parts' paint while painting), putting a stroke's changes back when a second finger cancels it (a pinch),
// the step-through state, the influence view's picking, the skeleton's drawing and bone tool (skeleton/), errors
// to the banner and its events to the app's.
import { SolverView } from './solver_view.js';
import { viewLabel } from '../methods.js';

export class ViewWiring {
  /**
   * @param {{ parent: HTMLElement, state: import('../app_state.js').AppState,
   *           editor: import('../interaction/handle_editor.js').HandleEditor, parts: import('../parts/volume_parts.js').VolumeParts,
   *           stepping: import('../step_through.js').StepThrough, influence: import('../influence/influence.js').Influence,
   *           skeleton: import('../skeleton/skeleton.js').Skeleton, banner: { show: Function },
   *           views: import('./solver_views.js').SolverViews, dispatch: (event: object) => void }} parts
   */
  constructor({ parent, state, editor, parts, stepping, influence, skeleton, banner, views, dispatch }) {
    Object.assign(this, { parent, state, editor, parts, stepping, influence, skeleton, banner, views, dispatch });
    this.diagonal = 1; // of the model and its cage: the brush radius is a fraction of it
    this.stroke = null; // what a brush or lasso stroke may change, to put back if it is cancelled
  }

  /** A new view for `key` (a method, or 'subspace:<coordinates>': methods.js), wired. */
  create(key) {
    const settings = this.state.settings;
    const values = settings.values;
    const view = new SolverView(this.parent, key, {
      handles: this.editor.handles,
      brushRadius: () => values.brushRadius * this.diagonal,
      tool: () => values,
      state: this.state, // the view follows the settings' changes itself
    });
    if (this.stepping.paused) view.setPaused(true);
    view.applySolverSettings(settings);
    view.applyDisplay(values);
    view.addEventListener('frame', () => this.dispatch({ type: 'frame', view: view.method }));
    view.addEventListener('error', (e) => this.banner.show(`${viewLabel(view.key)}: ${e.error.message}`));
    // While painting parts, the picker's strokes paint the current part instead of selecting handle vertices.
    view.addEventListener('pick', (e) => (this.parts.painting ? this.parts.paint([e.vertex], e.op) : this.editor.pick(e.vertex, e.op)));
    view.addEventListener('select', (e) => (this.parts.painting ? this.parts.paint(e.vertices, e.op) : this.editor.select(e.vertices, e.op)));
    view.addEventListener('stroke', (e) => this.#onStroke(e.phase));
    view.addEventListener('camera', () => this.views.linkCameras(view));
    this.influence.attach(view);
    // One tap, one tool: while influence picking is on, taps pick cage vertices, even in the bone tool (docs/app.md).
    this.skeleton.attach(view, () => values.tool === 'bone' && !this.influence.picking);
    return view;
  }

  /** A stroke starts (save what it may change), ends (one undo step of paint), or is cancelled by a second finger (put it back). */
  #onStroke(phase) {
    const target = this.parts.painting ? this.parts : this.editor;
    if (phase === 'start') this.stroke = { target, saved: target.saveStroke() };
    else if (phase === 'cancel' && this.stroke) this.stroke.target.restoreStroke(this.stroke.saved);
    else if (phase === 'end') this.stroke?.target.endStroke?.();
    if (phase !== 'start') this.stroke = null;
  }
}
