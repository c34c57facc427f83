// How a session (session.js) paces its step requests: how many iterations one asks for, how many may be out at
// once, and when a slow view in compare mode waits while the handles move. Each answer is the worker's time per
// iteration (SolveRecord.requestMs, smoothed).

const FRAME_BUDGET_MS = 25; // auto iterations per request: keep one request near a frame or two
// A worker answers a step, then waits for the page to ask for the next one; the page reads the answer only
// between its frames. In compare mode on a software renderer a frame draws three views and takes 60-90 ms,
// so a view whose request takes 30-50 ms sat idle for half of each cycle and updated once per frame at
// best (scripts/bench/compare.mjs, docs/app.md). Requests shorter than this get a second one queued behind them, so
// the worker goes on while the page draws; longer ones gain little from it and would waste a long
// iteration after convergence.
const PIPELINE_MS = 100;
// Compare mode shares the cores (and, with a software renderer, the drawing) between the views. A method
// whose request takes longer than SLOW_REQUEST_MS cannot follow a drag anyway: its answer is stale when it
// arrives, and while the handles move it only takes CPU from the others. Such a view waits while the targets
// keep changing (moved in the last HOLD_MS, and not released since), taking one request at least every
// MAX_HOLD_MS so it still shows progress, and solves at full speed once the handles stop or the drag is
// released (measurements: docs/app.md).
const SLOW_REQUEST_MS = 250;
const HOLD_MS = 200;
const MAX_HOLD_MS = 1000;

export class StepPacing {
  constructor() {
    this.iterationsPerStep = 'auto'; // or a count (the setting iterationsPerFrame)
    this.shared = false; // compare mode: the views share the cores
    this.lastRequestAt = 0;
  }

  /** Iterations for the next request at `requestMs` per iteration (0: not measured yet). */
  size(requestMs) {
    if (this.iterationsPerStep !== 'auto') return Math.max(1, this.iterationsPerStep | 0);
    if (!requestMs) return 1;
    return Math.max(1, Math.min(20, Math.floor(FRAME_BUDGET_MS / requestMs)));
  }

  /** Step requests kept in flight: two when a request is short (PIPELINE_MS), else one. */
  depth(requestMs) {
    const ms = requestMs * this.size(requestMs);
    return ms > 0 && ms < PIPELINE_MS ? 2 : 1;
  }

  /**
   * A slow view in compare mode while the handles move (last moved at `movedAt`; -Infinity once the drag is
   * released): it leaves the cores to the others for now.
   */
  holding(requestMs, movedAt, now = performance.now()) {
    if (!this.shared || requestMs * this.size(requestMs) < SLOW_REQUEST_MS) return false;
    return now - movedAt < HOLD_MS && now - this.lastRequestAt < MAX_HOLD_MS;
  }

  /** A step request went out at `now`. */
  sent(now = performance.now()) {
    this.lastRequestAt = now;
  }
}
