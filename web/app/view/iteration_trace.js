// What the last step did, drawn in a view while the solver is paused (step-through, step_through.js): for a
// Gauss-Newton iteration the step, each line-search trial with its alpha and merit, the multiplier lambda (one per
// volume part, with parts) and each energy term (docs/method.md sections 5-8) and, with a skeleton, each bone's multiplier and errors; for an ARAP iteration its energy and move; for an ARAP half
// step the local step's rotations or the global step's move, with the energy before and after (section 13).
import { methodLabel } from '../methods.js';
import { skeletonTraceLines } from '../skeleton/skeleton_text.js';

const num = (x) => (x === 0 ? '0' : Math.abs(x) >= 1e-3 && Math.abs(x) < 1e4 ? String(Number(x.toPrecision(4))) : x.toExponential(3));
const degrees = (radians) => `${((radians * 180) / Math.PI).toFixed(1)}\u00b0`;

/** The lines of a Gauss-Newton iteration's trace. */
function gaussNewtonLines(s, options) {
  const lines = [];
  if (s.lineSearch) {
    lines.push(`step: largest vertex move of the full step ${num(s.stepLength)}, slope ${num(s.slope)} (merit at alpha = 0: ${num(s.meritStart)})`);
    lines.push(`line search (Armijo c1 = ${options.c1}, backtracking c2 = ${options.c2}):`);
    for (const trial of s.lineSearch) {
      const verdict = trial.restored ? 'accepted' : trial.sufficientDecrease ? 'volume not restorable' : 'not enough decrease';
      lines.push(`  alpha ${num(trial.alpha).padEnd(9)} merit ${num(trial.merit).padEnd(10)} ${verdict}`);
    }
    lines.push(`accepted alpha ${num(s.alpha)}: largest vertex move ${num(s.step)}`);
  } else {
    lines.push(`step: largest vertex move ${num(s.step)} after ${s.lineSearchTrials} line-search trial${s.lineSearchTrials === 1 ? '' : 's'}`);
  }
  if (s.innerIterations) lines.push(`inner PCG: ${s.innerIterations} iterations, ${s.products} products${s.fallbacks ? ' (fell back to the gradient)' : ''}`);
  lines.push(...multiplierLines(s));
  const straightness = s.straightnessEnergy ? ` + bone straightness ${num(s.straightnessEnergy)}` : '';
  lines.push(`energy E = Laplacian ${num(s.laplacianEnergy)} + position ${num(s.positionEnergy)}${straightness} = ${num(s.energy)}`);
  const regularized = s.regularizationEnergy ? ` + R ${num(s.regularizationEnergy)}` : '';
  lines.push(`merit E${regularized} + ${s.partLambda?.length ? 'sum of lambda_k g_k over the parts' : 'lambda g'} = ${num(s.merit)}`);
  return lines;
}

const percent = (x) => `${(100 * (x ?? 0)).toExponential(2)} %`;
const SHOWN_PARTS = 8; // more parts (up to 64) would push the energies out of the box

// The volume's multiplier and change; with volume parts one multiplier per part (the global lambda is 0 then).
function multiplierLines(s) {
  const parts = s.partLambda ?? [];
  if (!parts.length) return [`multiplier lambda ${num(s.lambda)}   volume change ${percent(s.volumeRelError)}`];
  const lines = parts.slice(0, SHOWN_PARTS).map((lambda, k) => `part ${k}: multiplier ${num(lambda)}   volume change ${percent(s.partVolumeChange?.[k])}`);
  if (parts.length > SHOWN_PARTS) {
    const rest = parts.slice(SHOWN_PARTS).map(Math.abs);
    lines.push(`... ${rest.length} parts more, |multiplier| up to ${num(Math.max(...rest))}`);
  }
  return [`volume parts ${parts.length}: one multiplier each`, ...lines];
}

/** The lines of a trace (step_through.js). */
export function traceLines(trace, options = { c1: 1e-4, c2: 0.5 }) {
  const label = trace.label ?? methodLabel(trace.method);
  if (trace.kind === 'half') {
    const h = trace.half;
    if (!h) return [`${label}: no handles, nothing to step`];
    const head = h.phase === 'local'
      ? [`${label}: local step: the best rotation of every vertex for these positions`,
        `rotations: mean ${degrees(h.meanRotation)}, largest ${degrees(h.maxRotation)} (from the rest pose)`]
      : [`${label}: global step: the positions for these rotations (one sparse solve per axis)`,
        `largest vertex move ${num(h.step)}`];
    return [...head, `ARAP energy ${num(h.energyBefore)} -> ${num(h.energyAfter)}`,
      `next: the ${h.phase === 'local' ? 'global' : 'local'} step`];
  }
  const s = trace.stats;
  if (!s) return [`${label}: ${trace.idle ?? (trace.result?.stopReason || 'no handles, nothing to step')}`];
  const done = trace.result?.converged ? ` (${trace.result.stopReason})` : '';
  if (trace.method === 'arap') {
    return [`${label}: iteration ${s.iteration}${done}`, `ARAP energy ${num(s.energy)}   largest vertex move ${num(s.step)}`,
      `volume change ${(100 * s.volumeRelError).toFixed(3)} % (ARAP does not keep it)`,
      s.fallbacks ? 'Anderson extrapolation rejected: a plain local-global step' : 'local step, then global step (or an accelerated step)'];
  }
  // With a skeleton, each bone's multiplier and errors after the step (the worker's report).
  return [`${label}: Gauss-Newton iteration ${s.iteration}${done}`, ...gaussNewtonLines(s, options), ...skeletonTraceLines(trace.skeleton)];
}

export class IterationTrace {
  /** @param {HTMLElement} parent the view's element */
  constructor(parent) {
    this.element = Object.assign(document.createElement('div'), { className: 'sd-trace', hidden: true });
    this.element.setAttribute('aria-live', 'polite');
    parent.appendChild(this.element);
  }

  show(trace, options) {
    this.element.textContent = traceLines(trace, options).join('\n');
    this.element.hidden = false;
  }

  /** Paused with no step yet: say what to do. */
  prompt(text) {
    this.element.textContent = text;
    this.element.hidden = false;
  }

  hide() {
    this.element.hidden = true;
  }
}
