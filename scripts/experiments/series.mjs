// One convergence series of an experiment: a method run from the rest pose on a Deformer session, with
// per-iteration merit and cumulative ms, and the final shape measured by shared yardsticks.
//
// Yardsticks (the same for every method, so ARAP and the Gauss-Newton solves compare):
//   energy = 1/2 |f(X)|^2 of docs/method.md section 5 (binding benchEvaluateEnergy), split into its Laplacian
//   and position parts; arapEnergy = the ARAP energy with best rotations (binding benchArapEnergy);
//   volumeChangePercent = 100 (psi(X) - psi(X0)) / psi(X0); handle error = max |x_h - target_h|.
import { Timer } from '../lib/timer.mjs';

export const SERIES = {
  'subspace-fast': { label: 'subspace (fast, PCG)', options: { method: 'subspace', jacobian: 'fast', volume: true } },
  'subspace-exact': { label: 'subspace (exact, eq. 8)', options: { method: 'subspace', jacobian: 'exact', volume: true } },
  'subspace-novolume': { label: 'subspace, no volume constraint', options: { method: 'subspace', jacobian: 'fast', volume: false } },
  'full-fast': { label: 'full space (fast, PCG)', options: { method: 'full', jacobian: 'fast', volume: true } },
  'full-exact': { label: 'full space (exact, eq. 4)', options: { method: 'full', jacobian: 'exact', volume: true } },
  arap: { label: 'ARAP (one shot from rest)', options: { method: 'arap' } },
  'arap-sliced': { label: 'ARAP (drag in 10 slices)', options: { method: 'arap' }, slices: 10 },
};

// Iteration caps and wall-clock budgets per series (full run, --quick).
function limits(kind, quick) {
  if (kind.startsWith('arap')) return { cap: quick ? 150 : 500, budgetMs: quick ? 8000 : 40000 };
  if (kind === 'full-exact') return { cap: quick ? 4 : 25, budgetMs: quick ? 8000 : 45000 };
  if (kind === 'full-fast') return { cap: quick ? 40 : 300, budgetMs: quick ? 10000 : 60000 };
  if (kind === 'subspace-exact') return { cap: quick ? 20 : 100, budgetMs: quick ? 8000 : 40000 };
  return { cap: 100, budgetMs: quick ? 10000 : 40000 };
}

// Sampled iterations at which ARAP's iterates are measured with the shared energy (it costs a setup).
const sampled = (k) => k <= 10 || (k <= 50 && k % 5 === 0) || k % 25 === 0;

export function measure(ctx, positions) {
  const e = ctx.solver.benchEvaluateEnergy(ctx.rest, ctx.indices, positions, ctx.handleVertices, ctx.targets, 1.0);
  let maxError = 0;
  ctx.handleVertices.forEach((v, k) => {
    const d = Math.hypot(positions[3 * v] - ctx.targets[3 * k], positions[3 * v + 1] - ctx.targets[3 * k + 1],
      positions[3 * v + 2] - ctx.targets[3 * k + 2]);
    maxError = Math.max(maxError, d);
  });
  return {
    energy: e.energy,
    laplacianEnergy: e.laplacianEnergy,
    positionEnergy: e.positionEnergy,
    volumeChangePercent: (100 * (e.volume - e.restVolume)) / e.restVolume,
    handleMaxError: maxError,
    handleMaxErrorRelative: maxError / ctx.diagonal,
  };
}

/**
 * Runs one series from the rest pose.
 * @param {{ solver, d, targets: Float64Array, rest, indices, diagonal, quick, handleVertices: number[],
 *   solverOptions?: { weighting: string, integration: string } }} ctx the options every series shares
 * @param {string} kind a key of SERIES
 */
export function runSeries(ctx, kind) {
  const spec = SERIES[kind];
  const { cap, budgetMs } = limits(kind, ctx.quick);
  const { d } = ctx;
  d.setOptions({ ...ctx.solverOptions, ...spec.options, maxIterations: cap });
  d.reset();
  const iterations = [];
  const energyTrace = [];
  const isArap = kind.startsWith('arap');
  let stopReason = '';
  let converged = false;
  let cumulative = 0;
  const started = new Timer();
  const record = (r) => {
    for (const it of r.iterations) {
      cumulative += it.ms;
      const k = iterations.length + 1;
      iterations.push({
        iteration: k, merit: it.merit, energy: it.energy, volumeRelError: it.volumeRelError, step: it.step,
        lineSearchTrials: it.lineSearchTrials, innerIterations: it.innerIterations, products: it.products,
        ms: it.ms, cumulativeMs: cumulative,
      });
      if (!isArap) energyTrace.push({ iteration: k, energy: it.energy });
    }
  };
  // ARAP in slices: the targets move from rest to the goal in equal steps, a few iterations each (how
  // interactive ARAP is used; the report's section 3.2 discusses why it helps).
  if (spec.slices) {
    const goal = ctx.targets;
    const rest = new Float64Array(goal.length);
    ctx.handleVertices.forEach((v, k) => { for (let a = 0; a < 3; ++a) rest[3 * k + a] = ctx.rest[3 * v + a]; });
    for (let s = 1; s < spec.slices; ++s) {
      const t = s / spec.slices;
      d.setTargets(rest.map((r, i) => r + t * (goal[i] - r)));
      for (let k = 0; k < 10; ++k) {
        record(d.step(1));
        if (sampled(iterations.length)) energyTrace.push({ iteration: iterations.length, ...measure(ctx, d.positions()), slice: s });
      }
    }
  }
  d.setTargets(ctx.targets);
  while (iterations.length < cap && started.ms() < budgetMs) {
    const r = d.step(isArap ? 1 : Math.min(5, cap - iterations.length));
    record(r);
    if (isArap && sampled(iterations.length)) energyTrace.push({ iteration: iterations.length, ...measure(ctx, d.positions()) });
    stopReason = r.stopReason;
    if (r.converged) { converged = true; break; }
    if (r.iterations.length === 0 || stopReason.startsWith('numerical')) break;
  }
  if (!converged && !stopReason.startsWith('numerical')) {
    stopReason = iterations.length >= cap ? `iteration cap ${cap}` : `time budget ${budgetMs / 1e3} s`;
  }
  const positions = d.positions();
  const final = { ...measure(ctx, positions), arapEnergy: ctx.solver.benchArapEnergy(ctx.rest, ctx.indices, positions) };
  if (isArap && energyTrace.at(-1)?.iteration !== iterations.length) energyTrace.push({ iteration: iterations.length, energy: final.energy });
  return {
    method: kind, label: spec.label, options: spec.options, cap, budgetMs,
    iterations, energyTrace, converged, stopReason, totalMs: cumulative, wallMs: started.ms(),
    final, positions,
  };
}
