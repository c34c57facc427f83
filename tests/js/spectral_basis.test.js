// The cage-free spectral subspace through the wasm module (docs/method.md section 15): a session without a
// cage, the rest pose kept, a volume-preserving bend, the basis' size and eigenvalues, and its refusals.
import { beforeAll, describe, expect, it } from 'vitest';
import { CancelledError, Deformer, InputError, SolverError, loadSolver, makeExample } from 'subspace-deform';
import { thrown } from './support/thrown.js';
import { barEnds, endTargets } from './support/bar_ends.js';

let solver, bar, groups;

beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
  const { left, right } = barEnds(bar.mesh);
  groups = [left, right];
});

const targets = (move) => endTargets(bar.mesh, groups, move);

function maxDistance(a, b) {
  let worst = 0;
  for (let i = 0; i < a.length; i += 3) worst = Math.max(worst, Math.hypot(a[i] - b[i], a[i + 1] - b[i + 1], a[i + 2] - b[i + 2]));
  return worst;
}

describe('spectral basis (wasm)', () => {
  it('deforms a mesh without a cage: rest pose kept, the bend keeps the volume', () => {
    const d = Deformer.create(solver, bar.mesh, null, { basis: 'spectral', modes: 24 });
    try {
      expect(d.basis).toBe('spectral');
      expect(d.basisSize).toBe(28);
      expect(d.options().method).toBe('subspace');
      const lambda = d.basisEigenvalues();
      expect(lambda).toHaveLength(25);
      expect(Math.abs(lambda[0])).toBeLessThan(1e-8 * lambda[24]);
      for (let j = 1; j < 25; ++j) expect(lambda[j]).toBeGreaterThanOrEqual(lambda[j - 1]);
      d.setHandles(groups);
      d.setTargets(targets([0, 0, 0]));
      expect(d.solve().converged).toBe(true);
      expect(maxDistance(d.positions(), bar.mesh.positions)).toBeLessThanOrEqual(1e-10);
      d.setTargets(targets([0, -1.0, 0.3]));
      const r = d.solve();
      expect(r.converged).toBe(true);
      expect(Math.abs(r.iterations.at(-1).volumeRelError)).toBeLessThanOrEqual(1e-8);
      expect(maxDistance(d.positions(), bar.mesh.positions)).toBeGreaterThan(0.5);
      expect(d.subspaceCoefficients()).toHaveLength(3 * 28);
      expect(d.cagePositions()).toHaveLength(0);
    } finally {
      d.dispose();
    }
  });

  it('refuses a missing or bad modes count, too much memory, and stops when cancelled', () => {
    expect(thrown(() => Deformer.create(solver, bar.mesh, null, { basis: 'spectral' }))).toBeInstanceOf(InputError);
    expect(thrown(() => Deformer.create(solver, bar.mesh, null, { basis: 'wavelets', modes: 3 })).message).toMatch(/basis must be 'cage' or 'spectral'/);
    expect(thrown(() => Deformer.create(solver, bar.mesh, bar.cage, { modes: 3 })).message).toMatch(/modes is for the 'spectral' basis/);
    const tooMany = thrown(() => Deformer.create(solver, bar.mesh, null, { basis: 'spectral', modes: 100000 }));
    expect(tooMany).toBeInstanceOf(InputError);
    expect(tooMany.message).toMatch(/number of modes must be from 1 to/);
    const memory = thrown(() => Deformer.create(solver, bar.mesh, null, { basis: 'spectral', modes: 200, memoryBudgetMB: 1 }));
    expect(memory).toBeInstanceOf(SolverError);
    expect(memory.code).toBe('memory_budget');
    expect(memory.message).toMatch(/MB/);
    const cancelled = thrown(() => Deformer.create(solver, bar.mesh, null, { basis: 'spectral', modes: 24, onProgress: (f) => f < 0.2 }));
    expect(cancelled).toBeInstanceOf(CancelledError);
  });
});
