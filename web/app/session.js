// One solver session seen from the page: a worker (SolverClient) holding a Deformer for one method, the
// latest handles/targets/options to send, and the stepping loop. pump() is called every animation frame;
// it never waits: at most one step request is in flight, and rendering goes on while the worker iterates.
// After the handles stop moving it keeps stepping until the solver reports convergence (or the iteration cap).
import { InputError } from '../lib/errors.js';
import { SolverClient } from '../lib/worker/solver_client.js';
import { cancelledError, isCancelled, stoppedByFailure } from './errors.js';

const FRAME_BUDGET_MS = 25; // auto iterations per request: keep one request near a frame or two

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
    this.history = []; // { iteration, merit } for the plot
    this.last = null; // last IterationStats
    this.state = 'idle'; // idle | solving | converged | stopped | error
    this.stopReason = '';
    this.msPerIteration = 0;
    this.totalIterations = 0;
    this.sinceChange = 0;
    this.version = 0; // bumps on every handle / target / option change
    this.solvedVersion = -1;
    this.pending = { options: null, handles: null, targets: null };
    this.inFlight = false;
    this.hasHandles = false;
    this.waiters = [];
  }

  /**
   * Loads a model in a fresh worker; the current one keeps running (and its model stays on screen) until
   * the new one is bound. Rejects with the cancelled error (errors.js) when cancelLoad() is called or a newer
   * load starts.
   * @param {string} type 'loadExample' | 'loadFiles' | 'loadMeshes'
   */
  async load(type, payload, transfer = []) {
    this.cancelLoad();
    const client = new SolverClient({ onProgress: (f, phase) => this.onProgress?.(f, phase) });
    this.loading = client;
    try {
      const model = await client.request(type, payload, transfer);
      if (this.loading !== client) throw cancelledError();
      this.loading = null;
      this.client?.terminate();
      this.client = client;
      this.model = model;
      this.inFlight = false;
      this.hasHandles = false;
      this.pending = { options: { ...this.options, method: this.method }, handles: null, targets: null };
      this.#resetStats();
      this.state = 'idle';
      return model;
    } catch (error) {
      if (this.loading === client) this.loading = null;
      client.terminate();
      throw error;
    }
  }

  cancelLoad() {
    this.loading?.terminate();
    this.loading = null;
  }

  setMethod(method) {
    this.method = method;
    this.setOptions(this.options);
  }

  setOptions(options) {
    this.options = { ...options };
    this.pending.options = { ...options, method: this.method };
    this.#changed();
  }

  setHandles(groups, targets) {
    this.hasHandles = groups.length > 0 && groups.some((g) => g.length > 0);
    this.pending.handles = groups.map((g) => [...g]);
    this.pending.targets = targets;
    this.#changed();
  }

  setTargets(targets) {
    this.pending.targets = targets;
    this.#changed();
  }

  async reset() {
    this.#resetStats();
    if (!this.client) return;
    this.#changed();
    const frame = await this.client.request('reset');
    this.onFrame(frame, this);
  }

  #resetStats() {
    this.history = [];
    this.last = null;
    this.totalIterations = 0;
    this.sinceChange = 0;
    this.stopReason = '';
  }

  #changed() {
    this.version++;
    this.sinceChange = 0;
    this.state = this.hasHandles ? 'solving' : 'idle';
  }

  get iterationsForNextStep() {
    if (this.iterationsPerStep !== 'auto') return Math.max(1, this.iterationsPerStep | 0);
    if (!this.msPerIteration) return 1;
    return Math.max(1, Math.min(20, Math.floor(FRAME_BUDGET_MS / this.msPerIteration)));
  }

  /** Called every animation frame: sends what changed and asks for the next iterations when needed. */
  pump() {
    const client = this.client;
    if (!client || this.inFlight) return;
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
      client.request('setTargets', { targets: p.targets }).catch(fail);
      p.targets = null;
    }
    if (!this.hasHandles || this.state === 'error') return;
    const needed = this.version !== this.solvedVersion || this.state === 'solving';
    if (!needed) return;
    const version = this.version;
    const remaining = this.maxIterations - this.sinceChange;
    if (remaining <= 0) {
      this.state = 'stopped';
      this.stopReason = `not converged after ${this.maxIterations} iterations`;
      this.solvedVersion = version;
      this.#wake();
      return;
    }
    this.inFlight = true;
    client
      .request('step', { iterations: Math.min(this.iterationsForNextStep, remaining) })
      .then((frame) => {
        this.inFlight = false;
        if (client !== this.client) return;
        this.#accept(frame, version);
        this.onFrame(frame, this);
        // Ask for the next iterations right away: the solve rate must not be tied to the frame rate.
        this.pump();
      })
      .catch((error) => {
        this.inFlight = false;
        if (client === this.client && !isCancelled(error)) fail(error);
      });
  }

  #accept(frame, version) {
    const { iterations, converged, stopReason } = frame.result;
    let ms = 0;
    for (const it of iterations) {
      this.totalIterations++;
      this.history.push({ iteration: this.totalIterations, merit: it.merit, ms: it.ms });
      ms += it.ms;
      this.last = it;
    }
    if (this.history.length > 2000) this.history.splice(0, this.history.length - 2000);
    if (iterations.length) {
      const perIteration = ms / iterations.length;
      this.msPerIteration = this.msPerIteration ? 0.7 * this.msPerIteration + 0.3 * perIteration : perIteration;
    }
    this.sinceChange += iterations.length;
    this.stopReason = stopReason ?? '';
    if (version !== this.version) return; // the handles moved meanwhile: keep going
    if (converged) {
      this.state = 'converged';
      this.solvedVersion = version;
    } else if (stoppedByFailure(frame.result) || iterations.length === 0) {
      this.state = 'stopped';
      this.solvedVersion = version;
    } else {
      this.state = 'solving';
    }
    if (this.state !== 'solving') this.#wake();
  }

  #fail(error) {
    this.state = 'error';
    this.stopReason = error.message;
    this.solvedVersion = this.version;
    this.onError(error);
    this.#wake();
  }

  /** Resolves when the session is no longer solving (converged, stopped, idle or error). */
  settled() {
    if (!this.hasHandles || (this.state !== 'solving' && this.solvedVersion === this.version && !this.inFlight)) {
      return Promise.resolve(this.state);
    }
    return new Promise((resolve) => this.waiters.push(resolve));
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
