// What the app binds for a scene's subspace (web/app/loading/subspace_choice.js), and what it says when it cannot
// take the scene as it is; what a setCoordinates call binds with (the settings' values with its change, given as an
// argument to the binding: the settings take the change only once bound).
import { describe, expect, it } from 'vitest';
import { coordinatesSettings, sceneSubspaceNote, sceneSubspaceSettings, subspaceChoice } from '../../web/app/loading/subspace_choice.js';
import { DEFAULT_SETTINGS, SPECTRAL_MODES_RANGE } from '../../web/app/settings.js';
import { InputError } from '../../web/lib/errors.js';

describe('a scene\'s subspace in the app', () => {
  it('binds at most the app\'s spectral modes and says so when the scene asks for more', () => {
    const max = SPECTRAL_MODES_RANGE.max;
    expect(sceneSubspaceSettings({ basis: 'spectral', modes: 100000 })).toEqual({ basis: 'spectral', spectralModes: max });
    expect(sceneSubspaceNote({ basis: 'spectral', modes: 100000 })).toBe(`The scene asks for 100000 spectral modes; the app binds at most ${max}, so it uses ${max} (the command-line tool and the library take more).`);
    expect(sceneSubspaceSettings({ basis: 'spectral', modes: 40 })).toEqual({ basis: 'spectral', spectralModes: 40 });
    expect(sceneSubspaceNote({ basis: 'spectral', modes: max })).toBeNull();
    expect(sceneSubspaceNote({ basis: 'cage', coordinates: 'pmvc' })).toBeNull();
    expect(sceneSubspaceNote()).toBeNull();
  });
});

describe('setCoordinates\' values', () => {
  it('bind the cage with the type and resolution asked for, over the spectral basis of the settings', () => {
    const settings = { ...DEFAULT_SETTINGS, basis: 'spectral', coordinates: 'mvc', harmonicResolution: 0 };
    const change = coordinatesSettings('harmonic', 48);
    expect(change).toEqual({ basis: 'cage', coordinates: 'harmonic', harmonicResolution: 48 });
    expect(subspaceChoice({ ...settings, ...change })).toEqual({ basis: 'cage', coordinates: 'harmonic', harmonicResolution: 48 });
    expect(subspaceChoice(settings)).toEqual({ basis: 'spectral', modes: DEFAULT_SETTINGS.spectralModes }); // untouched
    expect(coordinatesSettings('mvc', 48)).toEqual({ basis: 'cage', coordinates: 'mvc' }); // mean value has no resolution
  });

  it('are checked as setOptions checks them, before anything binds', () => {
    expect(() => coordinatesSettings('nope')).toThrow(InputError);
    expect(() => coordinatesSettings('nope')).toThrow(/^setOptions: /);
    expect(() => coordinatesSettings('pmvc', -3)).toThrow(InputError);
  });
});
