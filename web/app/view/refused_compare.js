// What setCompare does when a new compare view cannot bind (e.g. "compare coordinates" with a harmonic grid the
// worker refuses): the views go back to what they were, so the box unticks and no view is left without a mesh
// (a tester saw an empty second view, its gizmo floating, while solve() still resolved "converged"), and the
// banner says why. A cancelled binding (a later request) is the later request's to show.
import { isCancelled } from '../errors.js';

/**
 * @param {Error} error the binding's
 * @param {string[]|false} previous the views' keys before (false: no compare mode)
 * @param {(compare: string[]|false) => Promise<void>} setCompare the app's
 * @param {{ show(text: string): void }} banner
 */
export async function refuseCompare(error, previous, setCompare, banner) {
  if (isCancelled(error)) throw error;
  await setCompare(previous).catch(() => {});
  banner.show(`Compare views not shown: ${error.message}`);
  throw error;
}
