// @ts-check
// subspace-deform, the browser entry (package.json "exports", condition "default"): the library plus the
// browser loader and the solver worker's client. A page or course script:
//
//   import { loadSolver, Deformer, loadExample } from 'subspace-deform';
//   const solver = await loadSolver();
//   const { mesh, cage } = await loadExample(solver, 'bar');
//   const d = Deformer.create(solver, mesh, cage);
//
// Or off the main thread: new SolverClient() and the requests of worker/protocol.js.

/** @typedef {import('./worker/protocol.js').Request} WorkerRequest */
/** @typedef {import('./worker/protocol.js').Reply} WorkerReply */
/** @typedef {import('./worker/protocol.js').Model} WorkerModel */
/** @typedef {import('./worker/protocol.js').Frame} WorkerFrame */

export * from './library.js';
export { loadSolver } from './load.js';
export { SolverClient, pageThreads, setPageThreads } from './worker/solver_client.js';
