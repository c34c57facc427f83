// @ts-check
// Main-thread handle on one solver worker: promise-based requests over postMessage (the messages:
// protocol.js). Requests are answered in order. A failed request rejects with the typed error the worker
// threw (errors.js: InputError, MeshError, SolverError, CancelledError, each with .code). terminate()
// cancels everything in flight (the only way to stop a long synchronous bind) and rejects the pending
// promises with a CancelledError.
//
// Threads: each worker holds its own wasm module and thread pool (the threaded build on an isolated page),
// so the workers of one page share its cores: each runs with an equal share (pageCores() / live workers,
// at least 1), adjusted whenever a worker starts or stops (protocol.js: init, setThreads). Compare mode
// (one worker per method) thus runs as many threads as cores in all, not that many per view. A client
// given `threads` keeps that count; setPageThreads(n) shares n threads instead of every core (the app's
// threads control). Each client keeps the SolverInfo its worker last reported (client.info).
import { CancelledError, InputError, SolverError, errorFromData } from '../errors.js';
import { pageCores } from '../load.js';
import { PROGRESS } from './protocol.js';
import { findDetached } from '../typed_arrays.js';
import { ModuleWorker } from './worker_start.js';

/** @typedef {import('./protocol.js').Request} Request */
/** @typedef {import('./protocol.js').Reply} Reply */

let nextId = 1;
const liveClients = new Set();
let pageThreadLimit = 0; // 0: every core of the page

function fairShare() {
  return Math.max(1, Math.floor(pageThreads() / Math.max(1, liveClients.size)));
}

/** The threads the page's solver workers share: setPageThreads' count, else every core (pageCores()). */
export function pageThreads() {
  return pageThreadLimit > 0 ? Math.min(pageThreadLimit, pageCores()) : pageCores();
}

/**
 * Shares `threads` threads (0: every core) between the page's solver workers, at least one each, and
 * rebalances the live ones now. A worker's pool holds pageCores() threads, so no count above that runs.
 * @param {number} threads
 */
export function setPageThreads(threads) {
  if (!Number.isInteger(threads) || threads < 0 || threads > 1024) {
    throw new InputError(`setPageThreads: threads must be an integer from 0 (every core) to 1024 (got ${threads})`);
  }
  pageThreadLimit = threads;
  rebalance();
}

function rebalance() {
  for (const client of liveClients) {
    if (client.fixedThreads) continue;
    // A worker that fails to load reports it to its own requests.
    client.request('setThreads', { threads: fairShare() }).catch(() => {});
  }
}

export class SolverClient {
  /**
   * @param {{ onProgress?: (fraction: number, phase: string) => void, threads?: number }} [options]
   *   threads: a fixed thread count for this worker (default: its share of the page's cores)
   */
  constructor({ onProgress, threads } = {}) {
    this.onProgress = onProgress ?? null;
    /** @type {Map<number, { resolve: (value: any) => void, reject: (error: Error) => void, type: string }>} */
    this.pending = new Map();
    this.terminated = false;
    this.fixedThreads = threads !== undefined && threads > 0 ? threads : 0;
    /** @type {import('./protocol.js').SolverInfo|null} the build and thread count the worker last reported */
    this.info = null;
    // Through a bootstrap blob (worker_start.js: it runs under any page's isolation, wherever the build lies).
    // Written as `new Worker(new URL(...))` so that Vite bundles the worker and puts its chunk's URL here.
    // ModuleWorker is a function that returns the Worker it made when called with `new`.
    const Worker = /** @type {new (url: URL, options: WorkerOptions) => Worker} */ (/** @type {unknown} */ (ModuleWorker));
    this.worker = new Worker(new URL('./solver_worker.js', import.meta.url), { type: 'module' });
    this.worker.onmessage = (event) => this.#receive(event.data);
    // A worker script that fails to load (e.g. the wasm is missing) reports here, not via a reply.
    this.worker.onerror = (event) => {
      event.preventDefault?.();
      this.#failAll(new SolverError(`solver worker failed: ${event.message || 'could not start (is build/wasm built?)'}`));
    };
    liveClients.add(this);
    // The first request: the module loads with this many threads (its pool holds pageCores()). The build
    // and count in effect reach the page in every loaded model (protocol.js: Model.solver).
    this.request('init', { threads: this.fixedThreads || fairShare() }).catch(() => {});
    rebalance();
  }

  /**
   * @param {Request['type']} type request name (protocol.js)
   * @param {object} [payload] the request's fields besides its type
   * @param {Transferable[]} [transfer] buffers handed over without a copy
   * @returns {Promise<any>} the reply's result (protocol.js says which, per type)
   */
  request(type, payload = {}, transfer = []) {
    if (this.terminated) return Promise.reject(new CancelledError());
    const id = nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject, type });
      try {
        this.worker.postMessage({ id, type, ...payload }, transfer);
      } catch (error) {
        // A detached array cannot be posted (a DataCloneError): name it as the caller's mistake.
        this.pending.delete(id);
        const at = findDetached(payload);
        reject(at ? new InputError(`${type}: ${at} is a detached typed array (its buffer was transferred); pass a copy`) : error);
      }
    });
  }

  terminate() {
    if (this.terminated) return;
    this.terminated = true;
    this.worker.terminate();
    liveClients.delete(this);
    rebalance();
    this.#failAll(new CancelledError());
  }

  /** @param {Reply | import('./protocol.js').Progress} message */
  #receive(message) {
    if ('type' in message && message.type === PROGRESS) {
      this.onProgress?.(message.fraction, message.phase);
      return;
    }
    const reply = /** @type {Reply} */ (message);
    const entry = this.pending.get(reply.id);
    if (!entry) return;
    this.pending.delete(reply.id);
    if (reply.ok) this.#noteInfo(entry.type, reply.result);
    if (reply.ok) entry.resolve(reply.result);
    else entry.reject(errorFromData(reply.error));
  }

  /**
   * init and setThreads answer with a SolverInfo, a loaded Model carries one.
   * @param {string} type the request's type
   * @param {any} result its reply's result
   */
  #noteInfo(type, result) {
    if (type === 'init' || type === 'setThreads') this.info = result;
    else if (result?.solver?.build) this.info = result.solver;
  }

  /** @param {Error} error */
  #failAll(error) {
    for (const entry of this.pending.values()) entry.reject(error);
    this.pending.clear();
  }
}
