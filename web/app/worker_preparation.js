// What a session asks of a freshly bound worker before any step (session.js adopt), so that a drag and its settle
// do not wait for it: the reduced integration's fit (method.md section 17.2; a rule that fails its test keeps the
// drag on full integration) and the factor preconditioner's pose-free parts (section 11.1), which only the subspace
// method's fast steps buy. The session's options go first: the worker starts with the defaults, and another
// energy weighting would remake both.

/**
 * @param {import('../lib/worker/solver_client.js').SolverClient} client the new worker
 * @param {{ method: string, options: object, reduces: boolean, onFit: (fit: object) => void,
 *           onError: (error: Error) => void }} session what the session holds; reduces: the drag samples
 */
export function prepareWorker(client, { method, options, reduces, onFit, onError }) {
  const factor = method === 'subspace' && options.preconditioner !== 'constant';
  if (!reduces && !factor) return;
  client.request('setOptions', { options: { ...options, method } }).catch(onError);
  if (reduces) client.request('prepareReduced').then(onFit, onError);
  if (factor) client.request('prepareFactor').catch(onError);
}
