// Text of the numbers the app shows: each view's stats line, the status bar (model, fps) and the panel's
// stats folder. Input: the stats object of the scripting API (DeformerApp.viewStats, docs/embed.md).
import { isSpectral } from '../lib/subspace.js';
import { skeletonStatsLine } from './skeleton/skeleton_text.js';

const STATE_LABELS = { converged: 'converged', solving: 'solving\u2026', stopped: 'stopped', error: 'error', idle: 'no handles',
  paused: 'paused (step-through: N or the step button)' };
const LONG_SOLVE_MS = 1000; // solves that take longer show their progress and, once done, their duration

/** The reason shown after the state, for states that end a solve without converging. */
function reasonOf(stats) {
  return stats.state === 'stopped' || stats.state === 'error' ? stats.stopReason : '';
}

/** 3.2 ms, 850 ms, 12.3 s, 2 min 05 s */
export function duration(ms) {
  if (ms < 100) return `${ms.toFixed(1)} ms`;
  if (ms < 1000) return `${ms.toFixed(0)} ms`;
  if (ms < 60000) return `${(ms / 1000).toFixed(1)} s`;
  const s = Math.round(ms / 1000);
  return `${Math.floor(s / 60)} min ${String(s % 60).padStart(2, '0')} s`;
}

/** x, or 0 where it is rounding: below 1e-12 of `scale`, the size of the terms it was computed from. */
function unlessRounding(x, scale) {
  return Math.abs(x) < 1e-12 * scale ? 0 : x;
}

/** x.toFixed(digits), never "-0.000": a value that rounds to zero shows no sign. */
function fixed(x, digits) {
  const text = x.toFixed(digits);
  return /^-0\.?0*$/.test(text) ? text.slice(1) : text;
}

/**
 * The merit E + lambda g, "0" where it is rounding: at rest E is 0 and lambda g is lambda times a volume
 * difference that is round-off of the volume (a merit of -1.2e-17 is no negative energy).
 */
export function meritText(stats) {
  const multipliers = Math.abs(stats.lambda ?? 0) + (stats.partLambda ?? []).reduce((sum, l) => sum + Math.abs(l), 0);
  const merit = unlessRounding(stats.merit, Math.abs(stats.energy ?? 0) + multipliers * Math.abs(stats.restVolume ?? 0));
  return merit === 0 ? '0' : merit.toExponential(3);
}

/** The volume change in percent with 6 decimals: 0 below rounding (1e-12 relative), never "-0.000000". */
export function volumeChangeText(stats) {
  return fixed(100 * unlessRounding(stats.volumeRelError, 1), 6);
}

/** Time per iteration: the warm median, or the first iteration (with its one-off work) until one is in. */
function timing(stats) {
  if (stats.msPerIteration > 0) return `${duration(stats.msPerIteration)}/iteration`;
  return stats.firstIterationMs > 0 ? `first iteration ${duration(stats.firstIterationMs)}` : '';
}

/**
 * Progress of a long solve: "iteration 12 of at most 100 · at most 2 min 47 s left (13 running 1.2 s)"; once
 * it ended: how many iterations and how long. Empty for quick solves.
 */
export function progressLine(stats) {
  const p = stats.progress;
  if (!p || p.elapsedMs < LONG_SOLVE_MS) return '';
  if (stats.state === 'solving') {
    const running = p.runningMs >= LONG_SOLVE_MS ? ` (iteration ${p.iteration + 1} running ${duration(p.runningMs)})` : '';
    // Nothing about the time left until an iteration's time is known ("at most 0.0 ms left" during the first).
    const left = p.msLeftAtMost === null ? '' : ` \u00b7 at most ${duration(p.msLeftAtMost)} left`;
    return `iteration ${p.iteration} of at most ${p.maxIterations} \u00b7 ${duration(p.elapsedMs)} so far${left}${running}`;
  }
  if (stats.state === 'converged' || stats.state === 'stopped') return `${p.iteration} iterations in ${duration(p.elapsedMs)}`;
  return '';
}

/** Which wasm build runs, with how many threads, and why a page got the single-threaded one. */
export function solverLine(solver) {
  if (!solver) return '';
  if (solver.build === 'threads') return `wasm: threaded build, ${solver.threads} thread${solver.threads === 1 ? '' : 's'}`;
  const why = /isolated/.test(solver.buildNote ?? '') ? ' (page not cross-origin isolated)'
    : solver.buildNote ? ' (the threaded build did not load)' : '';
  return `wasm: single-threaded build${why}`;
}

/**
 * The status bar's note when the solver runs single-threaded, with the reason and the fix on hover (a compact
 * view has no room for the stats line that says so). Empty with threads.
 */
export function buildNote(solver) {
  if (solver?.build !== 'single') return { text: '', title: '' };
  if (/isolated/.test(solver.buildNote ?? '')) {
    return { text: 'single-threaded: page not cross-origin isolated',
      title: 'The solver runs on one core: this page is not cross-origin isolated. One line gives it every core: load ' +
        'coi-serviceworker.js (it comes with the build) before the app, from the site\'s top folder (the project\'s docs/embed.md).' };
  }
  return { text: 'single-threaded: the threaded build did not load', title: solver.buildNote ?? '' };
}

/**
 * A view's stats line: the numbers (lines), the state word (styled by its state) and the reason.
 * @param {object} stats
 * @param {{ loaded: boolean|string, requestSize: number }} context loaded: true, or the text to show instead
 *   of the numbers (loading, or why no model is loaded); requestSize: iterations per step request
 * @returns {{ numbers: string, state: string, label: string, reason: string }}
 */
export function statsLine(stats, { loaded, requestSize }) {
  let numbers;
  if (loaded !== true) numbers = loaded || 'loading\u2026';
  else if (stats.iterations) {
    const integration = stats.samples ? `   reduced: ${stats.samples} samples`
      : stats.finishing ? '   reduced: finishing on every vertex' : '';
    numbers = `merit ${meritText(stats)}   volume change ${volumeChangeText(stats)}%\n` +
      `iterations ${stats.iterations}   ${timing(stats)}   k=${requestSize}/request${integration}`;
    const bones = skeletonStatsLine(stats.skeleton); // the bones' largest errors and multiplier, with a skeleton
    if (bones) numbers += `\n${bones}`;
  } else {
    numbers = `${stats.vertexCount} vertices, bind ${stats.bindMs.toFixed(0)} ms`;
  }
  const warnings = (stats.warnings ?? []).map((w) => `\u26a0 ${w.code}: ${w.message}`);
  const extra = [progressLine(stats), ...warnings, solverLine(stats.solver)].filter(Boolean);
  if (loaded === true && extra.length) numbers += `\n${extra.join('\n')}`;
  const reason = reasonOf(stats);
  return { numbers, state: stats.state, label: STATE_LABELS[stats.state] ?? stats.state, reason: reason ? `: ${reason}` : '' };
}

/**
 * "37 modes (40 asked; 3 repeated lower ones)": eigenvectors in the span of the constant, the linear maps and the
 * modes before them add nothing and are left out (on round shapes the first three are x, y and z).
 */
export function spectralModes(model) {
  const got = model.basisSize - 4;
  const asked = model.modesAsked ?? got;
  const modes = `${got} mode${got === 1 ? '' : 's'}`;
  return asked > got ? `${modes} (${asked} asked; ${asked - got} repeated lower ones, left out)` : modes;
}

/** The model in the status bar: name, vertices, triangles, and its subspace: the cage's vertices or the spectral modes. */
export function modelLine(model) {
  if (!model) return '';
  const n = (x) => x.toLocaleString('en-US');
  // The spectral basis B = [1, x0, y0, z0, phi_1 .. phi_k] has k + 4 columns; a cage the model has drives nothing.
  const coordinates = model.coordinates && model.coordinates.coordinates !== 'mvc' ? `, ${model.coordinates.coordinates} coordinates` : '';
  const subspace = isSpectral(model) ? `spectral basis, ${spectralModes(model)}`
    : `cage ${n(model.cage.positions.length / 3)} vertices${model.generatedCage ? ' (generated)' : ''}${coordinates}`;
  return `${model.name}: ${n(model.mesh.positions.length / 3)} vertices, ${n(model.mesh.indices.length / 3)} triangles, ${subspace}`;
}

/** Animation frames and redraws per second. */
export function fpsLine(fps, renderFps) {
  return `${fps.toFixed(0)} fps \u00b7 ${renderFps.toFixed(0)} redraws/s`;
}

/** The panel's stats folder, one string per row. */
export function panelStats(stats) {
  const reason = reasonOf(stats);
  return {
    status: reason ? `${stats.state}: ${reason}` : stats.state,
    merit: meritText(stats),
    volume: `${volumeChangeText(stats)} %`,
    parts: stats.partVolumeChange
      ? `${stats.partVolumeChange.length}, max ${(100 * Math.max(...stats.partVolumeChange.map(Math.abs))).toExponential(1)} %`
      : 'global volume',
    iterations: String(stats.iterations),
    msPerIteration: stats.msPerIteration ? stats.msPerIteration.toFixed(2) : '',
    fps: stats.fps.toFixed(0),
  };
}
