// Where one view's solve stands (session.js), as a state machine: its phase changes only through PHASE_TABLE,
// the one place that says what each event does in each phase (tests/js/session_state.test.js reads it row by row).
//
//   idle ──change──> solving ──converged──> converged
//                      │ │ │ └──stopped──> stopped      (a numerical failure, no iterations left, the iteration cap)
//                      │ └─┴──convergedOnSamples / stoppedOnSamples──> convergedOnSamples / stoppedOnSamples
//                      │      (the end of a solve on the drag's reduced integration: provisional; once the targets
//                      │      rest, the switch to the settled integration is a change, which solves on)
//   from every phase: change ──> solving, load or clear ──> idle, failed ──> failed
//
// Two things run beside the phase: step-through (`paused`: only single steps iterate) and the step requests the
// worker has not answered yet (`inFlight`). The session settles when no request is out and either it is paused or
// its phase needs no more iterations.

/** What the solve is doing. */
export const PHASES = Object.freeze(['idle', 'solving', 'converged', 'stopped', 'convergedOnSamples', 'stoppedOnSamples',
  'failed']);

/**
 * What can happen to it:
 * - load: a new model is bound (its rest pose, no handles yet)
 * - change: handles, targets, options or the integration changed, and there are handles: solve (again)
 * - clear: a change left no handles: the rest pose is the answer
 * - converged: an answer for the current change converged
 * - stopped: it stopped without converging (a numerical failure, no iterations), or the iteration cap was reached
 * - convergedOnSamples, stoppedOnSamples: the same with the drag's integration (reduced samples, integration_policy.js)
 * - failed: a request failed (the session's error)
 */
export const EVENTS = Object.freeze(['load', 'change', 'clear', 'converged', 'stopped', 'convergedOnSamples',
  'stoppedOnSamples', 'failed']);

// Answers that end a solve count only while it is solving: in any other phase they were queued behind the answer
// that ended it, or belong to a change already replaced; they are ignored ('-'). Nothing else is ever ignored.
/** The next phase for each phase and event, in EVENTS' order ('-': the event is ignored in that phase). */
export const PHASE_TABLE = Object.freeze({
  //                   load    change     clear   converged    stopped    convergedOnSamples    stoppedOnSamples    failed
  idle:               ['idle', 'solving', 'idle', '-',         '-',       '-',                  '-',                'failed'],
  solving:            ['idle', 'solving', 'idle', 'converged', 'stopped', 'convergedOnSamples', 'stoppedOnSamples', 'failed'],
  converged:          ['idle', 'solving', 'idle', '-',         '-',       '-',                  '-',                'failed'],
  stopped:            ['idle', 'solving', 'idle', '-',         '-',       '-',                  '-',                'failed'],
  convergedOnSamples: ['idle', 'solving', 'idle', '-',         '-',       '-',                  '-',                'failed'],
  stoppedOnSamples:   ['idle', 'solving', 'idle', '-',         '-',       '-',                  '-',                'failed'],
  failed:             ['idle', 'solving', 'idle', '-',         '-',       '-',                  '-',                'failed'],
});

/** Phases that need no more iterations (the session settles there once no request is out). */
const AT_REST = new Set(['idle', 'converged', 'stopped', 'failed']);

/** The word the stats and the scripting API use for each phase (docs/embed.md). */
const REPORTED = Object.freeze({
  idle: 'idle', solving: 'solving', converged: 'converged', stopped: 'stopped',
  convergedOnSamples: 'converged', stoppedOnSamples: 'stopped', failed: 'error',
});

/**
 * The phase after `event` in `phase` (the same phase where the table ignores it).
 * @throws {TypeError} for a phase or an event that does not exist (a programming error, never ignored)
 */
export function nextPhase(phase, event) {
  const row = PHASE_TABLE[phase];
  const column = EVENTS.indexOf(event);
  if (!row) throw new TypeError(`session: no phase '${phase}'`);
  if (column < 0) throw new TypeError(`session: no event '${event}'`);
  const next = row[column];
  return next === '-' ? phase : next;
}

export class SessionState {
  constructor() {
    this.phase = 'idle';
    this.paused = false; // step-through (step_through.js): changes are sent, iterations only by single steps
    this.inFlight = 0; // step requests sent and not answered
  }

  /** Applies `event` (EVENTS); returns whether the phase changed. */
  send(event) {
    const before = this.phase;
    this.phase = nextPhase(before, event);
    return this.phase !== before;
  }

  setPaused(paused) {
    this.paused = !!paused;
  }

  requestSent() {
    this.inFlight++;
  }

  requestAnswered() {
    this.inFlight--;
  }

  /** The worker that had them is gone: their answers never come. */
  dropRequests() {
    this.inFlight = 0;
  }

  /** Whether the solve ended on the drag's samples and waits for the targets to rest (the switch solves on). */
  get onSamples() {
    return this.phase === 'convergedOnSamples' || this.phase === 'stoppedOnSamples';
  }

  /** Whether the pump should ask for iterations (step-through asks only for single steps). */
  get wantsSteps() {
    return this.phase === 'solving' && !this.paused;
  }

  /** Nothing more happens until the next change (or, paused, the next single step). */
  get settled() {
    if (this.paused) return this.inFlight === 0;
    // Without handles the rest pose is the answer: a request still out belongs to an earlier change (ignored).
    return this.phase === 'idle' || (AT_REST.has(this.phase) && this.inFlight === 0);
  }

  /** The state as the stats report it: 'idle' | 'solving' | 'converged' | 'stopped' | 'error'. */
  get reported() {
    return REPORTED[this.phase];
  }

  /** The same, with 'paused' for a step-through solve that waits for its next step. */
  get shown() {
    return this.paused && this.phase === 'solving' ? 'paused' : this.reported;
  }
}
