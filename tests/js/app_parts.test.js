// The app's parts that need no page: its settings (the solver options per method and a scene's "solver"
// both ways, checked and defaulted by the library's options schema), the compare-mode option, the sorting of dropped files and the stats text.
import { describe, expect, it } from 'vitest';
import { AppSettings, DEFAULT_SETTINGS, checkCageSize, touchesSolver } from '../../web/app/settings.js';
import { COMPARE_METHODS, METHODS, compareMethods } from '../../web/app/methods.js';
import { sortFiles } from '../../web/app/loading/files.js';
import { panelStats, statsLine } from '../../web/app/stats_format.js';
import { DEFAULT_OPTIONS, OPTION_NAMES } from '../../web/lib/options.js';
import { InputError } from '../../web/lib/errors.js';

describe('AppSettings', () => {
  it('gives each method its own iteration cap and sends scene-only options only once set', () => {
    const settings = new AppSettings({ maxIterations: 40 });
    expect(settings.solverOptions('subspace').maxIterations).toBe(40);
    expect(settings.solverOptions('arap').maxIterations).toBe(DEFAULT_SETTINGS.arapMaxIterations);
    expect(settings.solverOptions('full')).not.toHaveProperty('cgMemory');
    settings.update({ cgMemory: 8 });
    expect(settings.solverOptions('full').cgMemory).toBe(8);
    // Display settings are no solver options.
    expect(settings.solverOptions('subspace')).not.toHaveProperty('showCage');
  });

  it("maps a scene's maxIterations to the cap of the scene's method, and back", () => {
    for (const method of ['subspace', 'arap']) {
      const solver = { method, maxIterations: 77, c1: 1e-3, arapEnergyTolerance: 1e-6 };
      const settings = new AppSettings(AppSettings.fromScene(solver, 'full'));
      expect(settings.values[method === 'arap' ? 'arapMaxIterations' : 'maxIterations']).toBe(77);
      expect(settings.values[method === 'arap' ? 'maxIterations' : 'arapMaxIterations']).toBe(DEFAULT_SETTINGS[method === 'arap' ? 'maxIterations' : 'arapMaxIterations']);
      expect(settings.toScene(method)).toMatchObject(solver);
    }
    // Without a method, the cap is the current view's.
    expect(AppSettings.fromScene({ maxIterations: 9 }, 'arap')).toEqual({ arapMaxIterations: 9 });
  });

  it('dispatches what changed; only solver settings concern the solvers', () => {
    const settings = new AppSettings();
    const seen = [];
    settings.addEventListener('change', (e) => seen.push(e.changed));
    settings.update({ wireframe: true });
    expect(seen).toEqual([{ wireframe: true }]);
    expect(settings.snapshot().wireframe).toBe(true);
    expect(touchesSolver({ wireframe: true, brushRadius: 0.1, cageVertices: 50 })).toBe(false);
    expect(touchesSolver({ showCage: false, jacobian: 'exact' })).toBe(true);
    expect(touchesSolver({ iterationsPerFrame: 3 })).toBe(true);
  });

  it('accepts cage sizes from 20 to 1000 only', () => {
    expect(() => checkCageSize(20)).not.toThrow();
    expect(() => checkCageSize(1000)).not.toThrow();
    for (const bad of [19, 1001, 50.5, '50', NaN]) expect(() => checkCageSize(bad)).toThrow(/from 20 to 1000/);
  });
});

describe('compareMethods', () => {
  it('reads lists, strings and booleans', () => {
    expect(compareMethods(false)).toBeNull();
    expect(compareMethods(undefined)).toBeNull();
    expect(compareMethods(true)).toEqual(COMPARE_METHODS);
    expect(compareMethods('true')).toEqual(COMPARE_METHODS);
    expect(compareMethods('arap, full')).toEqual(['arap', 'full']);
    expect(compareMethods('subspace|magic')).toEqual(['subspace']);
    expect(compareMethods('magic')).toEqual(COMPARE_METHODS);
    expect(compareMethods(['full', 'nope', 'arap'])).toEqual(['full', 'arap']);
    for (const m of COMPARE_METHODS) expect(METHODS).toContain(m);
  });
});

describe('sortFiles', () => {
  const file = (name) => ({ name });
  it('sorts meshes and scenes by extension, any case', () => {
    const { scenes, meshes } = sortFiles([file('a.OBJ'), file('s.json'), file('c.off'), file('d.ply'), file('e.stl')]);
    expect(scenes.map((f) => f.name)).toEqual(['s.json']);
    expect(meshes.map((f) => f.name)).toEqual(['a.OBJ', 'c.off', 'd.ply', 'e.stl']);
  });

  it('refuses other files, naming them', () => {
    expect(() => sortFiles([file('a.obj'), file('notes.txt'), file('b.glb')])).toThrow(/notes\.txt, b\.glb: unsupported file type/);
  });
});

describe('stats text', () => {
  const stats = { state: 'stopped', stopReason: 'not converged after 100 iterations', merit: 0.00123, volumeRelError: 2e-9,
    iterations: 100, msPerIteration: 3.24, fps: 59.6, vertexCount: 5042, bindMs: 7.4 };

  it('shows the numbers, the state and why a solve stopped', () => {
    const line = statsLine(stats, { loaded: true, requestSize: 4 });
    expect(line.numbers).toBe('merit 1.230e-3   volume change 0.000000%\niterations 100   3.2 ms/iteration   k=4/request');
    expect(line).toMatchObject({ state: 'stopped', label: 'stopped', reason: ': not converged after 100 iterations' });
    expect(panelStats(stats)).toEqual({ status: 'stopped: not converged after 100 iterations', merit: '1.230e-3',
      volume: '0.000000 %', iterations: '100', msPerIteration: '3.24', fps: '60' });
  });

  it('before the first iteration: the model size and bind time, or loading', () => {
    const idle = { ...stats, state: 'idle', iterations: 0 };
    expect(statsLine(idle, { loaded: true, requestSize: 1 })).toMatchObject({ numbers: '5042 vertices, bind 7 ms', label: 'no handles', reason: '' });
    expect(statsLine(idle, { loaded: false, requestSize: 1 }).numbers).toBe('loading\u2026');
    expect(panelStats({ ...stats, state: 'converged' }).status).toBe('converged');
  });
});

describe('AppSettings and the library options schema', () => {
  it("takes the solver defaults from the library's table", () => {
    for (const key of ['method', 'jacobian', 'volume', 'maxIterations', 'positionWeight', 'c1', 'c2']) {
      expect(DEFAULT_SETTINGS[key]).toBe(DEFAULT_OPTIONS[key]);
    }
  });

  it('passes every other option of the table on once set (an option added to the table needs no app edit)', () => {
    const others = OPTION_NAMES.filter((name) => !(name in DEFAULT_SETTINGS));
    expect(others.length).toBeGreaterThan(3);
    const settings = new AppSettings();
    for (const name of others) expect(settings.solverOptions('subspace')).not.toHaveProperty(name);
    settings.update(Object.fromEntries(others.map((name) => [name, DEFAULT_OPTIONS[name]])));
    for (const name of others) expect(settings.solverOptions('subspace')[name]).toBe(DEFAULT_OPTIONS[name]);
  });

  it("refuses a bad solver option with the library's message, changing nothing", () => {
    const settings = new AppSettings();
    expect(() => settings.update({ wireframe: true, c1: 2 })).toThrow(InputError);
    expect(() => settings.update({ c1: 2 })).toThrow(/setOptions: c1 must be a number in \(0, 1\) \(got 2\)/);
    expect(() => settings.update({ method: 'magic' })).toThrow(/setOptions: method must be one of/);
    expect(() => settings.update({ arapMaxIterations: 0 })).toThrow(/arapMaxIterations must be an integer from 1/);
    expect(() => new AppSettings({ jacobian: 'approximate' })).toThrow(/settings: jacobian must be one of/);
    expect(settings.values.wireframe).toBe(false);
    expect(settings.values.c1).toBe(DEFAULT_OPTIONS.c1);
  });
});
