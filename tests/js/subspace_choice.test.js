// What the app binds for a scene's subspace (web/app/loading/subspace_choice.js), and what it says when it cannot
// take the scene as it is.
import { describe, expect, it } from 'vitest';
import { sceneSubspaceNote, sceneSubspaceSettings } from '../../web/app/loading/subspace_choice.js';
import { SPECTRAL_MODES_RANGE } from '../../web/app/settings.js';

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
