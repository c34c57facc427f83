// One solver session seen from the page: a worker (SolverClient) holding a Deformer for one method, the
// latest handles/targets/options to send, and the stepping loop. pump() is called every animation frame;
// it never waits: at most one step request is in flight, and rendering goes on while the worker iterates.
// After the handles stop moving it keeps stepping until the solver reports convergence (or the iteration cap).
import { InputError } from '../lib/errors.js';
import { isCancelled, stoppedByFailure } from './errors.js';
import { IntegrationPolicy } from './integration_policy.js';
import { prepareLoad } from './loading/prepared_load.js';
import { SolveRecord } from './solve_record.js';

const FRAME_BUDGET_MS = 25; // auto iterations per request: keep one request near a frame or two
// A worker answers a step, then waits for the page to ask for the next one; the page reads the answer only
// between its frames. In compare mode on a software renderer a frame draws three views and takes 60-90 ms,
// so a view whose request takes 30-50 ms sat idle for half of each cycle and updated once per frame at
// best (scripts/bench/compare.mjs, docs/app.md). Requests shorter than this get a second one queued behind them, so
// the worker goes on while the page draws; longer ones gain little from it and would waste a long
// iteration after convergence.
const PIPELINE_MS = 100;
// Compare mode shares the cores (and, with a software renderer, the drawing) between the views. A method
// whose request takes longer than SLOW_REQUEST_MS cannot follow a drag anyway: its answer is stale when it
// arrives, and while the handles move it only takes CPU from the others. Such a view waits while the targets
// keep changing (changed in the last HOLD_MS), taking one request at least every MAX_HOLD_MS so it still
// shows progress, and solves at full speed once the handles stop (measurements: docs/app.md).
const SLOW_REQUEST_MS = 250;
const HOLD_MS = 200;
const MAX_HOLD_MS = 1000;

export class Session {
  /**
   * @param {{ method: string, onFrame: (frame) => void, onError: (error: Error) => void,
   *           onProgress?: (fraction: number, phase: string) => void }} options
   */
  constructor({ method, onFrame, onError, onProgress }) {
    this.method = method;
    this.onFrame = onFrame;
    this.onError = onError;
    this.onProgress = onProgress;
    this.client = null;
    this.loading = null; // the client binding a new model (terminated to cancel)
    this.model = null;
    this.options = {};
    this.iterationsPerStep = 'auto';
    this.maxIterations = 100;
    this.record = new SolveRecord(method); // merit series, time per iteration, progress
    this.state = 'idle'; // idle | solving | converged | stopped | error
    this.#clearStats();
    this.version = 0; // bumps on every handle / target / option change
    this.solvedVersion = -1;
    this.pending = { options: null, handles: null, targets: null };
    this.inFlight = 0; // step requests sent and not answered (at most 2: see PIPELINE_MS)
    this.queuedIterations = 0; // their iterations
    this.hasHandles = false;
    this.waiters = [];
    this.yieldWhileMoving = false; // set in compare mode: see SLOW_REQUEST_MS
    this.lastRequestAt = 0;
    this.paused = false; // step-through (step_through.js): changes are sent, iterations only by stepOnce()
    this.idleWaiters = [];
    this.integration = new IntegrationPolicy(); // reduced while the handles move (integration_policy.js)
  }

  /**
   * Loads a model in a fresh worker; the current one keeps running (and its model stays on screen) until
   * the new one is bound. Rejects with the cancelled error (errors.js) when cancelLoad() is called or a newer
   * load starts.
   * @param {string} type 'loadExample' | 'loadFiles' | 'loadMeshes'
   * @param {object} payload
   * @param {{ transfer?: Transferable[], check?: (model: object, client: import('../lib/worker/solver_client.js').SolverClient) => Promise<void>|void }} [options]
   *   check: runs on the new model in its new worker before anything changes here; when it throws, the load
   *   fails with that error and the current model stays (a scene whose handles do not fit the mesh it names)
   */
  load(type, payload, options = {}) {
    return prepareLoad(this, type, payload, options).then((prepared) => prepared.commit());
  }

  /** Makes a bound and checked worker this session's (loading/prepared_load.js): the old one goes, the solve
   *  starts from the new rest pose. */
  adopt(client, model) {
    this.loading = null;
    this.client?.terminate();
    this.client = client;
    this.model = model;
    this.inFlight = 0;
    this.queuedIterations = 0;
    this.hasHandles = false;
    this.pending = { options: { ...this.options, method: this.method }, handles: null, targets: null };
    this.integration.newModel();
    // Fit the reduced integration now rather than at the first step of a drag (queued before any step); a rule
    // that fails its test keeps the drag on full integration.
    if (this.integration.reduces(this.method, model)) {
      const checked = (fit) => { if (client === this.client) this.integration.checkFit(fit); };
      client.request('prepareReduced').then(checked, (error) => this.#fail(error));
    }
    this.record.newModel();
    this.#clearStats();
    this.state = 'idle';
    return model;
  }

  cancelLoad() {
    this.loading?.terminate();
    this.loading = null;
  }

  /** Another method (its solve starts from rest in the worker): a fresh plot series and timings. */
  setMethod(method) {
    this.method = method;
    this.record.setMethod(method);
    this.#clearStats();
    this.setOptions(this.options);
  }

  setOptions(options) {
    this.options = { ...options };
    this.pending.options = { ...options, method: this.method };
    this.integration.forget();
    this.record.expectSetUp(); // the position weight or the method may re-factor
    this.#changed();
  }

  setHandles(groups, targets, lines = null) {
    this.integration.moved();
    this.hasHandles = groups.length > 0 && groups.some((g) => g.length > 0);
    this.pending.handles = groups.map((g) => [...g]);
    this.pending.targets = { targets, lines };
    this.record.expectSetUp();
    this.#changed();
  }

  /** Targets, with each group's handle line (handle_lines.js; null: point targets). */
  setTargets(targets, lines = null) {
    this.integration.moved();
    this.pending.targets = { targets, lines };
    this.#changed();
  }

  /** Tells the worker when the integration changes; a switch back to full at rest solves on to the full answer. */
  #chooseIntegration() {
    const change = this.integration.next(this.method, this.model, this.options.integration ?? 'full');
    if (!change) return;
    this.pending.options = { ...this.options, method: this.method, integration: change.integration };
    if (change.switched && this.hasHandles) this.#changed();
  }

  /** The volume parts changed in the worker (positions kept): solve again to restore them. */
  partsChanged() {
    this.#changed();
  }

  /** Back to the rest pose in the worker, then the same targets are solved again (a fresh series). */
  async resolveFromRest() {
    this.record.restart();
    this.#clearStats();
    if (!this.client) return;
    this.#changed();
    const frame = await this.client.request('reset');
    this.onFrame(frame, this);
  }

  #clearStats() {
    this.last = null; // last IterationStats
    this.stopReason = '';
    this.warnings = []; // the settled result's warnings (Deformer.resultWarnings): folds, a crossed cage
  }

  #changed() {
    this.version++;
    this.record.changed();
    this.state = this.hasHandles ? 'solving' : 'idle';
    this.warnings = [];
  }

  // A solve settled: its record ends, and what its result should be warned about is asked (once per version).
  #settled(version, client = this.client) {
    this.record.ended();
    client?.request('resultWarnings').then((w) => { if (client === this.client && version === this.version) this.warnings = w; }, () => {});
  }

  /** The current series' merits (the plot). */
  get history() {
    return this.record.points;
  }

  /** Iterations in the current series (since the load, the method switch or the last re-solve). */
  get totalIterations() {
    return this.record.iterations;
  }

  /** Median ms of the last iterations without one-off work (0 before the first). */
  get msPerIteration() {
    return this.record.msPerIteration;
  }

  /** The current solve: iterations since the last change, elapsed and remaining time (SolveRecord.progress). */
  get progress() {
    return this.record.progress(this.maxIterations, this.inFlight > 0);
  }

  get iterationsForNextStep() {
    if (this.iterationsPerStep !== 'auto') return Math.max(1, this.iterationsPerStep | 0);
    const ms = this.record.requestMs;
    if (!ms) return 1;
    return Math.max(1, Math.min(20, Math.floor(FRAME_BUDGET_MS / ms)));
  }

  /** A slow view in compare mode while the handles move: it leaves the cores to the others for now. */
  #holding() {
    if (!this.yieldWhileMoving || this.record.requestMs * this.iterationsForNextStep < SLOW_REQUEST_MS) return false;
    const now = performance.now();
    return now - this.record.changedAt < HOLD_MS && now - this.lastRequestAt < MAX_HOLD_MS;
  }

  /** Step requests kept in flight: two when a request is short (PIPELINE_MS), else one. */
  #depth() {
    const ms = this.record.requestMs * this.iterationsForNextStep;
    return ms > 0 && ms < PIPELINE_MS ? 2 : 1;
  }

  /** Step-through: while paused only stepOnce() and arapHalfStep() iterate; edits still reach the worker. */
  setPaused(paused) {
    this.paused = paused;
    if (this.#isSettled()) this.#wake(); // a solve() waiting on a paused view resolves (the next pump resumes it)
  }

  /** Resolves when no step request is in flight (a pause has taken effect). */
  idle() {
    if (this.inFlight === 0) return Promise.resolve();
    return new Promise((resolve) => this.idleWaiters.push(resolve));
  }

  /**
   * One iteration now (step-through): what changed is sent first. Resolves with the worker's StepResult, or
   * null without a model or handles.
   */
  async stepOnce() {
    const client = this.client;
    if (!client || !this.hasHandles) return null;
    this.#chooseIntegration();
    this.#sendPending(client);
    const version = this.version;
    this.inFlight++;
    try {
      const frame = await client.request('step', { iterations: 1 });
      if (client !== this.client) return null;
      this.#accept(frame, version);
      this.onFrame(frame, this);
      return frame.result;
    } catch (error) {
      if (client === this.client && !isCancelled(error)) this.#fail(error);
      throw error;
    } finally {
      this.#answered(0);
    }
  }

  /** ARAP step-through: the local or the global half of the next iteration; resolves with its numbers. */
  async arapHalfStep(phase) {
    const client = this.client;
    if (!client || !this.hasHandles) return null;
    this.#sendPending(client);
    const frame = await client.request('arapHalfStep', { phase });
    if (client === this.client) this.onFrame(frame, this);
    return frame.half;
  }

  #answered(iterations) {
    this.inFlight--;
    this.queuedIterations -= iterations;
    if (this.inFlight === 0) {
      if (this.paused) this.#wake();
      const waiters = this.idleWaiters;
      this.idleWaiters = [];
      for (const w of waiters) w();
    }
  }

  /** Sends the pending options, handles and targets. */
  #sendPending(client) {
    const p = this.pending;
    const fail = (error) => this.#fail(error);
    if (p.options) {
      client.request('setOptions', { options: p.options }).catch(fail);
      p.options = null;
    }
    if (p.handles) {
      if (this.hasHandles) client.request('setHandles', { groups: p.handles }).catch(fail);
      // No handles left: the rest pose is the minimizer, show it.
      else client.request('reset').then((frame) => client === this.client && this.onFrame(frame, this)).catch(fail);
      p.handles = null;
    }
    if (p.targets && this.hasHandles) {
      client.request('setTargets', p.targets).catch(fail);
      p.targets = null;
    }
  }

  /** Called every animation frame: sends what changed and asks for the next iterations when needed. */
  pump() {
    const client = this.client;
    if (!client || this.inFlight >= this.#depth()) return;
    const fail = (error) => this.#fail(error);
    this.#chooseIntegration();
    this.#sendPending(client);
    if (!this.hasHandles || this.state === 'error' || this.paused) return;
    const needed = this.version !== this.solvedVersion || this.state === 'solving';
    if (!needed || this.#holding()) return;
    const version = this.version;
    const remaining = this.maxIterations - this.record.sinceChange - this.queuedIterations;
    if (remaining <= 0) {
      if (this.inFlight) return; // the cap is reached once those are answered
      this.state = 'stopped';
      this.stopReason = `not converged after ${this.maxIterations} iterations`;
      this.solvedVersion = version;
      this.record.ended();
      this.#wake();
      return;
    }
    const k = Math.min(this.iterationsForNextStep, remaining);
    this.inFlight++;
    this.queuedIterations += k;
    this.lastRequestAt = performance.now();
    const answered = () => this.#answered(k);
    client
      .request('step', { iterations: k })
      .then((frame) => {
        if (client !== this.client) return;
        answered();
        this.#accept(frame, version);
        this.onFrame(frame, this);
        if (this.#isSettled()) this.#wake();
        // Ask for the next iterations right away: the solve rate must not be tied to the frame rate.
        this.pump();
      })
      .catch((error) => {
        if (client !== this.client) return;
        answered();
        if (!isCancelled(error)) fail(error);
      });
  }

  #accept(frame, version) {
    const { iterations, converged, stopReason } = frame.result;
    this.record.add(iterations);
    if (iterations.length) this.last = iterations.at(-1);
    this.stopReason = stopReason ?? '';
    if (version !== this.version) return; // the handles moved meanwhile: keep going
    if (version === this.solvedVersion && this.state !== 'solving') return; // queued behind the one that settled it
    if (converged) {
      this.state = 'converged';
      this.solvedVersion = version;
    } else if (stoppedByFailure(frame.result) || iterations.length === 0) {
      this.state = 'stopped';
      this.solvedVersion = version;
    } else {
      this.state = 'solving';
    }
    if (this.state !== 'solving') this.#settled(version);
  }

  #fail(error) {
    this.record.ended();
    this.state = 'error';
    this.stopReason = error.message;
    this.solvedVersion = this.version;
    this.onError(error);
    this.#wake();
  }

  /** Resolves when the session is no longer solving (converged, stopped, idle or error). */
  settled() {
    if (this.#isSettled()) return Promise.resolve(this.state);
    return new Promise((resolve) => this.waiters.push(resolve));
  }

  #isSettled() {
    if (this.paused) return this.inFlight === 0; // step-through: nothing more happens until the next step
    // A solve that converged on samples while the handles moved goes on with the full integration once they rest.
    const refining = this.integration.sent !== null && this.integration.sent !== (this.options.integration ?? 'full');
    return !this.hasHandles ||
      (this.state !== 'solving' && this.solvedVersion === this.version && this.inFlight === 0 && !refining);
  }

  #wake() {
    const waiters = this.waiters;
    this.waiters = [];
    for (const w of waiters) w(this.state);
  }

  request(type, payload) {
    if (!this.client) return Promise.reject(new InputError('no model is loaded'));
    return this.client.request(type, payload);
  }

  dispose() {
    this.cancelLoad();
    this.client?.terminate();
    this.client = null;
  }
}
