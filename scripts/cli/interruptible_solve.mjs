// deform's solve, in chunks of iterations so that a long one can be stopped: Ctrl-C (SIGINT) or --time-limit
// end it between two chunks, and the command still writes what it has (the mesh so far and a report saying
// it was cut short) instead of losing it. A solve with huge limits (maxIterations 2^31-1, tolerances 0) can
// run for hours; it is the only way out that keeps the work. Iterating in chunks gives the same iterates as
// one solve() (the session keeps its state between steps); the chunk size follows the measured time per
// iteration so that a stop takes effect within about a quarter of a second.
import { STOP_CODES } from 'subspace-deform';
import { Timer } from '../lib/timer.mjs';

const CHUNK_MS = 250;
const PROGRESS_EVERY_MS = 5000;

const reasonOf = (stop) => STOP_CODES.find((c) => c.name === stop)?.reason ?? stop;

/**
 * Iterates until the solver stops by itself or maxIterations is reached (as solve() does), or until
 * interrupted.
 * @param {import('subspace-deform').Deformer} deformer with handles and targets set
 * @param {{ maxIterations: number, timeLimitMs?: number, onProgress?: (iterations: number, ms: number) => void }} options
 * @returns {Promise<{ result: import('subspace-deform').StepResult, cutShort: null | { by: 'SIGINT' | 'time limit', afterMs: number } }>}
 */
export async function solveInterruptibly(deformer, { maxIterations, timeLimitMs = Infinity, onProgress }) {
  let signalled = false;
  const onSignal = () => { signalled = true; };
  process.on('SIGINT', onSignal);
  const started = new Timer();
  const iterations = [];
  let last = null;
  let chunk = 1;
  let nextProgress = PROGRESS_EVERY_MS;
  let cutShort = null;
  try {
    while (iterations.length < maxIterations) {
      const stepTimer = new Timer();
      last = deformer.step(Math.min(chunk, maxIterations - iterations.length));
      iterations.push(...last.iterations);
      if (last.stop !== 'iteration_limit') break;
      const ms = stepTimer.ms();
      chunk = Math.max(1, Math.min(2 * chunk, Math.round((chunk * CHUNK_MS) / Math.max(ms, 1e-3))));
      // Lets a pending SIGINT run its handler.
      await new Promise((resolve) => setImmediate(resolve));
      const elapsed = started.ms();
      if (signalled || elapsed >= timeLimitMs) {
        cutShort = { by: signalled ? 'SIGINT' : 'time limit', afterMs: elapsed };
        break;
      }
      if (elapsed >= nextProgress) {
        onProgress?.(iterations.length, elapsed);
        nextProgress += PROGRESS_EVERY_MS;
      }
    }
  } finally {
    process.off('SIGINT', onSignal);
  }
  return { result: combined(last, iterations, maxIterations), cutShort };
}

// One StepResult for the whole solve, as solve() reports it: reaching the cap is 'max_iterations'.
function combined(last, iterations, maxIterations) {
  if (!last) return { iterations, converged: false, stop: 'no_iterations', stopReason: reasonOf('no_iterations') };
  if (last.stop === 'iteration_limit' && iterations.length >= maxIterations) {
    return { iterations, converged: false, stop: 'max_iterations', stopReason: reasonOf('max_iterations') };
  }
  return { ...last, iterations };
}
