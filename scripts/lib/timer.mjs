// Elapsed time for what the scripts report and for their time budgets (benchmarks, experiments, the CLI's
// report and --time-limit, the fuzzer's duration), on a monotonic clock: performance.now(), never Date.now(),
// which jumps with the system clock. The same as cpp/core/timer.h's Timer.

/** Milliseconds and seconds since construction. */
export class Timer {
  #start = performance.now();

  /** @returns {number} */
  ms() {
    return performance.now() - this.#start;
  }

  /** @returns {number} */
  seconds() {
    return this.ms() / 1e3;
  }
}

// A time as people read it in the CLI's summaries ("3.2 ms", "850 ms", "12.3 s", "2 min 05 s"), the app's own
// formatter (its stats line shows the same times).
export { duration } from '../../web/app/stats_format.js';
