// Runs web/lib/worker/solver_worker.js in a Node worker thread, as a browser runs it in a Web Worker: it
// gets `self` with postMessage/onmessage (bridged to worker_threads), and the module is loaded from its
// bytes first (Node's fetch cannot load it), so the worker's own loadSolver() finds it ready.
import { readFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { parentPort } from 'node:worker_threads';
import { loadSolver } from '../../../web/lib/load.js';
import { wasmDir } from '../../../web/lib/node.js';

await loadSolver({ wasmBinary: readFileSync(resolve(wasmDir(), 'subspace_deform.wasm')) });
globalThis.self = {
  postMessage: (message, transfer) => parentPort.postMessage(message, transfer),
  onmessage: null,
};
parentPort.on('message', (data) => globalThis.self.onmessage?.({ data }));
await import('../../../web/lib/worker/solver_worker.js');
parentPort.postMessage({ type: 'host-ready' });
