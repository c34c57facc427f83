// Step-through: the solver paused, then advanced one iteration at a time in every view, each iteration shown
// with what it did (the Gauss-Newton step, each line-search trial and its alpha, the multiplier lambda and
// each energy term; for ARAP its energy, or one half of an iteration: the local step's best rotations and
// the global step's positions: docs/method.md sections 7, 8 and 13). While paused, handle edits and gizmo
// drags still reach the solvers, which wait: the next step starts from the pose on screen towards the new
// targets. The app exposes it as `app.stepping`; each view draws its trace (view/iteration_trace.js).
//
// Events: 'change' { paused } when paused or resumed; 'trace' { view, trace } after each step of a view,
// trace = { kind: 'iteration', stats, result } or { kind: 'half', half } (ARAP half step).
import { EventDispatcher } from 'three';
import { AppLifetime } from './app_lifetime.js';

export class StepThrough extends EventDispatcher {
  /**
   * @param {{ views: import('./view/solver_views.js').SolverViews, ready: () => Promise<unknown>,
   *   life: import('./app_lifetime.js').AppLifetime }} parts views: the views on screen (their `list` is read at each
   *   call: compare mode changes it); ready: the app's first load; life: the app's, whose end rejects a pending step
   */
  constructor({ views, ready, life = new AppLifetime() }) {
    super();
    this.views = views;
    this.ready = ready;
    this.life = life;
    this.paused = false;
    /** @type {Map<object, 'local'|'global'>} the next ARAP half step of each view (local first) */
    this.halves = new Map();
  }

  /**
   * Pauses (or resumes) every view's solver. Resolves once a pause has taken effect (no step in flight); rejects with
   * a CancelledError when the app is disposed first (its workers' answers never come then).
   */
  setPaused(paused) {
    return this.life.guard(() => this.#setPaused(paused));
  }

  async #setPaused(paused) {
    this.paused = !!paused;
    for (const view of this.views.list) view.setPaused(this.paused);
    this.halves.clear();
    this.dispatchEvent({ type: 'change', paused: this.paused });
    if (this.paused) await Promise.all(this.views.list.map((v) => v.session.idle()));
  }

  /** Resumes if paused, pauses otherwise. */
  toggle() {
    return this.setPaused(!this.paused);
  }

  /**
   * One iteration in every view (pausing first if needed; compare views still binding are waited for: `ready`).
   * Resolves with one trace per view, in view order: { method, kind: 'iteration', stats (the iteration's
   * IterationStats, or null when the solver had nothing to do: `idle` says why), result: { converged, stop,
   * stopReason }, skeleton: the bones' report after it, or null }. Rejects with a CancelledError when the app is
   * disposed first.
   */
  next() {
    return this.life.guard(() => this.#next());
  }

  async #next() {
    await this.ready();
    if (!this.paused) await this.#setPaused(true);
    this.halves.clear();
    return Promise.all(this.views.list.map(async (view) => {
      const result = await view.session.stepOnce();
      const trace = { method: view.method, kind: 'iteration', stats: result?.iterations.at(-1) ?? null,
        result: result ? { converged: result.converged, stop: result.stop, stopReason: result.stopReason } : null,
        skeleton: view.skeletonView.report }; // with bones: each one's multiplier and errors after the step
      if (!trace.stats) trace.idle = idleReason(view.session, result);
      this.#show(view, trace);
      return trace;
    }));
  }

  /**
   * ARAP views: the next half of a local-global iteration, local (the best rotation of every vertex for the
   * positions on screen) then global (the positions for those rotations); other views do nothing. Resolves
   * with one trace per ARAP view: { method, kind: 'half', half: { phase, energyBefore, energyAfter,
   * meanRotation, maxRotation, step } } (rotations in radians). Rejects with a CancelledError when the app is disposed
   * first.
   */
  nextHalf() {
    return this.life.guard(() => this.#nextHalf());
  }

  async #nextHalf() {
    await this.ready();
    if (!this.paused) await this.#setPaused(true);
    const arap = this.views.list.filter((v) => v.method === 'arap');
    return Promise.all(arap.map(async (view) => {
      const phase = this.halves.get(view) ?? 'local';
      const half = await view.session.arapHalfStep(phase);
      this.halves.set(view, phase === 'local' ? 'global' : 'local');
      const trace = { method: view.method, kind: 'half', half };
      this.#show(view, trace);
      return trace;
    }));
  }

  /** The half step the ARAP views take next ('local' or 'global'). */
  get nextPhase() {
    const view = this.views.list.find((v) => v.method === 'arap');
    return (view && this.halves.get(view)) ?? 'local';
  }

  /** Whether an ARAP view is on screen (half steps apply to it). */
  get hasArap() {
    return this.views.list.some((v) => v.method === 'arap');
  }

  #show(view, trace) {
    view.showTrace(trace);
    this.dispatchEvent({ type: 'trace', view: view.method, trace });
  }
}

/** Why a step ran no iteration, as the step-through's box says it. */
function idleReason(session, result) {
  if (!session.client) return 'still binding the model: step again once it is bound';
  if (!session.hasHandles) return 'no handles, nothing to step';
  if (result?.nothingToDo) {
    const at = session.last ? ` at iteration ${session.last.iteration}` : '';
    return `converged${at}: nothing to do (move a handle to solve again)`;
  }
  return result?.stopReason || 'no iteration';
}
