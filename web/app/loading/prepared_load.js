// Loading a model in two halves, so that several views take a new model together or not at all: prepareLoad
// binds and checks it in a fresh worker of a Session, changing nothing there yet; commit() then makes it the
// session's model. loadEveryView prepares every view first and commits only when all have it, so a failure or a
// Cancel in the last view never leaves the first on a model the app does not hold.
import { SolverClient } from '../../lib/worker/solver_client.js';
import { cancelledError } from '../errors.js';

/**
 * Binds a model in a fresh worker of `session` (its loading client until then; cancelLoad() or a newer load
 * terminates it) and runs `check` on it there.
 * @param {import('../session.js').Session} session
 * @param {string} type 'loadExample' | 'loadFiles' | 'loadMeshes'
 * @param {object} payload
 * @param {{ transfer?: Transferable[], check?: (model: object, client: SolverClient) => Promise<void>|void }} [options]
 * @returns {Promise<{ model: object, current: () => boolean, commit: () => object, discard: () => void }>}
 *   current: still the session's pending load; commit: makes it the session's model (returns it); discard: drops it
 */
export async function prepareLoad(session, type, payload, { transfer = [], check } = {}) {
  session.cancelLoad();
  const client = new SolverClient({ onProgress: (f, phase) => session.onProgress?.(f, phase) });
  session.loading = client;
  const current = () => session.loading === client;
  const discard = () => {
    if (session.client === client) return; // committed: it is the session's worker now
    if (current()) session.loading = null;
    client.terminate();
  };
  try {
    const model = await client.request(type, payload, transfer);
    if (!current()) throw cancelledError();
    if (check) await check(model, client);
    if (!current()) throw cancelledError();
    const commit = () => {
      if (!current()) throw cancelledError();
      return session.adopt(client, model);
    };
    return { model, current, commit, discard };
  } catch (error) {
    discard();
    throw error;
  }
}

/**
 * Binds a model in the first view (type, payload, check), then in every other view (`others(view, model)`: their
 * loadMeshes payload), and only then makes it every view's model. Resolves with the first view's model.
 */
export async function loadEveryView(views, type, payload, { check, others }) {
  const [first, ...rest] = views;
  const prepared = [];
  try {
    prepared.push(await prepareLoad(first.session, type, payload, { check }));
    const { model } = prepared[0];
    for (const view of rest) prepared.push(await prepareLoad(view.session, 'loadMeshes', others(view, model)));
    if (!prepared.every((p) => p.current())) throw cancelledError();
    for (const p of prepared) p.commit();
    return model;
  } catch (error) {
    for (const p of prepared) p.discard();
    throw error;
  }
}
