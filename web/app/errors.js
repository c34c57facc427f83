// The one place where the app tells kinds of errors and stop reasons apart, one question per function. It
// reads the library's typed errors and codes (web/lib/errors.js, the step results' `stop`), never message
// text.
import { CancelledError } from '../lib/errors.js';

/** The error a cancelled load or request rejects with (a terminated worker, a superseded load). */
export function cancelledError() {
  return new CancelledError();
}

/** True when the work was cancelled (Cancel button, a newer load, a disposed view): nothing to report. */
export function isCancelled(error) {
  return error instanceof CancelledError;
}

/** A lone mesh was loaded without a cage: the page offers "Generate cage". */
export function isMissingCage(error) {
  return error?.code === 'no_cage';
}

/** The mesh itself is unusable (open, non-manifold, ...): no cage can be generated until it is fixed. */
export function cannotGetCage(error) {
  return error?.code === 'invalid_mesh';
}

/** The work would need more memory than its budget (W, the dense exact step, the spectral basis' modes). */
export function isOverBudget(error) {
  return error?.code === 'memory_budget';
}

/** A step result that ended the solve without converging (a numerical failure): stop asking for steps. */
export function stoppedByFailure(result) {
  return result?.stop === 'numerical_failure';
}
