// The cage-free spectral subspace against the cage's and the full space, on each scene of the report's
// experiments (docs/method.md section 15; the report's future work): the subspace method with the spectral
// basis B for k + 4 = m (as many unknowns per coordinate as the cage) and a sweep of k, run from rest like
// the other series, and the condition number of the step's normal matrix at the rest pose for every basis
// (benchStepConditioning), raw and in an orthonormal basis of the subspace.
import { Deformer } from 'subspace-deform';
import { runSeries } from './series.mjs';
import { renderViews } from './render.mjs';
import { Timer } from '../lib/timer.mjs';

const SWEEP = [10, 20, 50, 100, 200];

/** k for the spectral series: m - 4 (the cage's size) and the sweep, each with k + 5 <= n. */
export function spectralModes(m, n) {
  return [...new Set([m - 4, ...SWEEP])].filter((k) => k >= 1 && k + 5 <= n).sort((a, b) => a - b);
}

// One spectral session per k: its basis is bound at creation, like a cage.
function spectralSeries(ctx, model, k, m) {
  const d = Deformer.create(ctx.solver, model.mesh, null, { basis: 'spectral', modes: k });
  try {
    d.setHandles(ctx.groups);
    const s = runSeries({ ...ctx, d }, 'subspace-fast');
    s.method = `spectral-${k}`;
    s.label = `spectral, k = ${k}${k + 4 === m ? ' (k + 4 = m)' : ''}`;
    s.modes = k;
    s.bindMs = d.bindMs;
    return s;
  } finally {
    d.dispose();
  }
}

function conditioning(ctx, basis) {
  try {
    return ctx.solver.benchStepConditioning(ctx.rest, ctx.indices, ctx.rest, ctx.handleVertices, ctx.targets, 1.0, basis);
  } catch (error) {
    return { error: error.message };
  }
}

/**
 * Runs the spectral series of one scene and the conditioning of every basis; `standard` holds the scene's
 * other series (the cage subspace and the full space are taken from there, not run again).
 * @returns {{ modes: number[], series: object[], conditioning: object, image: object }}
 */
export function compareSubspaces(ctx, model, scene, standard, out, log) {
  const n = model.mesh.positions.length / 3, m = model.cage.positions.length / 3;
  const modes = spectralModes(m, n);
  const series = [];
  for (const k of modes) {
    const timer = new Timer();
    const s = spectralSeries(ctx, model, k, m);
    series.push(s);
    log(`${scene.id} ${s.label}: ${s.iterations.length} iterations, energy ${s.final.energy.toExponential(3)}, ` +
      `handle error ${s.final.handleMaxErrorRelative.toExponential(2)} D, bind ${s.bindMs.toFixed(0)} ms, ${s.stopReason} ` +
      `(${timer.seconds().toFixed(1)} s)`);
  }
  const result = {
    modes,
    series,
    conditioning: {
      full: conditioning(ctx, { kind: 'full' }),
      cage: conditioning(ctx, { kind: 'cage', positions: model.cage.positions, indices: model.cage.indices }),
      spectral: Object.fromEntries(modes.map((k) => [k, conditioning(ctx, { kind: 'spectral', modes: k })])),
    },
  };
  const pick = (method) => standard.find((s) => s.method === method);
  const panels = [pick('subspace-fast'), ...series.filter((s) => s.modes === m - 4 || s.modes === modes[0] || s.modes === modes.at(-1)),
    pick('full-fast')].filter(Boolean);
  result.image = renderViews(out, scene.id, model.mesh, panels.map((s) => ({ ...s, label: s.method === 'subspace-fast' ? 'cage subspace' : s.label })),
    ctx, { yaw: model.real ? scene.view?.yaw ?? 0 : 0, file: `${scene.id}_subspaces.png` });
  return result;
}
