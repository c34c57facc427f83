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
