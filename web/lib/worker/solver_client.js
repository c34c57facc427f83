// Main-thread handle on one solver worker: promise-based requests over postMessage (protocol in
// solver_worker.js). Requests are answered in order. terminate() cancels everything in flight (the only
// way to stop a long synchronous bind) and rejects the pending promises with a 'cancelled' error.
//
// Threads: each worker holds its own wasm module and thread pool (the threaded build on an isolated page),
// so the workers of one page share its cores: each runs with an equal share (pageCores() / live workers,
// at least 1), adjusted whenever a worker starts or stops. Compare mode (one worker per method) thus runs
// as many threads as cores in all, not that many per view. A client given `threads` keeps that count.
import { pageCores } from '../load.js';

let nextId = 1;
const liveClients = new Set();

function fairShare() {
  return Math.max(1, Math.floor(pageCores() / Math.max(1, liveClients.size)));
}

function rebalance() {
  for (const client of liveClients) {
    if (client.fixedThreads) continue;
    client.request('setThreads', { threads: fairShare() }).then((info) => {
      client.solverInfo = info;
    }, () => {}); // a worker that fails to load reports it to its own requests
  }
}

export class SolverClient {
  /**
   * @param {{ onProgress?: (fraction: number, phase: string) => void, threads?: number }} [options]
   *   threads: a fixed thread count for this worker (default: its share of the page's cores)
   */
  constructor({ onProgress, threads } = {}) {
    this.onProgress = onProgress ?? null;
    this.pending = new Map();
    this.terminated = false;
    this.fixedThreads = threads > 0 ? threads : 0;
    /** { build, threads, buildNote? } once the worker has loaded the module */
    this.solverInfo = null;
    this.worker = new Worker(new URL('./solver_worker.js', import.meta.url), { type: 'module' });
    this.worker.onmessage = (event) => this.#receive(event.data);
    // A worker script that fails to load (e.g. the wasm is missing) reports here, not via a reply.
    this.worker.onerror = (event) => {
      event.preventDefault?.();
      this.#failAll(new Error(`solver worker failed: ${event.message || 'could not start (is build/wasm built?)'}`));
    };
    liveClients.add(this);
    // The first request: the module loads with this many threads (its pool holds pageCores()).
    this.request('init', { threads: this.fixedThreads || fairShare() }).then((info) => {
      this.solverInfo = info;
    }, () => {});
    rebalance();
  }

  /**
   * @param {string} type request name (see solver_worker.js)
   * @param {object} [payload]
   * @param {Transferable[]} [transfer] buffers handed over without a copy
   * @returns {Promise<any>}
   */
  request(type, payload = {}, transfer = []) {
    if (this.terminated) return Promise.reject(new Error('cancelled'));
    const id = nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject, type });
      this.worker.postMessage({ id, type, ...payload }, transfer);
    });
  }

  get busy() {
    return this.pending.size > 0;
  }

  terminate() {
    if (this.terminated) return;
    this.terminated = true;
    this.worker.terminate();
    liveClients.delete(this);
    rebalance();
    this.#failAll(new Error('cancelled'));
  }

  #receive(message) {
    if (message.type === 'progress') {
      this.onProgress?.(message.fraction, message.phase);
      return;
    }
    const entry = this.pending.get(message.id);
    if (!entry) return;
    this.pending.delete(message.id);
    if (message.ok) entry.resolve(message.result);
    else entry.reject(new Error(message.error));
  }

  #failAll(error) {
    for (const entry of this.pending.values()) entry.reject(error);
    this.pending.clear();
  }
}
