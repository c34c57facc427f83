// The parts of solver/scene.js the app uses beyond the CLI's parseScene: a scene without a model (applied to
// the model on screen) and the handles list alone (kept across a new cage), with the same validation.
import { describe, expect, it } from 'vitest';
import { parseScene, parseSceneHandles } from 'subspace-deform';

describe('parseScene with modelOptional', () => {
  it('accepts handles and options without "mesh" or "example"', () => {
    const s = parseScene({ handles: [{ vertices: [4] }], solver: { method: 'arap', arapEnergyTolerance: 1e-6 } }, { modelOptional: true });
    expect(s).toMatchObject({ mesh: null, cage: null, example: null, generateCage: null });
    expect(s.handles).toEqual([{ vertices: [4], translate: [0, 0, 0], rotate: null, moving: false, line: null }]);
    expect(s.solver).toEqual({ method: 'arap', arapEnergyTolerance: 1e-6 });
  });

  it('still rejects a cage without a mesh, both model sources, and bad fields', () => {
    expect(() => parseScene({ cage: 'c.obj', handles: [] }, { modelOptional: true })).toThrow(/need a "mesh"/);
    expect(() => parseScene({ generateCage: { vertices: 50 }, handles: [] }, { modelOptional: true })).toThrow(/need a "mesh"/);
    expect(() => parseScene({ mesh: 'm.obj', example: 'bar', handles: [] }, { modelOptional: true })).toThrow(/exactly one of "mesh"/);
    expect(() => parseScene({ handles: [], solver: { maxIterations: 0 } }, { modelOptional: true })).toThrow(/solver\.maxIterations must be an integer from 1 to 2147483647 \(got 0\)/);
  });

  it('keeps requiring a model by default (the CLI)', () => {
    expect(() => parseScene({ handles: [] })).toThrow(/exactly one of "mesh"/);
  });
});

describe('parseSceneHandles', () => {
  it('gives what parseScene gives for the same list', () => {
    const handles = [{ vertices: [0, 1] }, { vertices: [2], translate: [0, 1, 0], rotate: { axis: [0, 2, 0], degrees: 90 } }];
    expect(parseSceneHandles(handles)).toEqual(parseScene({ mesh: 'm.obj', handles }).handles);
    expect(parseSceneHandles(handles)[1].rotate.axis).toEqual([0, 1, 0]);
  });

  it('marks a group moving when it has a motion, even a zero one (the app keeps its gizmo on it)', () => {
    const handles = [{ vertices: [0] }, { vertices: [1], translate: [0, 0, 0] }, { vertices: [2], rotate: { axis: [1, 0, 0], angle: 0 } }];
    expect(parseSceneHandles(handles).map((h) => h.moving)).toEqual([false, true, true]);
  });

  it('rejects a non-list and a vertex in two groups, naming the entry', () => {
    expect(() => parseSceneHandles({ vertices: [1] })).toThrow(/"handles" must be an array/);
    expect(() => parseSceneHandles([{ vertices: [1] }, { vertices: [3, 1] }])).toThrow(/vertex 1 is in handles\[0\] and handles\[1\]/);
  });
});
