// One solver session seen from the page: a worker (SolverClient) holding a Deformer for one method, the
// latest handles/targets/options to send, and the stepping loop. pump() is called every animation frame;
// it never waits: at most one step request is in flight, and rendering goes on while the worker iterates.
// After the handles stop moving it keeps stepping until the solver reports convergence (or the iteration cap).
// Where the solve stands is one SessionState (session_state.js: its phases and their transitions as one table);
// the session owns its IntegrationPolicy and SolveRecord, and the app changes it only through its methods.
import { InputError } from '../lib/errors.js';
import { isCancelled, stoppedByFailure } from './errors.js';
import { IntegrationPolicy } from './integration_policy.js';
import { prepareLoad } from './loading/prepared_load.js';
import { PendingChanges } from './pending_changes.js';
import { SolveRecord } from './solve_record.js';
import { SessionState } from './session_state.js';
import { StepPacing } from './step_pacing.js';
import { prepareWorker } from './worker_preparation.js';

export class Session {
  #record; // merit series, time per iteration, progress (solve_record.js)
  #state = new SessionState(); // the phase, step-through, the step requests out (session_state.js)
  #integration = new IntegrationPolicy(); // reduced while the handles move (integration_policy.js)
  #pacing = new StepPacing(); // iterations per request, requests out at once, compare mode's holds
  #maxIterations = 100;
  #resultWarnings = []; // the settled result's (Deformer.resultWarnings): folds, a crossed cage

  /** @param {{ method: string, onFrame: (frame) => void, onError: (error: Error) => void,
   *            onProgress?: (fraction: number, phase: string) => void }} options */
  constructor({ method, onFrame, onError, onProgress }) {
    this.method = method;
    this.onFrame = onFrame;
    this.onError = onError;
    this.onProgress = onProgress;
    this.client = null;
    this.loading = null; // the client binding a new model (terminated to cancel)
    this.model = null;
    this.options = {};
    this.#record = new SolveRecord(method);
    this.#clearStats();
    this.version = 0; // bumps on every handle / target / option change: older answers only add their iterations
    this.pending = new PendingChanges(); // sent before the next request
    this.queuedIterations = 0; // iterations of the step requests out
    this.hasHandles = false;
    this.waiters = [];
    this.idleWaiters = [];
  }

  /**
   * Loads a model in a fresh worker (loading/prepared_load.js); the current one keeps running (and its model stays on
   * screen) until the new one is bound. Rejects with the cancelled error (errors.js) when cancelLoad() is called or a
   * newer load starts, and with the error of `options.check` (run on the new model in its worker before anything
   * changes here: a scene whose handles do not fit the mesh it names), the current model staying.
   * @param {string} type 'loadExample' | 'loadFiles' | 'loadMeshes'
   * @param {object} payload
   * @param {Parameters<typeof prepareLoad>[3]} [options]
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
    this.#state.dropRequests(); // the old worker's: their answers never come
    this.queuedIterations = 0;
    this.hasHandles = false;
    this.pending = new PendingChanges({ ...this.options, method: this.method });
    this.#integration.newModel();
    // What a drag and its settle would wait for, made now; a worker replaced since (a newer model) is not this one's.
    prepareWorker(client, { method: this.method, options: this.options, reduces: this.#integration.reduces(this.method, model),
      onFit: (fit) => client === this.client && this.#integration.checkFit(fit),
      onError: (error) => client === this.client && !isCancelled(error) && this.#fail(error) });
    this.#record.newModel();
    this.#clearStats();
    this.#send('load');
    return model;
  }

  cancelLoad() {
    this.loading?.terminate();
    this.loading = null;
  }

  /** Another method (its solve starts from rest in the worker): a fresh plot series and timings. */
  setMethod(method) {
    this.method = method;
    this.#record.setMethod(method);
    this.#clearStats();
    this.setOptions(this.options);
  }

  setOptions(options) {
    this.options = { ...options };
    this.pending.options = { ...options, method: this.method };
    this.#integration.forget();
    this.#record.expectSetUp(); // the position weight or the method may re-factor
    this.#changed();
  }

  /**
   * The app's solver settings for this view's method (settings.js): the worker's options, the iteration cap since a
   * change, iterations per request ('auto' or a count) and the integration while dragging ('auto' | 'full' | 'reduced').
   */
  applySettings({ options, maxIterations, iterationsPerStep, dragIntegration }) {
    this.#maxIterations = maxIterations;
    this.#pacing.iterationsPerStep = iterationsPerStep;
    this.#integration.whileMoving = dragIntegration;
    this.setOptions(options);
  }

  /** Compare mode: the views share the cores, and a slow one waits while the handles move (step_pacing.js). */
  shareCores(shared) {
    this.#pacing.shared = shared;
  }

  setHandles(groups, targets, lines = null) {
    this.#integration.moved();
    this.hasHandles = groups.length > 0 && groups.some((g) => g.length > 0);
    this.pending.handles = groups.map((g) => [...g]);
    this.pending.targets = { targets, lines };
    this.#record.expectSetUp();
    this.#changed();
  }

  /** Targets, with each group's handle line (handle_lines.js; null: point targets). */
  setTargets(targets, lines = null) {
    this.#integration.moved();
    this.pending.targets = { targets, lines };
    this.#changed();
  }

  /** The drag ended (a pointer release): the targets rest now, and the settled integration takes over at once. */
  released() {
    this.#integration.released();
  }

  /**
   * Tells the worker when the integration changes; a switch back to full at rest solves on to the full answer (so
   * does any change while a solve that ended on the drag's samples waits for it: session_state.js).
   */
  #chooseIntegration() {
    const change = this.#integration.next(this.method, this.model, this.#settledIntegration);
    if (!change) return;
    this.pending.options = { ...this.options, method: this.method, integration: change.integration };
    if ((change.switched || this.#state.onSamples) && this.hasHandles) this.#changed();
  }

  /** The integration the settled answer uses (the solver option). */
  get #settledIntegration() {
    return this.options.integration ?? 'full';
  }

  /** The volume parts changed in the worker (positions kept): solve again to restore them. */
  partsChanged() {
    this.#changed();
  }

  /** Back to the rest pose in the worker, then the same targets are solved again (a fresh series). */
  async resolveFromRest() {
    this.#record.restart();
    this.#clearStats();
    if (!this.client) return;
    this.#changed();
    const frame = await this.client.request('reset');
    this.onFrame(frame, this);
  }

  #clearStats() {
    this.last = null; // last IterationStats
    this.stopReason = '';
    this.#resultWarnings = [];
  }

  #changed() {
    this.version++;
    this.#record.changed();
    this.#resultWarnings = [];
    this.#send(this.hasHandles ? 'change' : 'clear');
  }

  /** Applies a state event (session_state.js), and resolves the waiters of settled() once the session has settled. */
  #send(event) {
    const changed = this.#state.send(event);
    if (this.#state.settled) this.#wake();
    return changed;
  }

  // A solve settled: its record ends, and what its result should be warned about is asked (once per version).
  #settled(version, client = this.client) {
    this.#record.ended();
    const keep = (w) => { if (client === this.client && version === this.version) this.#resultWarnings = w; };
    client?.request('resultWarnings').then(keep, () => {});
  }

  /** 'idle' | 'solving' | 'converged' | 'stopped' | 'error' (the stats' word: session_state.js). */
  get state() {
    return this.#state.reported;
  }

  /** The same, or 'paused' for a step-through solve waiting for its next step. */
  get status() {
    return this.#state.shown;
  }

  /** [{ code, message }]: a reduced rule that failed its test, then the settled result's (folds, a crossed cage). */
  get warnings() {
    const notice = this.#integration.notice;
    return [...(notice ? [notice] : []), ...this.#resultWarnings];
  }

  /** The plot's series and the timings, to read (the session alone changes them). */
  get record() {
    return this.#record;
  }

  /** The current series' merits (the plot). */
  get history() {
    return this.#record.points;
  }

  /** Iterations in the current series (since the load, the method switch or the last re-solve). */
  get totalIterations() {
    return this.#record.iterations;
  }

  /** Median ms of the last iterations without one-off work (0 before the first). */
  get msPerIteration() { return this.#record.msPerIteration; }

  /** The current solve: iterations since the last change, elapsed and remaining time (SolveRecord.progress). */
  get progress() {
    return this.#record.progress(this.#maxIterations, this.#state.inFlight > 0);
  }

  get iterationsForNextStep() {
    return this.#pacing.size(this.#record.requestMs);
  }

  /** Step-through: while paused only stepOnce() and arapHalfStep() iterate; edits still reach the worker. */
  setPaused(paused) {
    this.#state.setPaused(paused);
    if (this.#state.settled) this.#wake(); // a solve() waiting on a paused view resolves (the next pump resumes it)
  }

  /** Resolves when no step request is in flight (a pause has taken effect). */
  idle() {
    if (this.#state.inFlight === 0) return Promise.resolve();
    return new Promise((resolve) => this.idleWaiters.push(resolve));
  }

  /**
   * One iteration now (step-through): what changed is sent first. Resolves with the worker's StepResult, or
   * null without a model or handles. A converged solve with nothing changed since is not stepped (an iteration would
   * move nothing and only count up): its answer has no iterations, `nothingToDo` and the stop null.
   */
  async stepOnce() {
    const client = this.client;
    if (!client || !this.hasHandles) return null;
    if (this.#state.phase === 'converged') return { iterations: [], converged: true, stop: null, stopReason: this.stopReason, nothingToDo: true };
    this.#chooseIntegration();
    this.#sendPending(client);
    const version = this.version;
    this.#state.requestSent();
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
      if (client === this.client) this.#answered(0); // a replaced worker's requests were dropped with it
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
    this.#state.requestAnswered();
    this.queuedIterations -= iterations;
    if (this.#state.inFlight > 0) return;
    if (this.#state.settled) this.#wake();
    for (const w of this.idleWaiters.splice(0)) w();
  }

  /** Sends the pending options, handles and targets. */
  #sendPending(client) {
    const onRest = (frame) => client === this.client && this.onFrame(frame, this);
    this.pending.send(client, { hasHandles: this.hasHandles, onRest, fail: (error) => this.#fail(error) });
  }

  /** Called every animation frame: sends what changed and asks for the next iterations when needed. */
  pump() {
    const client = this.client;
    if (!client || this.#state.inFlight >= this.#pacing.depth(this.#record.requestMs)) return;
    const fail = (error) => this.#fail(error);
    this.#chooseIntegration();
    this.#sendPending(client);
    if (!this.#state.wantsSteps || this.#pacing.holding(this.#record.requestMs, this.#integration.movedAt)) return;
    const version = this.version;
    const remaining = this.#maxIterations - this.#record.sinceChange - this.queuedIterations;
    if (remaining <= 0) {
      if (this.#state.inFlight) return; // the cap is reached once those are answered
      this.stopReason = `not converged after ${this.#maxIterations} iterations`;
      this.#record.ended();
      this.#send(this.#onSamples('stopped'));
      return;
    }
    const k = Math.min(this.iterationsForNextStep, remaining);
    this.#state.requestSent();
    this.queuedIterations += k;
    this.#pacing.sent();
    let answeredOnce = false; // onFrame may throw after answered(): the catch below must not count it twice
    const answered = () => {
      if (!answeredOnce) this.#answered(k);
      answeredOnce = true;
    };
    client
      .request('step', { iterations: k })
      .then((frame) => {
        if (client !== this.client) return;
        answered();
        this.#accept(frame, version);
        this.onFrame(frame, this);
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
    const { iterations, stopReason } = frame.result;
    this.#record.add(iterations);
    if (iterations.length) this.last = iterations.at(-1);
    this.stopReason = stopReason ?? '';
    if (version !== this.version) return; // the handles moved meanwhile: keep going
    const end = this.#ending(frame.result);
    // Answers queued behind the one that ended the solve change nothing (the table ignores them).
    if (end && this.#send(end)) this.#settled(version);
  }

  /** The event an answer for the current change brings (session_state.js), or null when the solve goes on. */
  #ending(result) {
    // A solve that converged on samples while the handles moved goes on with the full integration once they rest.
    if (result.converged) return this.#onSamples('converged');
    return stoppedByFailure(result) || result.iterations.length === 0 ? this.#onSamples('stopped') : null;
  }

  /** The end of a solve (`end`: 'converged' | 'stopped'), provisional when it ran on the drag's samples. */
  #onSamples(end) {
    return this.#integration.refines(this.#settledIntegration) ? `${end}OnSamples` : end;
  }

  #fail(error) {
    this.#record.ended();
    this.stopReason = error.message;
    this.#send('failed');
    this.onError(error);
  }

  /** Resolves when the session is no longer solving (converged, stopped, idle or error; paused: no step out). */
  settled() {
    if (this.#state.settled) return Promise.resolve(this.state);
    return new Promise((resolve) => this.waiters.push(resolve));
  }

  #wake() {
    for (const w of this.waiters.splice(0)) w(this.state);
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
