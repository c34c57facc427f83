// The one place where the app tells kinds of errors and stop reasons apart. Each question is one function,
// so that moving from message text to the library's typed errors and codes changes one line each.
// (Until then the worker sends plain messages, and these read them.)

/** The error a cancelled load or request rejects with (a terminated worker, a superseded load). */
export function cancelledError() {
  return new Error('cancelled');
}

/** True when the work was cancelled (Cancel button, a newer load, a disposed view): nothing to report. */
export function isCancelled(error) {
  return error?.message === 'cancelled';
}

/** A lone mesh was loaded without a cage: the page offers "Generate cage". */
export function isMissingCage(error) {
  return /has no cage/.test(error?.message ?? '');
}

/** The mesh itself is unusable (open, non-manifold, ...): no cage can be generated until it is fixed. */
export function cannotGetCage(error) {
  return /cannot get a/.test(error?.message ?? '');
}

/** A step result that ended the solve without converging (a numerical failure): stop asking for steps. */
export function stoppedByFailure(result) {
  return /fail|nan|stall/i.test(result?.stopReason ?? '');
}
