// Volume kept per part in the app (docs/method.md section 16): the "parts" painting mode (brush and lasso
// paint the current part instead of selecting handle vertices), automatic parts, and the partition each
// view's solver keeps. The partition goes to every view's worker (setVolumeParts) and again after every new
// binding of the same mesh (a new basis or cage); a new mesh clears it. The parts are shown as vertex colours, and
// the paint is what the brush edits: parts the solvers keep (painted and kept, automatic, a saved scene's) are
// painted too, so a further stroke adds to them. Each stroke, tap and change of the kept parts is one undo step
// in the app's one timeline (edit_timeline.js), with the handles' and the skeleton's edits.
//
// Events: 'change' { painting, current, parts } after every edit (parts: the number of parts the solvers keep,
// 0 for the one global volume). A model of several components keeps one volume per component unless told
// otherwise (parts then counts them), and "global" keeps one volume for all.
import { EventDispatcher } from 'three';
import { InputError } from '../../lib/errors.js';
import { checkVolumePartsSpec } from '../../lib/parts.js';
import { MAX_PARTS, PartsPainter } from './parts_painter.js';
import { EditTimeline } from '../interaction/edit_timeline.js';
import { UndoHistory } from '../interaction/undo_history.js';

// A paint step is a byte per vertex: 100 steps of a million-vertex model are 100 MB at most.
const MAX_STEPS = 100;

export class VolumeParts extends EventDispatcher {
  /**
   * @param {{ views: import('../view/solver_views.js').SolverViews, banner: { show: Function }, timeline?: EditTimeline }} parts
   *   views: the views on screen (their `list` is read at each call: compare mode changes it); timeline: the app's
   *   one undo timeline
   */
  constructor({ views, banner, timeline = new EditTimeline() }) {
    super();
    this.views = views;
    this.banner = banner;
    this.painter = new PartsPainter();
    this.history = new UndoHistory(timeline, { max: MAX_STEPS });
    timeline.join({ history: this.history, undo: () => this.#travel('undo'), redo: () => this.#travel('redo') });
    this.kept = null; // the paint when the kept parts last changed: what a saved scene holds of it
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
      this.kept = this.painter.snapshot();
      this.history.clear();
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

  /** Brush or lasso strokes while painting: one undo step per stroke (or per tap outside a stroke). */
  paint(vertices, op) {
    // While auto parts, the default or a scene's parts are being made, their answer replaces the paint: a stroke
    // meanwhile would be lost, so the brush waits.
    if (this.#repainting > 0 || !this.painter.changes(vertices, op)) return;
    if (this.#stroke?.stamp === undefined) {
      const stamp = this.history.record({ paint: this.painter.snapshot() }); // a stroke changes the paint alone
      if (this.#stroke) this.#stroke.stamp = stamp;
    }
    this.painter.paint(vertices, op);
    this.#show();
  }

  #stroke = null; // the stroke under way: { stamp } (its undo step's, once taken)

  /** A stroke starts: what it may change (the paint), to put back if it is cancelled (a second finger: a pinch). */
  saveStroke() {
    this.#stroke = {};
    return this.painter.vertexPart?.slice() ?? null;
  }

  /** The stroke is over (the pointer released, or a new model). */
  endStroke() {
    this.#stroke = null;
  }

  restoreStroke(saved) {
    if (saved) this.painter.vertexPart = saved.slice();
    // A cancelled stroke never happened: its step goes, and the redo it ended comes back.
    if (this.#stroke?.stamp !== undefined) this.history.drop(this.#stroke.stamp);
    this.#stroke = null;
    this.#show();
  }

  /**
   * Whether there is paint the solvers do not keep ("keep painted parts" not pressed since): a saved scene holds
   * the parts the solvers keep, not that paint.
   */
  get unkeptPaint() {
    return !!this.painter.vertexPart && !this.painter.same(this.kept);
  }

  /** Keeps the painted parts' volumes (the unpainted vertices form one more part). */
  apply() {
    const spec = this.painter.description();
    if (!spec) {
      this.banner.show('Paint parts first: turn on "paint parts" (P) and shift-drag (brush) or alt-drag (lasso) on the mesh.', { kind: 'info' });
      return Promise.resolve(0);
    }
    return this.#use(spec, { painted: true });
  }

  /** K automatic parts (spectral clustering in the worker). */
  auto(parts) {
    return this.use({ auto: parts });
  }

  /** Back to the default volume (one per component: the global one for a single mesh); the painted parts are cleared too. */
  clear() {
    return this.#use(null, { cleared: true });
  }

  /**
   * Makes every view keep the volume of the parts a description gives (web/lib/parts.js; null: the global
   * volume), one undo step. Resolves with the number of parts. The parts are painted (vertex lists as they are,
   * list k as part k; automatic and triangle parts per triangle), so that the brush adds to them.
   * @param {object|null} spec
   * @param {{ partition?: Int32Array|null, freshHistory?: boolean }} [options] partition: what a worker already
   *   made of `spec` on this mesh (one part per triangle; a scene's parts, made while the scene was checked), sent
   *   as it is; freshHistory: no undo step (a scene with its own model: there was nothing before it)
   */
  use(spec, options = {}) {
    return this.#use(spec, options);
  }

  // `painted`: the spec is the paint's own (keep painted parts): the paint stays as it is, part numbers and all,
  // and what is kept is the paint as it was sent, not strokes made while the workers answer.
  // `cleared`: the paint goes too (the default parts).
  // The undo step is recorded now, so that it comes before strokes made while the workers answer (their undo takes
  // them back first); what the solvers kept before it is filled in when its turn comes (sends go in order).
  async #use(spec, { partition = null, freshHistory = false, painted = false, cleared = false }) {
    let normalised;
    try {
      normalised = spec === null ? null : checkVolumePartsSpec(spec, 'volumeParts');
    } catch (error) {
      this.banner.show(error.message);
      throw error;
    }
    const kind = normalised?.kind;
    const repaint = cleared || (kind === 'vertices' && !painted) || kind === 'auto' || kind === 'triangles';
    const sent = this.painter.snapshot();
    const before = { paint: sent, spec: this.spec, kept: this.kept };
    const stamp = freshHistory ? null : this.history.record(before);
    return this.#inTurn(async () => {
      Object.assign(before, { spec: this.spec, kept: this.kept });
      let parts;
      try {
        parts = await this.#send(partition ?? spec);
      } catch (error) {
        if (stamp !== null) this.history.drop(stamp);
        this.banner.show(error.message);
        throw error;
      }
      this.spec = spec;
      if (cleared && this.indices) this.painter.reset(this.painter.vertexPart.length);
      if (kind === 'vertices' && !painted) this.painter.fromVertexLists(normalised.lists);
      if (kind === 'auto' || kind === 'triangles') this.painter.fromTriangles(parts, this.indices); // what the worker made
      this.kept = repaint ? this.painter.snapshot() : sent;
      if (freshHistory) this.history.clear();
      this.#show();
      return this.count;
    }, repaint);
  }

  #queue = Promise.resolve(); // settles once every send so far is answered
  #pending = 0; // sends of kept parts not yet answered (changes, undo and redo of them)
  #repainting = 0; // of them, those whose answer replaces the paint

  // Runs `job` (async) once the sends before it are answered: the workers take the kept parts in the order asked.
  #inTurn(job, repaint = false) {
    const run = () => job().finally(() => {
      --this.#pending;
      if (repaint) --this.#repainting;
    });
    const result = this.#pending === 0 ? run() : this.#queue.then(run, run);
    ++this.#pending;
    if (repaint) ++this.#repainting;
    this.#queue = result.catch(() => {});
    return result;
  }

  // Undo or redo of a stroke (the paint alone, at once) or of a change of the kept parts (in turn, after the sends
  // before it: a press meant for a step that is gone by then, dropped as refused or taken by a later stroke, does
  // nothing).
  #travel(way) {
    const next = this.history.peek(way);
    if (!next) return false;
    if (!('spec' in next.snapshot)) {
      this.painter.restore(this.history[way]({ paint: this.painter.snapshot() }).paint);
      this.#show();
      return true;
    }
    this.#inTurn(async () => {
      if (this.history.peek(way)?.stamp === next.stamp) await this.#travelKept(way);
    }).catch(() => {});
    return true;
  }

  // The solvers get the step's parts again when they differ; the step's description and kept paint are the
  // solvers' only once they take them (a refusal is named in the banner, and the parts they keep stay described).
  async #travelKept(way) {
    const step = this.history[way]({ paint: this.painter.snapshot(), spec: this.spec, kept: this.kept });
    this.painter.restore(step.paint);
    this.#show();
    try {
      if (step.spec !== this.spec) await this.#send(step.spec);
      this.spec = step.spec;
      this.kept = step.kept;
    } catch (error) {
      this.banner.show(error.message);
    }
    this.#show();
  }

  // The first view computes the partition; the others take it per triangle (no second clustering).
  async #send(spec) {
    const [first, ...rest] = this.views.list;
    const reply = await first.session.request('setVolumeParts', { parts: spec });
    const parts = reply.parts;
    for (const view of rest) await view.session.request('setVolumeParts', { parts: parts.length ? parts : null });
    for (const view of this.views.list) view.session.partsChanged();
    this.count = partCount(parts);
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

// How many parts a partition per triangle has (0: none, the default). A loop: Math.max(...parts) spreads one argument
// per triangle and overflows the call stack above some 100k triangles.
export function partCount(parts) {
  let largest = -1;
  for (const part of parts) if (part > largest) largest = part;
  return largest + 1;
}
