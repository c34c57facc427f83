// The app's parts for touch and the step-through that need no page: the tool settings, the status bar's note
// when the solver runs single-threaded, and the text of a step's trace (Gauss-Newton with and without the
// line search's trials, ARAP iterations and half steps).
import { describe, expect, it } from 'vitest';
import { AppSettings, TOOLS, touchesSolver } from '../../web/app/settings.js';
import { buildNote } from '../../web/app/stats_format.js';
import { traceLines } from '../../web/app/view/iteration_trace.js';
import { InputError } from '../../web/lib/errors.js';

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
