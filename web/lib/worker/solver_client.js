// Main-thread handle on one solver worker: promise-based requests over postMessage (protocol in
// solver_worker.js). Requests are answered in order. terminate() cancels everything in flight (the only
// way to stop a long synchronous bind) and rejects the pending promises with a 'cancelled' error.

let nextId = 1;

export class SolverClient {
  /** @param {{ onProgress?: (fraction: number, phase: string) => void }} [options] */
  constructor({ onProgress } = {}) {
    this.onProgress = onProgress ?? null;
    this.pending = new Map();
    this.terminated = false;
    this.worker = new Worker(new URL('./solver_worker.js', import.meta.url), { type: 'module' });
    this.worker.onmessage = (event) => this.#receive(event.data);
    // A worker script that fails to load (e.g. the wasm is missing) reports here, not via a reply.
    this.worker.onerror = (event) => {
      event.preventDefault?.();
      this.#failAll(new Error(`solver worker failed: ${event.message || 'could not start (is build/wasm built?)'}`));
    };
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
