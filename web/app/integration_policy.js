// Which integration the subspace method uses for the next request (docs/app.md, docs/method.md section 17):
// reduced while the handles move, on models where it pays, and the solver option's (full by default) once they
// rest, so the shape that settles is the full answer. The setting dragIntegration: 'auto' reduces for models of
// at least AUTO_REDUCED_VERTICES vertices whose reduced rule passed its test (a rule that misses part of the
// energy would drag a different shape: then 'auto' keeps full integration and the app says why); 'reduced' and
// 'full' always or never. A drag's end (a pointer release) is a rest at once.

/** Below this, a full iteration is already within a frame or two on a laptop core (docs/benchmarks.md). */
export const AUTO_REDUCED_VERTICES = 20000;
/**
 * The handles count as resting when their targets have not changed for RESTING_MS, or for three of the drag's
 * own intervals between changes when those are longer (a huge model drawn by a slow renderer changes its targets
 * once per slow frame: without this, every pause between two frames would look like a rest and start a full
 * iteration in the middle of the drag), at most MAX_RESTING_MS.
 */
export const RESTING_MS = 300;
export const MAX_RESTING_MS = 3000;

export class IntegrationPolicy {
  constructor() {
    this.whileMoving = 'auto'; // 'auto' | 'full' | 'reduced'
    this.movedAt = -Infinity;
    this.moveInterval = 0; // between the last two changes of a drag (0: none seen yet)
    this.sent = null; // the integration the worker was last told (null: not yet, or options were replaced)
    this.notice = null; // { code, message } when the model's reduced rule failed its test: 'auto' keeps full
  }

  /** A new model: its reduced rule is not known yet. */
  newModel() {
    this.notice = null;
    this.forget();
  }

  /** The model's reduced rule (ReducedIntegrationInfo): one that failed its test is not used while dragging. */
  checkFit(fit) {
    if (fit.reliable) return;
    this.notice = {
      severity: 'warning',
      code: 'reduced_integration_inaccurate',
      message: `the reduced integration's rule misses part of this model's energy (error ${fit.testError.toPrecision(2)} ` +
        'on held-out poses): dragging with full integration',
    };
    this.forget();
  }

  /** The targets or handles changed at `now`. */
  moved(now = performance.now()) {
    // The pace of the last drag is kept across pauses, so that the first change of the next drag (whose interval
    // is not known yet) does not look like a rest either.
    const interval = now - this.movedAt;
    if (interval < MAX_RESTING_MS) this.moveInterval = interval;
    this.movedAt = now;
  }

  /** The drag ended (a pointer release): the targets rest from now on, without waiting for RESTING_MS. */
  released() {
    this.movedAt = -Infinity; // the drag's pace (moveInterval) is kept, as across any pause
  }

  /** Whether the targets have rested long enough at `now` for the settled integration. */
  resting(now = performance.now()) {
    return now - this.movedAt >= Math.min(MAX_RESTING_MS, Math.max(RESTING_MS, 3 * this.moveInterval));
  }

  /** The worker's options were replaced: choose again before the next request. */
  forget() {
    this.sent = null;
  }

  /**
   * Whether the worker was last told another integration than `settled` (the drag's): an answer that converged on
   * it is not the settled one yet, the switch at rest solves on.
   */
  refines(settled) {
    return this.sent !== null && this.sent !== settled;
  }

  /** Whether the method iterates on the reduced rule while the handles move. */
  reduces(method, model) {
    if (method !== 'subspace' || !model) return false;
    if (this.whileMoving === 'auto') return model.vertexCount >= AUTO_REDUCED_VERTICES && !this.notice;
    return this.whileMoving === 'reduced';
  }

  /** The integration wanted now: the drag's while the targets move, `settled` (the solver option) at rest. */
  wanted(method, model, settled, now = performance.now()) {
    if (this.resting(now) || method !== 'subspace') return settled;
    if (this.whileMoving === 'auto') return this.reduces(method, model) ? 'reduced' : settled;
    return this.whileMoving;
  }

  /**
   * The integration to tell the worker, or null when it already has it; `switched` is true for a change after
   * the first choice (the solve must go on: at rest, to the full answer).
   */
  next(method, model, settled) {
    const integration = this.wanted(method, model, settled);
    if (integration === this.sent) return null;
    const switched = this.sent !== null;
    this.sent = integration;
    return { integration, switched };
  }
}
