// The app's parts for touch and the step-through that need no page: the tool settings, the status bar's note
// when the solver runs single-threaded, and the text of a step's trace (Gauss-Newton with and without the
// line search's trials, ARAP iterations and half steps).
import { describe, expect, it } from 'vitest';
import { AppSettings, TOOLS, touchesSolver } from '../../web/app/settings.js';
import { buildNote } from '../../web/app/stats_format.js';
import { traceLines } from '../../web/app/view/iteration_trace.js';
import { StepThrough } from '../../web/app/step_through.js';
import { AppLifetime } from '../../web/app/app_lifetime.js';
import { CancelledError, InputError } from '../../web/lib/errors.js';

describe('tool settings', () => {
  it('take the five tools (the bone tool last) and erase, concern no solver, and refuse anything else naming the setting', () => {
    const settings = new AppSettings();
    expect(settings.values.tool).toBe('pick');
    expect(settings.values.erase).toBe(false);
    for (const tool of TOOLS) settings.update({ tool });
    settings.update({ erase: true });
    expect(touchesSolver({ tool: 'brush', erase: true })).toBe(false);
    expect(() => settings.update({ tool: 'paint' })).toThrow(InputError);
    expect(() => settings.update({ tool: 'paint' })).toThrow(/tool must be one of 'orbit', 'pick', 'brush', 'lasso'/);
    expect(() => settings.update({ erase: 'yes' })).toThrow(/erase must be true or false/);
    expect(settings.values.tool).toBe('bone'); // unchanged by the refused updates
  });
});

describe('the status bar note', () => {
  it('says when and why the solver runs single-threaded, with the fix on hover, and nothing with threads', () => {
    expect(buildNote({ build: 'threads', threads: 2 })).toEqual({ text: '', title: '' });
    expect(buildNote(null).text).toBe('');
    const isolated = buildNote({ build: 'single', threads: 1, buildNote: 'the page is not cross-origin isolated, so it runs single-threaded' });
    expect(isolated.text).toBe('single-threaded: page not cross-origin isolated');
    expect(isolated.title).toMatch(/coi-serviceworker\.js/);
    const failed = buildNote({ build: 'single', threads: 1, buildNote: 'the threaded build did not load (404); running single-threaded' });
    expect(failed.text).toBe('single-threaded: the threaded build did not load');
    expect(failed.title).toMatch(/404/);
  });
});

const gaussNewton = {
  iteration: 3, merit: 0.0123, energy: 0.0121, laplacianEnergy: 0.007, positionEnergy: 0.0051, regularizationEnergy: 2e-4,
  volume: 1, volumeRelError: 1e-14, lambda: -0.25, step: 0.04, lineSearchTrials: 2, innerIterations: 7, products: 7,
  passes: 14, fallbacks: 0, ms: 3,
};

describe('the step-through trace', () => {
  it('shows a Gauss-Newton iteration: the trials with alpha and merit, lambda and each energy term', () => {
    const stats = { ...gaussNewton, meritStart: 0.05, slope: -0.08, stepLength: 0.08, alpha: 0.5,
      lineSearch: [{ alpha: 1, merit: 0.06, sufficientDecrease: false, restored: false }, { alpha: 0.5, merit: 0.0123, sufficientDecrease: true, restored: true }] };
    const text = traceLines({ method: 'subspace', kind: 'iteration', stats, result: { converged: false } }, { c1: 1e-4, c2: 0.5 }).join('\n');
    expect(text).toMatch(/Gauss-Newton iteration 3/);
    expect(text).toMatch(/Armijo c1 = 0.0001, backtracking c2 = 0.5/);
    expect(text).toMatch(/alpha 1\s+merit 0\.06\d*\s+not enough decrease/);
    expect(text).toMatch(/alpha 0\.5\s+merit 0\.0123\s+accepted/);
    expect(text).toMatch(/multiplier lambda -0\.25/);
    expect(text).toMatch(/Laplacian 0\.007\d* \+ position 0\.0051\d* = 0\.0121/);
    expect(text).toMatch(/merit E \+ R 2\.000e-4 \+ lambda g = 0\.0123/);
  });

  it('without the line search trace still shows the trials counted, lambda and the energies', () => {
    const text = traceLines({ method: 'full', kind: 'iteration', stats: gaussNewton, result: { converged: true, stopReason: 'converged: step below tolerance' } }).join('\n');
    expect(text).toMatch(/Full space: Gauss-Newton iteration 3 \(converged: step below tolerance\)/);
    expect(text).toMatch(/after 2 line-search trials/);
    expect(text).toMatch(/multiplier lambda/);
  });

  it('with volume parts gives each part\'s multiplier and change, not the global lambda (0 then), and the merit sums them', () => {
    const stats = { ...gaussNewton, lambda: 0, partLambda: [-5.9e-4, -4.4e-6, 9.4e-4], partVolumeChange: [1e-15, -2e-14, 0] };
    const text = traceLines({ method: 'subspace', kind: 'iteration', stats, result: { converged: false } }).join('\n');
    expect(text).not.toMatch(/multiplier lambda/);
    expect(text).toMatch(/volume parts 3: one multiplier each\npart 0: multiplier -5\.900e-4 {3}volume change 1\.00e-13 %\npart 1: multiplier -4\.400e-6/);
    expect(text).toMatch(/part 2: multiplier 9\.400e-4/);
    expect(text).toMatch(/merit E \+ R 2\.000e-4 \+ sum of lambda_k g_k over the parts = 0\.0123/);
    const many = traceLines({ method: 'subspace', kind: 'iteration', stats: { ...stats, partLambda: Array.from({ length: 12 }, (_, k) => k / 10) } });
    expect(many.join('\n')).toMatch(/part 7: .*\n\.\.\. 4 parts more, \|multiplier\| up to 1\.1/);
  });

  it('says why a step ran no iteration: converged already, or the model still binding', () => {
    expect(traceLines({ method: 'subspace', kind: 'iteration', stats: null, result: { converged: true }, idle: 'converged at iteration 7: nothing to do' }))
      .toEqual(['Subspace (cage): converged at iteration 7: nothing to do']);
    expect(traceLines({ method: 'full', kind: 'iteration', stats: null, result: null })).toEqual(['Full space: no handles, nothing to step']);
  });

  it('shows ARAP iterations and half steps with their energies and rotations', () => {
    const iteration = traceLines({ method: 'arap', kind: 'iteration', stats: { ...gaussNewton, energy: 0.5, volumeRelError: -0.03 } }).join('\n');
    expect(iteration).toMatch(/ARAP energy 0\.5/);
    expect(iteration).toMatch(/volume change -3\.000 %/);
    const local = traceLines({ method: 'arap', kind: 'half', half: { phase: 'local', energyBefore: 0.6, energyAfter: 0.5, meanRotation: Math.PI / 18, maxRotation: Math.PI / 4, step: 0 } }).join('\n');
    expect(local).toMatch(/local step: the best rotation of every vertex/);
    expect(local).toMatch(/mean 10\.0°, largest 45\.0°/);
    expect(local).toMatch(/ARAP energy 0\.6 -> 0\.5/);
    expect(local).toMatch(/next: the global step/);
    const global = traceLines({ method: 'arap', kind: 'half', half: { phase: 'global', energyBefore: 0.5, energyAfter: 0.4, meanRotation: 0, maxRotation: 0, step: 0.02 } }).join('\n');
    expect(global).toMatch(/global step: the positions for these rotations/);
    expect(global).toMatch(/largest vertex move 0\.02/);
  });
});

describe('StepThrough', () => {
  // A view whose session answers a step with `result` (null: no model or no handles).
  const view = (method, session) => ({ method, setPaused() {}, showTrace(trace) { this.trace = trace; }, skeletonView: { report: null },
    session: { idle: async () => {}, ...session } });

  it('waits for the views to be bound (`ready`) and says why a view ran no iteration', async () => {
    let bound = false;
    const views = [
      view('subspace', { client: {}, hasHandles: true, last: { iteration: 7 }, stepOnce: async () => ({ iterations: [], converged: true, stop: null, nothingToDo: true }) }),
      view('full', { client: {}, hasHandles: false, stepOnce: async () => null }),
      view('arap', { client: null, hasHandles: false, stepOnce: async () => null }),
    ];
    const stepping = new StepThrough({ views: { list: views }, ready: () => new Promise((resolve) => setTimeout(() => { bound = true; resolve(); }, 5)) });
    const traces = await stepping.next();
    expect(bound).toBe(true);
    expect(traces.map((t) => t.idle)).toEqual(['converged at iteration 7: nothing to do (move a handle to solve again)',
      'no handles, nothing to step', 'still binding the model: step again once it is bound']);
    expect(views[0].trace.idle).toMatch(/^converged at iteration 7/);
  });

  // An attack: an embed removed while its stepping.next() waited left that promise pending for ever (the pause waits
  // for the step requests out, whose worker dispose() terminated without an answer). Each of the step-through's
  // promises now rejects with a CancelledError when the app's life ends, and one asked for afterwards at once.
  it('rejects a pending next(), nextHalf() or setPaused() with a CancelledError when the app is disposed', async () => {
    const never = () => new Promise(() => {}); // the terminated worker's answer
    const life = new AppLifetime();
    const stepping = new StepThrough({ views: { list: [view('arap', { client: {}, hasHandles: true, idle: never, stepOnce: never, arapHalfStep: never })] },
      ready: async () => {}, life });
    const outcome = (promise) => Promise.race([promise.then(() => 'resolved', (e) => `${e.name}: ${e.message}`),
      new Promise((resolve) => setTimeout(() => resolve('pending'), 50))]);
    const pending = [stepping.next(), stepping.nextHalf(), stepping.setPaused(true)].map(outcome);
    await new Promise((resolve) => setTimeout(resolve, 10));
    life.end();
    expect(await Promise.all(pending)).toEqual(Array(3).fill('CancelledError: cancelled: the app was disposed'));
    await expect(stepping.next()).rejects.toBeInstanceOf(CancelledError);
  });

  // A reviewer's find: guard() took the promise, so the call had already run when it saw the app disposed:
  // setPaused() on a disposed app still paused its (disposed) views and fired 'change', and a disposed app's
  // solve() left the rejection of the promise it dropped unhandled. Now nothing runs after the end.
  it('does nothing once the app is disposed: no pause of the views, no change event, the call rejects at once', async () => {
    const life = new AppLifetime();
    let paused = 0;
    const stepping = new StepThrough({ views: { list: [{ ...view('full', {}), setPaused() { paused++; } }] }, ready: async () => {}, life });
    const events = [];
    stepping.addEventListener('change', (e) => events.push(e.paused));
    life.end();
    for (const call of [() => stepping.setPaused(true), () => stepping.next(), () => stepping.nextHalf()]) {
      await expect(call()).rejects.toBeInstanceOf(CancelledError);
    }
    expect({ paused, events, flag: stepping.paused }).toEqual({ paused: 0, events: [], flag: false });
    let called = false;
    await expect(life.guard(() => { called = true; return Promise.reject(new Error('dropped')); })).rejects.toBeInstanceOf(CancelledError);
    expect(called).toBe(false); // the rejected promise is never made, so it cannot go unhandled
    await expect(new AppLifetime().guard(() => { throw new Error('thrown'); })).rejects.toThrow('thrown');
  });
});
