// Volume kept per part through the wasm module (docs/method.md section 16): partitions from lists and
// automatically, every part's volume kept where one global volume lets the middle thin, the statistics per
// part, and the refusals.
import { beforeAll, describe, expect, it } from 'vitest';
import { Deformer, InputError, loadSolver, makeExample, volumeParts } from 'subspace-deform';
import { thrown } from './support/thrown.js';
import { barEnds, endTargets } from './support/bar_ends.js';

let solver, bar, groups, targets;

beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
  const { left, right } = barEnds(bar.mesh);
  groups = [left, right];
  targets = endTargets(bar.mesh, groups, [1.5, -0.6, 0]);  // stretch: the right end pulled away and down
});

// Three slabs along x by vertex lists (the rest: x > 0.8).
function slabLists() {
  const a = [], b = [];
  for (let i = 0; i < bar.mesh.positions.length / 3; ++i) {
    const x = bar.mesh.positions[3 * i];
    if (x < -0.8) a.push(i);
    else if (x < 0.8) b.push(i);
  }
  return [a, b];
}

describe('volume parts (wasm)', () => {
  it('makes partitions from vertex lists, triangle lists and automatically', () => {
    const triangles = bar.mesh.indices.length / 3;
    const fromVertices = volumeParts(solver, bar.mesh, slabLists());
    expect(fromVertices).toBeInstanceOf(Int32Array);
    expect(fromVertices).toHaveLength(triangles);
    expect(new Set(fromVertices)).toEqual(new Set([0, 1, 2]));
    const fromTriangles = volumeParts(solver, bar.mesh, { triangles: [[0, 1, 2]] });
    expect(fromTriangles[0]).toBe(0);
    expect(fromTriangles[3]).toBe(1);
    const auto = volumeParts(solver, bar.mesh, { auto: 4 });
    expect(new Set(auto)).toEqual(new Set([0, 1, 2, 3]));
    expect(volumeParts(solver, bar.mesh, { auto: 4 })).toEqual(auto);  // deterministic
  });

  it('refuses bad descriptions naming the problem', () => {
    expect(thrown(() => volumeParts(solver, bar.mesh, { auto: 0 })).message).toMatch(/auto must be an integer from 1/);
    expect(thrown(() => volumeParts(solver, bar.mesh, { colours: [] })).message).toMatch(/exactly one of "vertices", "triangles" or "auto"/);
    expect(thrown(() => volumeParts(solver, bar.mesh, [[0], []])).message).toMatch(/\[1\] must be a non-empty array/);
    const outside = thrown(() => volumeParts(solver, bar.mesh, [[10000000]]));
    expect(outside).toBeInstanceOf(InputError);
    expect(outside.message).toMatch(/list 0 has vertex 10000000 outside/);
    const d = Deformer.create(solver, bar.mesh, bar.cage);
    try {
      expect(thrown(() => d.setVolumeParts([0, 1]))).toBeInstanceOf(InputError);
      expect(thrown(() => d.setVolumeParts('head'))).toBeInstanceOf(InputError);
      expect(d.volumeParts()).toHaveLength(0);
    } finally {
      d.dispose();
    }
  });

  it.each(['subspace', 'full'])('keeps every part\'s volume to 1e-8 where the global constraint lets one change (%s)', (method) => {
    const parts = volumeParts(solver, bar.mesh, slabLists());
    const d = Deformer.create(solver, bar.mesh, bar.cage);
    try {
      d.setOptions({ method, maxIterations: method === 'full' ? 40 : 100 });
      d.setHandles(groups);
      d.setTargets(targets);
      d.solve();
      d.setVolumeParts(parts);
      const rest = d.restPartVolumes();
      const globalChange = Array.from(d.partVolumes(), (v, k) => (v - rest[k]) / rest[k]);
      expect(Math.max(...globalChange.map(Math.abs))).toBeGreaterThan(0.01);
      d.reset();
      const r = d.solve();
      const last = r.iterations.at(-1);
      expect(last.partVolumeChange).toHaveLength(3);
      expect(last.partLambda).toHaveLength(3);
      for (const change of last.partVolumeChange) expect(Math.abs(change)).toBeLessThanOrEqual(1e-8);
      expect(Math.abs(last.volumeRelError)).toBeLessThanOrEqual(1e-8);
      d.setVolumeParts(null);
      expect(d.volumeParts()).toHaveLength(0);
      expect(d.restPartVolumes()[0]).toBeCloseTo(d.restVolume, 12);
    } finally {
      d.dispose();
    }
  });
});
