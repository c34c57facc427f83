// What one view's session has done, for the stats line and the convergence plot: the series of merits
// (a fresh series per method and per model, since merits of different methods are not comparable), the
// time per iteration, and the progress of the current solve (iterations since the last change, elapsed
// time, the most time left before the iteration cap).
//
// Time per iteration: the first iteration after a load, a method switch, a new handle set or a re-solve
// from rest carries one-off work (the first evaluation after a factorization, the engine compiling the
// solver's hot code: bar-fine, subspace: 88 ms against 26-28 ms for the next ones), so the figure shown is
// the median of the last iterations without those. Until one is in, the first is shown as what it is.

const WINDOW = 15; // iterations in the median
const SERIES_KEPT = 8;
const POINTS_KEPT = 2000;

function median(values) {
  if (!values.length) return 0;
  const sorted = [...values].sort((a, b) => a - b);
  const mid = sorted.length >> 1;
  return sorted.length % 2 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
}

export class SolveRecord {
  constructor(method) {
    this.method = method;
    /** @type {{ method: string, points: { iteration: number, merit: number, ms: number }[] }[]} oldest first */
    this.series = [];
    this.warm = []; // ms of recent iterations without one-off work
    this.firstMs = 0; // the last cold iteration, shown until a warm one is in
    this.cold = true; // the next iteration carries one-off work
    this.requestMs = 0; // smoothed ms of every iteration: sizes the next request (auto)
    this.sinceChange = 0; // iterations since the handles, targets or options last changed
    this.changedAt = performance.now();
    this.lastIterationAt = 0;
    this.endedAt = 0; // when the current solve stopped (0 while solving)
  }

  /** A new model: every series goes (its merits are another model's). */
  newModel() {
    this.series = [];
    this.restart();
  }

  /** Another method: a fresh series; the timings are that method's. */
  setMethod(method) {
    this.method = method;
    this.restart();
  }

  /** A re-solve from rest (or a new model or method): a fresh series, timings measured again. */
  restart() {
    const current = this.current;
    if (!current || current.points.length) this.series.push({ method: this.method, points: [] });
    else current.method = this.method;
    if (this.series.length > SERIES_KEPT) this.series.splice(0, this.series.length - SERIES_KEPT);
    this.warm = [];
    this.firstMs = 0;
    this.requestMs = 0;
    this.expectSetUp();
    this.changed();
  }

  /** The next iteration carries one-off work (new handle groups: a new factorization). */
  expectSetUp() {
    this.cold = true;
  }

  /** Handles, targets or options changed: a new solve starts now. */
  changed() {
    this.sinceChange = 0;
    this.changedAt = performance.now();
    this.endedAt = 0;
  }

  /** The series being drawn (the latest). */
  get current() {
    return this.series.at(-1) ?? null;
  }

  /** Its points: merit per iteration. */
  get points() {
    return this.current?.points ?? [];
  }

  /** Iterations in the current series. */
  get iterations() {
    return this.current?.points.length ? this.current.points.at(-1).iteration : 0;
  }

  /** Adds a reply's iterations to the current series and the timings. */
  add(iterations) {
    if (!this.current) this.series.push({ method: this.method, points: [] });
    const points = this.current.points;
    for (const it of iterations) {
      points.push({ iteration: (points.at(-1)?.iteration ?? 0) + 1, merit: it.merit, ms: it.ms, samples: it.samples });
      if (this.cold) this.firstMs = it.ms;
      else this.warm.push(it.ms);
      this.cold = false;
      this.requestMs = this.requestMs ? 0.7 * this.requestMs + 0.3 * it.ms : it.ms;
    }
    if (points.length > POINTS_KEPT) points.splice(0, points.length - POINTS_KEPT);
    if (this.warm.length > WINDOW) this.warm.splice(0, this.warm.length - WINDOW);
    this.sinceChange += iterations.length;
    if (iterations.length) this.lastIterationAt = performance.now();
  }

  /** The solve ended (converged, stopped, failed): its time stops counting. */
  ended() {
    if (!this.endedAt) this.endedAt = performance.now();
  }

  /** Median ms of the last warm iterations (0 before the first). */
  get msPerIteration() {
    return median(this.warm);
  }

  /**
   * The solve since the last change: iterations, elapsed ms, the cap, the most time left before the cap at
   * the current time per iteration (null while no iteration's time is known: the first one still runs), and how
   * long the iteration in flight has run.
   * @param {number} cap iterations allowed since a change
   * @param {boolean} inFlight a step request is running
   */
  progress(cap, inFlight) {
    const now = performance.now();
    const ms = this.msPerIteration || this.firstMs;
    return {
      iteration: this.sinceChange,
      maxIterations: cap,
      elapsedMs: (this.endedAt || now) - this.changedAt,
      msLeftAtMost: ms > 0 ? Math.max(0, cap - this.sinceChange) * ms : null,
      runningMs: inFlight && !this.endedAt ? now - Math.max(this.lastIterationAt, this.changedAt) : 0,
    };
  }
}
