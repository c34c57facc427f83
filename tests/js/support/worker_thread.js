// The solver worker in a Node thread (worker_host.mjs) and the page's side of its protocol: one request, answered
// by one reply (the client's job in the browser). Progress messages are collected in `progress`.
import { Worker } from 'node:worker_threads';

/** @returns {Promise<{ worker: Worker, request: (type: string, payload?: object) => Promise<any>, progress: any[], pending: Map<any, Function> }>} */
export async function startWorkerThread() {
  const worker = new Worker(new URL('./worker_host.mjs', import.meta.url));
  const pending = new Map();
  const progress = [];
  let nextId = 1;
  await new Promise((resolve, reject) => {
    worker.on('error', reject);
    worker.on('message', (message) => {
      if (message.type === 'host-ready') resolve();
      else if (message.type === 'progress') progress.push(message);
      else pending.get(message.id)?.(message);
    });
  });
  const request = (type, payload = {}) => new Promise((resolve) => {
    const id = nextId++;
    pending.set(id, resolve);
    worker.postMessage({ id, type, ...payload });
  });
  return { worker, request, progress, pending };
}
