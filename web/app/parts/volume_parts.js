// Volume kept per part in the app (docs/method.md section 16): the "parts" painting mode (brush and lasso
// paint the current part instead of selecting handle vertices), automatic parts, and the partition each
// view's solver keeps. The partition goes to every view's worker (setVolumeParts) and again after every new
// binding of the same mesh (a new basis or cage); a new mesh clears it. The parts are shown as vertex colours.
//
// Events: 'change' { painting, current, parts } after every edit (parts: the number of parts the solvers keep,
// 0 for the one global volume). A model of several components keeps one volume per component unless told
// otherwise (parts then counts them), and "global" keeps one volume for all.
import { EventDispatcher } from 'three';
import { InputError } from '../../lib/errors.js';
import { checkVolumePartsSpec } from '../../lib/parts.js';
import { MAX_PARTS, PartsPainter } from './parts_painter.js';

export class VolumeParts extends EventDispatcher {
  /**
   * @param {{ views: import('../view/solver_views.js').SolverViews, banner: { show: Function } }} parts views: the views
   *   on screen (their `list` is read at each call: compare mode changes it)
   */
  constructor({ views, banner }) {
    super();
    this.views = views;
    this.banner = banner;
    this.painter = new PartsPainter();
    this.painting = false;
    this.indices = null;
    /** The description the solvers keep (web/lib/parts.js), or null for the default (one per component). */
    this.spec = null;
    this.count = 0;
  }

  get current() {
    return this.painter.current;
  }

  /** The parts description as a scene writes it (docs/scene-format.md), or null for the default parts. */
  get sceneSpec() {
    const s = this.spec;
    if (!s) return null;
    if (s.kind === 'auto') return { auto: s.parts };
    return s.kind ? { [s.kind]: s.lists } : s;
  }

  /** A model was bound: the same mesh keeps its parts (sent to the new workers), a new one starts without. */
  async onLoad(model, sameMesh) {
    this.indices = model.mesh.indices;
    if (!sameMesh) {
      this.painter.reset(model.mesh.positions.length / 3);
      this.spec = null;
      this.count = model.volumePartCount > 1 ? model.volumePartCount : 0;  // components keep their own volumes
      this.#show();
      return;
    }
    if (this.spec) await this.#send(this.spec).catch((error) => this.banner.show(error.message));
    this.#show();
  }

  /** Parts painting on/off: while on, the brush and the lasso paint the current part. */
  setPainting(on) {
    this.painting = !!on;
    this.#changed();
  }

  /** The part the brush paints (0 .. MAX_PARTS - 1). */
  setCurrent(part) {
    if (!(Number.isInteger(part) && part >= 0 && part < MAX_PARTS)) {
      throw new InputError(`parts: the painted part must be an integer from 0 to ${MAX_PARTS - 1} (got ${part})`);
    }
    this.painter.current = part;
    this.#changed();
  }

  /** Brush or lasso strokes while painting. */
  paint(vertices, op) {
    this.painter.paint(vertices, op);
    this.#show();
  }

  /** What a stroke may change (the paint), to put back if it is cancelled (a second finger: a pinch). */
  saveStroke() {
    return this.painter.vertexPart?.slice() ?? null;
  }

  restoreStroke(saved) {
    if (saved) this.painter.vertexPart = saved.slice();
    this.#show();
  }

  /** Keeps the painted parts' volumes (the unpainted vertices form one more part). */
  apply() {
    const spec = this.painter.description();
    if (!spec) {
      this.banner.show('Paint parts first: turn on "paint parts" (P) and shift-drag (brush) or alt-drag (lasso) on the mesh.', { kind: 'info' });
      return Promise.resolve(0);
    }
    return this.use(spec);
  }

  /** K automatic parts (spectral clustering in the worker). */
  auto(parts) {
    return this.use({ auto: parts });
  }

  /** Back to the default volume (one per component: the global one for a single mesh); the painted parts are cleared too. */
  clear() {
    if (this.indices) this.painter.reset(this.painter.vertexPart.length);
    return this.use(null);
  }

  /**
   * Makes every view keep the volume of the parts a description gives (web/lib/parts.js; null: the global
   * volume). Resolves with the number of parts.
   * @param {object|null} spec
   * @param {{ partition?: Int32Array|null }} [options] partition: what a worker already made of `spec` on
   *   this mesh (one part per triangle; a scene's parts, made while the scene was checked), sent as it is
   */
  async use(spec, { partition = null } = {}) {
    let parts;
    try {
      if (spec !== null) checkVolumePartsSpec(spec, 'volumeParts');
      parts = await this.#send(partition ?? spec);
    } catch (error) {
      this.banner.show(error.message);
      throw error;
    }
    this.spec = spec;
    if (spec && (spec.auto !== undefined || spec.kind === 'auto' || spec.triangles || spec.kind === 'triangles')) {
      this.painter.fromTriangles(parts, this.indices);  // show (and let the brush edit) what the worker made
    }
    this.#show();
    return this.count;
  }

  // The first view computes the partition; the others take it per triangle (no second clustering).
  async #send(spec) {
    const [first, ...rest] = this.views.list;
    const reply = await first.session.request('setVolumeParts', { parts: spec });
    const parts = reply.parts;
    for (const view of rest) await view.session.request('setVolumeParts', { parts: parts.length ? parts : null });
    for (const view of this.views.list) view.session.partsChanged();
    this.count = parts.length ? Math.max(...parts) + 1 : 0;
    return parts;
  }

  #show() {
    const colors = this.painter.colors();
    for (const view of this.views.list) view.showParts(colors);
    this.#changed();
  }

  #changed() {
    this.dispatchEvent({ type: 'change', painting: this.painting, current: this.current, parts: this.count });
  }
}
