// Scene files (docs/scene-format.md): validation with errors that name the field, and handle targets.
import { describe, expect, it } from 'vitest';
import { handleTargets, parseScene } from 'subspace-deform';

const base = {
  mesh: 'bar.obj',
  cage: 'bar_cage.obj',
  handles: [{ vertices: [0, 1] }, { vertices: [2], translate: [0, -0.4, 0.2] }],
  solver: { method: 'subspace', jacobian: 'fast', volume: true, maxIterations: 50, positionWeight: 2 },
};

describe('parseScene', () => {
  it('accepts the scene-format example (text or object) and fills defaults', () => {
    for (const input of [JSON.stringify(base), base]) {
      const s = parseScene(input);
      expect(s.mesh).toBe('bar.obj');
      expect(s.cage).toBe('bar_cage.obj');
      expect(s.handles[0]).toEqual({ vertices: [0, 1], translate: [0, 0, 0], rotate: null, moving: false, line: null });
      expect(s.handles[1].translate).toEqual([0, -0.4, 0.2]);
      expect(s.handles[1].moving).toBe(true);
      expect(s.solver).toEqual(base.solver);
    }
    expect(parseScene({ mesh: 'm.obj', handles: [] }).cage).toBeNull();
    expect(parseScene({ example: 'bunny', handles: [] })).toMatchObject({ mesh: null, example: 'bunny', generateCage: null });
    expect(parseScene({ mesh: 'm.obj', generateCage: { vertices: 80 }, handles: [] }).generateCage).toEqual({ vertices: 80 });
  });

  it('reads the subspace basis (cage by default, or spectral with modes) and the volume parts', () => {
    expect(parseScene(base).subspace).toEqual({ basis: 'cage' });
    expect(parseScene(base).volumeParts).toBeNull();
    const s = parseScene({ mesh: 'm.obj', handles: [], subspace: { basis: 'spectral', modes: 40 }, volumeParts: { auto: 5 } });
    expect(s.subspace).toEqual({ basis: 'spectral', modes: 40 });
    expect(s.volumeParts).toEqual({ kind: 'auto', parts: 5 });
    expect(parseScene({ mesh: 'm.obj', handles: [], volumeParts: [[0, 1], [2]] }).volumeParts).toEqual({ kind: 'vertices', lists: [[0, 1], [2]] });
    expect(parseScene({ mesh: 'm.obj', handles: [], volumeParts: { triangles: [[3]] } }).volumeParts).toEqual({ kind: 'triangles', lists: [[3]] });
    for (const volumeParts of [{ kind: 'triangles', lists: [[3]] }, { kind: 'auto', parts: 2 }, { kind: 'global' }]) { // normalised: as it is
      expect(parseScene({ mesh: 'm.obj', handles: [], volumeParts }).volumeParts).toEqual(volumeParts);
    }
  });

  it('reads what the app shows ("view": compared methods, camera direction, paused), refusing bad values by name', () => {
    expect(parseScene(base).view).toBeNull();
    const view = { compare: ['arap', 'subspace'], direction: [-1, -0.35, 0.25], paused: true };
    expect(parseScene({ ...base, view }).view).toEqual(view);
    expect(parseScene({ ...base, view: {} }).view).toEqual({ compare: null, direction: null, paused: false });
    expect(() => parseScene({ ...base, view: { compare: ['arap', 'arap'] } })).toThrow(/view\.compare must be a list of distinct methods/);
    expect(() => parseScene({ ...base, view: { compare: ['ARAP'] } })).toThrow(/view\.compare/);
    expect(() => parseScene({ ...base, view: { direction: [0, 0, 0] } })).toThrow(/view\.direction must be \[x, y, z\], finite and not zero/);
    expect(() => parseScene({ ...base, view: { direction: [1, 2] } })).toThrow(/view\.direction/);
    expect(() => parseScene({ ...base, view: { paused: 'yes' } })).toThrow(/view\.paused must be true or false/);
    expect(() => parseScene({ ...base, view: { zoom: 2 } })).toThrow(/view has unknown field "zoom"/);
    expect(() => parseScene({ ...base, view: [] })).toThrow(/"view" must be/);
  });

  it('reads rotations in radians or degrees and normalises the axis', () => {
    const s = parseScene({ mesh: 'm.obj', handles: [
      { vertices: [0], rotate: { axis: [0, 0, 2], angle: Math.PI / 2 } },
      { vertices: [1], rotate: { axis: [0, 0, 1], degrees: 90, center: [1, 0, 0] } }] });
    expect(s.handles[0].rotate.axis).toEqual([0, 0, 1]);
    expect(s.handles[1].rotate.angle).toBeCloseTo(Math.PI / 2, 15);
    expect(s.handles[1].rotate.center).toEqual([1, 0, 0]);
  });

  it.each([
    ['{ not json', /not valid JSON/],
    [[], /top level must be an object/],
    [{ handles: [] }, /exactly one of "mesh" \(a file path\) or "example"/],
    [{ mesh: 'm.obj', example: 'bar', handles: [] }, /exactly one of "mesh"/],
    [{ mesh: 7, handles: [] }, /"mesh" must be a file path/],
    [{ example: 'bunny', cage: 'c.obj', handles: [] }, /brings its own cage/],
    [{ mesh: 'm.obj', cage: 'c.obj', generateCage: { vertices: 50 }, handles: [] }, /either "cage" or "generateCage"/],
    [{ mesh: 'm.obj', generateCage: { vertices: 2.5 }, handles: [] }, /"generateCage" must be \{ "vertices": K \}/],
    // The generator's limits (CAGE_LIMITS), so no tool starts loading a scene whose cage cannot be made.
    [{ example: 'bar', generateCage: { vertices: 20001 }, handles: [] }, /integer K from 4 to 20000 \(got \{"vertices":20001\}\)/],
    [{ mesh: 'm.obj', generateCage: { vertices: 1e9 }, handles: [] }, /integer K from 4 to 20000/],
    [{ mesh: 'm.obj', generateCage: { vertices: 3 }, handles: [] }, /integer K from 4 to 20000/],
    [{ mesh: 'm.obj', generateCage: null, handles: [] }, /"generateCage" must be \{ "vertices": K \} .*\(got null; leave "generateCage" out for no cage\)/],
    // An unknown field was dropped silently: { vertices: 40, offset: 0.5 } made a cage with the default offset.
    [{ mesh: 'm.obj', generateCage: { vertices: 40, offset: 0.5 }, handles: [] }, /^scene: generateCage has unknown field "offset" \(known: vertices; .*deform\.mjs cage --offset\/--resolution/],
    [{ mesh: 'm.obj', generateCage: { resolution: 64, vertices: 40 }, handles: [] }, /generateCage has unknown field "resolution"/],
    [{ mesh: 'm.obj', generateCage: { vertices: 40, verts: 50 }, handles: [] }, /generateCage has unknown field "verts"/],
    [{ mesh: 'm.obj' }, /"handles" must be an array/],
    [{ mesh: 'm.obj', handles: [{ vertices: [] }] }, /handles\[0\]\.vertices must be a non-empty array/],
    [{ mesh: 'm.obj', handles: [{ vertices: [1.5] }] }, /handles\[0\]\.vertices\[0\] = 1\.5 is not a vertex index/],
    [{ mesh: 'm.obj', handles: [{ vertices: [1] }, { vertices: [1] }] }, /vertex 1 is in handles\[0\] and handles\[1\]/],
    // It said "vertex 0 is in handles[0] and handles[0]".
    [{ mesh: 'm.obj', handles: [{ vertices: [2] }, { vertices: [0, 0, 0] }] }, /^scene: handles\[1\]\.vertices lists vertex 0 more than once$/],
    [{ mesh: 'm.obj', handles: [{ vertices: [1], translate: [0, 1] }] }, /handles\[0\]\.translate must be an array of 3 finite numbers/],
    [{ mesh: 'm.obj', handles: [{ vertices: [1], rotate: { axis: [0, 0, 0], angle: 1 } }] }, /rotate\.axis must not be zero/],
    [{ mesh: 'm.obj', handles: [{ vertices: [1], rotate: { axis: [0, 0, 1] } }] }, /exactly one of "angle" \(radians\) or "degrees"/],
    [{ mesh: 'm.obj', handles: [{ vertices: [1], move: [0, 0, 1] }] }, /handles\[0\] has unknown field "move"/],
    [{ mesh: 'm.obj', handles: [], solver: { method: 'magic' } }, /solver\.method must be one of 'subspace', 'full', 'arap'/],
    [{ mesh: 'm.obj', handles: [], solver: { positionWeight: -1 } }, /solver\.positionWeight must be a number in \(0, 1000000\]/],
    [{ mesh: 'm.obj', handles: [], solver: { maxIters: 3 } }, /solver has unknown field "maxIters"/],
    [{ mesh: 'm.obj', handles: [], extra: 1 }, /unknown field "extra"/],
    [{ mesh: 'm.obj', handles: [], subspace: { basis: 'spectral' } }, /subspace\.modes must be an integer >= 1/],
    [{ mesh: 'm.obj', handles: [], subspace: { basis: 'wavelets', modes: 3 } }, /subspace\.basis must be "cage" or "spectral"/],
    [{ mesh: 'm.obj', handles: [], subspace: { basis: 'cage', modes: 3 } }, /subspace\.modes is for the "spectral" basis/],
    [{ mesh: 'm.obj', handles: [], subspace: { kind: 'cage' } }, /subspace has unknown field "kind"/],
    [{ mesh: 'm.obj', handles: [], volumeParts: { auto: 0 } }, /volumeParts.*auto must be an integer from 1/],
    [{ mesh: 'm.obj', handles: [], volumeParts: [[0], [-1]] }, /volumeParts.*\[1\] must be a non-empty array of indices/],
    [{ mesh: 'm.obj', handles: [], volumeParts: { vertices: [[0]], auto: 2 } }, /exactly one of "vertices", "triangles" or "auto"/],
    // The normalised form (what parseScene returns) took any other field and dropped it.
    [{ mesh: 'm.obj', handles: [], volumeParts: { kind: 'global', lists: [[1]] } }, /^scene: "volumeParts" has unknown field "lists" \(kind 'global' takes no other field\)$/],
    [{ mesh: 'm.obj', handles: [], volumeParts: { kind: 'vertices', lists: [[0, 1, 2]], extra: 5 } }, /"volumeParts" has unknown field "extra" \(kind 'vertices' takes "lists"\)/],
    [{ mesh: 'm.obj', handles: [], volumeParts: { kind: 'auto', parts: 3, lists: [[0]] } }, /unknown field "lists" \(kind 'auto' takes "parts"\)/],
  ])('rejects %j with a message naming the field', (input, pattern) => {
    expect(() => parseScene(input)).toThrow(pattern);
  });
});

describe('handleTargets', () => {
  const rest = new Float64Array([0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 1, 0]);

  it('translates, rotates about the centroid by default or a given center, groups in order', () => {
    const s = parseScene({ mesh: 'm.obj', handles: [
      { vertices: [3], translate: [0, 0, 1] },
      { vertices: [1, 2], rotate: { axis: [0, 0, 1], degrees: 180 } },          // about centroid (1.5, 0, 0)
      { vertices: [0], rotate: { axis: [0, 0, 1], degrees: 90, center: [1, 0, 0] } }] });
    const { groups, targets } = handleTargets(rest, s.handles);
    expect(groups).toEqual([[3], [1, 2], [0]]);
    const expected = [3, 1, 1, 2, 0, 0, 1, 0, 0, 1, -1, 0];
    expected.forEach((x, i) => expect(targets[i]).toBeCloseTo(x, 12));
  });

  it('rejects vertices beyond the mesh', () => {
    const s = parseScene({ mesh: 'm.obj', handles: [{ vertices: [0] }, { vertices: [4] }] });
    expect(() => handleTargets(rest, s.handles)).toThrow(/handles\[1\] uses vertex 4, but the mesh has 4 vertices/);
  });

  it('refuses targets beyond the coordinates a mesh may have, naming the group (1e308 ended in numerical_failure, exit 0)', () => {
    for (const translate of [[1e308, 0, 0], [0, -2e30, 0]]) {
      const s = parseScene({ mesh: 'm.obj', handles: [{ vertices: [0] }, { vertices: [1, 2], translate }] });
      expect(() => handleTargets(rest, s.handles)).toThrow(/^scene: handles\[1\] moves vertex 1 to a coordinate of \d\.\d\de\+\d+, beyond the 1e30 a mesh may have/);
    }
    const turned = parseScene({ mesh: 'm.obj', handles: [{ vertices: [3], rotate: { axis: [0, 0, 1], degrees: 90, center: [2e30, 0, 0] } }] });
    expect(() => handleTargets(rest, turned.handles)).toThrow(/handles\[0\] moves vertex 3 to a coordinate of 2\.00e\+30/);
    const near = parseScene({ mesh: 'm.obj', handles: [{ vertices: [0], translate: [1e29, 0, 0] }] });
    expect(handleTargets(rest, near.handles).targets[0]).toBe(1e29);
  });
});
