// The app's page-free parts of the spectral basis and the volume parts: the painter's parts and colours, the
// basis settings, the saved scene's "subspace" and "volumeParts", and the stats row.
import { describe, expect, it } from 'vitest';
import { PartsPainter, PART_COLORS } from '../../web/app/parts/parts_painter.js';
import { AppSettings, touchesSolver } from '../../web/app/settings.js';
import { savedScene } from '../../web/app/loading/saved_scene.js';
import { panelStats } from '../../web/app/stats_format.js';
import { InputError } from '../../web/lib/errors.js';
import { parseScene } from '../../web/lib/scene.js';

describe('PartsPainter', () => {
  it('paints vertex parts and describes them as vertex lists; unpainted vertices are the rest', () => {
    const painter = new PartsPainter();
    painter.reset(6);
    expect(painter.description()).toBeNull();
    expect(painter.colors()).toBeNull();
    painter.current = 2;
    painter.paint([0, 1]);
    painter.current = 0;
    painter.paint([4, 5]);
    painter.paint([5], 'remove');
    expect(painter.description()).toEqual({ vertices: [[4], [0, 1]] });
    const colors = painter.colors();
    expect(Array.from(colors.slice(0, 3))).toEqual(PART_COLORS[2].map(Math.fround));
    expect(colors).toHaveLength(18);
  });

  it('takes a partition per triangle (auto parts) as vertex parts', () => {
    const painter = new PartsPainter();
    painter.reset(4);
    painter.fromTriangles(new Int32Array([0, 1]), new Uint32Array([0, 1, 2, 1, 3, 2]));
    expect(Array.from(painter.vertexPart)).toEqual([0, 1, 1, 1]);
  });
});

describe('basis and parts settings', () => {
  it('checks the basis, its modes and the auto parts; none of them concerns the solvers', () => {
    const settings = new AppSettings({ basis: 'spectral', spectralModes: 60 });
    expect(settings.values).toMatchObject({ basis: 'spectral', spectralModes: 60, autoParts: 6 });
    expect(() => settings.update({ basis: 'wavelets' })).toThrow(InputError);
    expect(() => settings.update({ spectralModes: 0 })).toThrow(/spectralModes must be an integer from 1 to 300/);
    expect(() => settings.update({ autoParts: 1 })).toThrow(/autoParts must be an integer from 2 to 16/);
    expect(touchesSolver({ basis: 'cage', spectralModes: 10, autoParts: 3 })).toBe(false);
    expect(settings.solverOptions('subspace')).not.toHaveProperty('basis');
  });

  it('saves the spectral basis and the parts in the scene, which parses back', () => {
    const model = { name: 'bar', basis: 'spectral', basisSize: 44, source: { example: 'bar' } };
    const scene = savedScene(model, [], { method: 'subspace' }, { auto: 5 });
    expect(scene).toMatchObject({ example: 'bar', subspace: { basis: 'spectral', modes: 40 }, volumeParts: { auto: 5 } });
    expect(parseScene(scene)).toMatchObject({ subspace: { basis: 'spectral', modes: 40 }, volumeParts: { kind: 'auto', parts: 5 } });
    expect(savedScene({ ...model, basis: 'cage' }, [], {})).not.toHaveProperty('subspace');
  });

  it('shows the parts in the stats: how many and the largest change, or the global volume', () => {
    const base = { state: 'converged', stopReason: '', merit: 1, volumeRelError: 0, iterations: 3, msPerIteration: 1, fps: 60 };
    expect(panelStats({ ...base, partVolumeChange: null }).parts).toBe('global volume');
    expect(panelStats({ ...base, partVolumeChange: [1e-15, -3e-15, 2e-16] }).parts).toBe('3, max 3.0e-13 %');
  });
});
