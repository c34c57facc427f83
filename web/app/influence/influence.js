// "What does this cage vertex control?": the mesh coloured by one column of the subspace basis (the weight of
// one cage vertex at every mesh vertex, or one column of the spectral basis), negative weights in a colour of
// their own, the scale in a legend. Each view asks its own worker for the column (its own coordinates: in
// "compare coordinates" two types side by side), and the views share one scale. While picking is on, a click
// (or tap) near a cage vertex shows that vertex; the handle selection is off meanwhile.
//
// After every change it calls dispatch({ type: 'influence', column, picking }) (column null: nothing shown).
import { InputError } from '../../lib/errors.js';
import { isSpectral } from '../../lib/subspace.js';
import { COORDINATE_LABELS } from '../methods.js';
import { cageVertexAt } from './cage_vertex_picking.js';
import { influenceColors, sharedScale } from './influence_colors.js';

const CLICK_PIXELS = 5; // a press that moves less than this is a click, not an orbit
const PICK_PIXELS = { mouse: 14, pen: 14, touch: 28 }; // how near a cage vertex a click must be

export class Influence {
  /**
   * @param {{ views: import('../view/solver_views.js').SolverViews, banner: { show: Function },
   *           dispatch: (event: object) => void }} parts views: the views on screen (their `list` is read at each call)
   */
  constructor({ views, banner, dispatch }) {
    this.views = views;
    this.dispatch = dispatch;
    this.banner = banner;
    /** The basis column shown, or null. */
    this.column = null;
    this.picking = false;
    /** The shared scale of what is shown ({ min, max }), or null. */
    this.scale = null;
    this.request = 0; // the latest show(): older answers are dropped
  }

  /** Picking on/off: while on, a click near a cage vertex shows it (and selects no handle vertices). */
  setPicking(on) {
    this.picking = !!on;
    for (const view of this.views.list) view.picker.enabled = !this.picking;
    this.#changed();
  }

  /**
   * Colours every view's mesh by basis column `column` (a cage vertex, or a spectral column) and shows the legend.
   * Resolves once every view shows it; rejects (and shows the banner) with an InputError for a column out of range.
   * @param {number} column from 0 to the basis size - 1
   */
  async show(column) {
    const views = this.views.list.filter((view) => view.session.model);
    const size = views[0]?.session.model.basisSize ?? 0;
    if (!(Number.isInteger(column) && column >= 0 && column < size)) {
      const error = new InputError(`influence: the column must be an integer from 0 to ${size - 1} (got ${JSON.stringify(column)})`);
      this.banner.show(error.message);
      throw error;
    }
    const request = ++this.request;
    const answers = await Promise.all(views.map((view) => view.session.request('basisColumn', { column })));
    if (request !== this.request) return; // a newer show() or hide() came meanwhile
    this.column = column;
    this.scale = sharedScale(answers);
    views.forEach((view, k) => {
      const { colors, negative } = influenceColors(answers[k].values, this.scale);
      const model = view.session.model;
      view.showInfluence({
        colors,
        cageVertex: model.basis === 'cage' ? column : -1,
        legend: { title: titleOf(model, column), scale: this.scale, range: answers[k], negative, vertices: answers[k].values.length },
      });
    });
    this.#changed();
  }

  /** Back to the plain (or volume parts') colours. */
  hide() {
    ++this.request;
    this.column = null;
    this.scale = null;
    for (const view of this.views.list) view.showInfluence(null);
    this.#changed();
  }

  /** After a new binding (or new compare views): shows the same column again if the basis still has it. */
  async refresh() {
    if (this.column === null) return;
    const size = this.views.list[0]?.session.model?.basisSize ?? 0;
    if (this.column >= size) return this.hide();
    return this.show(this.column).catch(() => {});
  }

  /** Listens to a view's clicks for picking (the view's own pointer handlers keep working). */
  attach(view) {
    const canvas = view.viewport.canvas;
    let down = null;
    canvas.addEventListener('pointerdown', (event) => {
      down = this.picking && event.isPrimary ? { x: event.clientX, y: event.clientY, id: event.pointerId } : null;
    }, true);
    canvas.addEventListener('pointerup', (event) => {
      if (!down || event.pointerId !== down.id) return;
      const moved = Math.hypot(event.clientX - down.x, event.clientY - down.y);
      down = null;
      if (moved > CLICK_PIXELS) return;
      const vertex = cageVertexAt(view.viewport, event, PICK_PIXELS[event.pointerType] ?? PICK_PIXELS.mouse);
      if (vertex >= 0) this.show(vertex).catch(() => {});
    }, true);
    view.picker.enabled = !this.picking;
  }

  #changed() {
    this.dispatch({ type: 'influence', column: this.column, picking: this.picking });
  }
}

// What a column is, for the legend: a cage vertex with the view's coordinates, or a spectral column (the
// constant, x, y and z, then the modes).
function titleOf(model, column) {
  if (isSpectral(model)) {
    const names = ['constant', 'x', 'y', 'z'];
    return `spectral basis column ${column}: ${column < 4 ? names[column] : `mode ${column - 3}`}`;
  }
  const coordinates = model.coordinates?.coordinates ?? 'mvc';
  return `cage vertex ${column} \u00b7 ${COORDINATE_LABELS[coordinates]} coordinates`;
}
