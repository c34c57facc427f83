// The Deformer session through the wasm module: rest pose, a volume-preserving bend, warm-started steps,
// readable errors (from the JS checks and from C++), and disposal.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { CancelledError, Deformer, InputError, MeshError, STOP_CODES, loadSolver, makeExample } from 'subspace-deform';
import { thrown } from './support/thrown.js';
import { barEnds, endTargets as restTargets } from './support/bar_ends.js';

let solver;
let bar; // { mesh, cage }: ~5k-vertex capsule in a 28-vertex bar cage
let ends; // { left: number[], right: number[] } vertex indices of the two caps

beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
  ends = barEnds(bar.mesh);
});

function maxDistance(a, b) {
  let worst = 0;
  for (let i = 0; i < a.length; i += 3) worst = Math.max(worst, Math.hypot(a[i] - b[i], a[i + 1] - b[i + 1], a[i + 2] - b[i + 2]));
  return worst;
}

const BBOX = Math.hypot(5, 1, 1); // the bar's bounding-box diagonal, about

describe('Deformer (wasm)', () => {
  let d;
  beforeAll(() => {
    d = Deformer.create(solver, bar.mesh, bar.cage);
  });
  afterAll(() => d.dispose());

  it('binds W and reports the session', () => {
    expect(d.vertexCount).toBe(bar.mesh.positions.length / 3);
    expect(d.bindMs).toBeGreaterThan(0);
    expect(d.restVolume).toBeGreaterThan(0);
    expect(d.fallbackCount).toBeGreaterThanOrEqual(0);
    expect(d.options()).toMatchObject({ method: 'subspace', jacobian: 'fast', volume: true });
  });

  it.each(['fast', 'exact'])('keeps the rest pose when the targets are at rest (%s)', (jacobian) => {
    const groups = [ends.left, ends.right];
    d.setOptions({ method: 'subspace', jacobian });
    d.setHandles(groups);
    d.setTargets(restTargets(bar.mesh, groups));
    const r = d.solve();
    expect(r.converged).toBe(true);
    expect(maxDistance(d.positions(), bar.mesh.positions)).toBeLessThanOrEqual(1e-10 * BBOX);
  });

  it('never reports targets 1e20 away as converged: the stop is stalled and the volume kept', () => {
    const groups = [ends.left, ends.right];
    d.setOptions({ method: 'subspace', jacobian: 'fast', volume: true });
    d.reset();
    d.setHandles(groups);
    d.setTargets(restTargets(bar.mesh, groups, [1e20, 0, 0]));
    const r = d.solve();
    expect(r.converged).toBe(false);
    expect(r.stop).toBe('stalled');
    expect(STOP_CODES.find((c) => c.name === 'stalled').converged).toBe(false);
    for (const it of r.iterations) expect(Math.abs(it.volumeRelError)).toBeLessThanOrEqual(1e-9);
    expect(d.positions().every(Number.isFinite)).toBe(true);
    d.reset();
  });

  it('reduced integration: fitted on first use, reported, and close to the full solve', () => {
    const groups = [ends.left, ends.right];
    d.setOptions({ method: 'subspace', jacobian: 'fast', volume: true, integration: 'full' });
    d.reset();
    d.setHandles(groups);
    d.setTargets(restTargets(bar.mesh, groups, [0, -1.0, 0.3]));
    expect(d.solve().converged).toBe(true);
    const full = d.positions();
    expect(d.reducedIntegration().fitted).toBe(false);
    d.setOptions({ integration: 'reduced' });
    d.reset();
    const r = d.solve();
    expect(r.converged).toBe(true);
    const info = d.reducedIntegration();
    expect(info).toMatchObject({ fitted: true, rule: 'clusters', candidates: bar.mesh.positions.length / 3 });
    expect(info.samples).toBeGreaterThan(100);
    expect(info.testError).toBeLessThan(0.1);
    expect(r.iterations[0]).toMatchObject({ samples: info.samples, finishing: false });
    expect(r.iterations.at(-1)).toMatchObject({ samples: 0, finishing: true }); // on every vertex (method.md 17.3)
    expect(maxDistance(d.positions(), full)).toBeLessThan(2e-5 * BBOX); // the rule alone: about 1e-4
    expect(d.fullEnergy()).toBeGreaterThan(0);
    expect(() => d.setOptions({ integration: 'sampled' })).toThrow(/integration must be one of 'full', 'reduced'/);
    d.setOptions({ integration: 'full' });
    d.reset();
  });

  it('prepareFactor makes the factor preconditioner\'s parts before the solve that buys it, changing no result', () => {
    const groups = [ends.left, ends.right];
    const solveWith = (options, prepare) => {
      const e = Deformer.create(solver, bar.mesh, bar.cage);
      try {
        e.setOptions({ cgTolerance: 1e-8, ...options }); // runs long enough to buy the factor
        e.setHandles(groups);
        e.setTargets(restTargets(bar.mesh, groups, [0, -1.0, 0.3]));
        if (prepare) e.prepareFactor();
        const r = e.solve();
        return { positions: Array.from(e.positions()), products: r.iterations.map((it) => it.products) };
      } finally {
        e.dispose();
      }
    };
    const lazy = solveWith({ preconditioner: 'gauss-newton' }, false);
    const prepared = solveWith({ preconditioner: 'gauss-newton' }, true);
    expect(prepared.products).toEqual(lazy.products);
    expect(prepared.positions).toEqual(lazy.positions);
    // The factor was bought: with the constant preconditioner alone the runs differ.
    expect(solveWith({ preconditioner: 'constant' }, true).products).not.toEqual(lazy.products);
  });

  it('records each iteration\'s line search for stepping through a solve', () => {
    const groups = [ends.left, ends.right];
    d.setOptions({ method: 'subspace', jacobian: 'fast', volume: true });
    d.reset();
    d.setHandles(groups);
    d.setTargets(restTargets(bar.mesh, groups, [0, -1.0, 0.3]));
    const { c1, c2 } = d.options();
    const moved = d.solve().iterations.filter((it) => it.alpha > 0);
    expect(moved.length).toBeGreaterThan(0);
    for (const it of moved) {
      expect(it.lineSearch.length).toBe(it.lineSearchTrials);
      expect(it.slope).toBeLessThan(0);
      it.lineSearch.forEach((trial, t) => expect(trial.alpha).toBeCloseTo(c2 ** t, 15));
      const accepted = it.lineSearch.at(-1);
      expect(accepted).toMatchObject({ alpha: it.alpha, sufficientDecrease: true, restored: true });
      expect(accepted.merit).toBeLessThanOrEqual(it.meritStart + c1 * it.alpha * it.slope);
    }
    d.reset();
  });

  it('bends while conserving the volume to 1e-8, the merit never increasing', () => {
    const groups = [ends.left, ends.right];
    d.setOptions({ method: 'subspace', jacobian: 'fast', volume: true });
    d.reset();
    d.setHandles(groups);
    d.setTargets(restTargets(bar.mesh, groups, [0, -1.0, 0.3]));
    const r = d.solve();
    expect(r.converged).toBe(true);
    expect(r.stopReason).toMatch(/^converged/);
    const last = r.iterations.at(-1);
    expect(Math.abs(last.volumeRelError)).toBeLessThanOrEqual(1e-8);
    for (let k = 1; k < r.iterations.length; ++k) {
      expect(r.iterations[k].merit).toBeLessThanOrEqual(r.iterations[k - 1].merit * (1 + 1e-12));
    }
    for (const key of ['iteration', 'merit', 'energy', 'laplacianEnergy', 'positionEnergy', 'straightnessEnergy', 'volume', 'volumeRelError', 'lambda', 'step', 'lineSearchTrials', 'innerIterations', 'products', 'ms']) {
      expect(typeof last[key]).toBe('number');
    }
    const positions = d.positions();
    expect(positions).toBeInstanceOf(Float64Array);
    expect(maxDistance(positions, bar.mesh.positions)).toBeGreaterThan(0.5);
    expect(positions.every(Number.isFinite)).toBe(true);
    expect(maxDistance(d.cagePositions(), bar.cage.positions)).toBeGreaterThan(0.1);
  });

  it('warm-started single steps continue from the last positions', () => {
    const before = d.positions();
    const groups = [ends.left, ends.right];
    d.setTargets(restTargets(bar.mesh, groups, [0, -1.05, 0.3]));
    const r = d.step(1);
    expect(r.iterations).toHaveLength(1);
    expect(r.iterations[0].iteration).toBeGreaterThan(1); // counted since the reset
    expect(maxDistance(d.positions(), before)).toBeLessThan(0.2);
  });

  it('ARAP stops when its energy stops decreasing, by the arapEnergyTolerance given', () => {
    const groups = [ends.left, ends.right];
    d.setOptions({ method: 'arap', maxIterations: 200, arapEnergyTolerance: 1e-3 });
    d.setHandles(groups);
    d.setTargets(restTargets(bar.mesh, groups, [0, -0.4, 0]));
    const loose = d.solve();
    expect(loose.converged).toBe(true);
    expect(loose.stopReason).toMatch(/ARAP energy stopped decreasing/);
    d.setOptions({ arapEnergyTolerance: 0 }); // never by energy: only the step rule or the cap
    d.reset();
    const strict = d.solve();
    expect(strict.iterations.length).toBeGreaterThan(loose.iterations.length);
    expect(d.options().arapEnergyTolerance).toBe(0);
    for (let k = 1; k < strict.iterations.length; ++k) {
      expect(strict.iterations[k].energy).toBeLessThanOrEqual(strict.iterations[k - 1].energy * (1 + 1e-12));
    }
    d.setOptions({ method: 'subspace', maxIterations: 100, arapEnergyTolerance: 1e-5 });
  });

  it('cgMemory (preconditioner pairs) changes the product count, not the minimizer', () => {
    const groups = [ends.left, ends.right];
    d.setOptions({ method: 'subspace', jacobian: 'fast', cgMemory: 0 });
    d.setHandles(groups);
    d.setTargets(restTargets(bar.mesh, groups, [0, -0.6, 0.2]));
    const products = (r) => r.iterations.reduce((sum, it) => sum + it.products, 0);
    const plain = d.solve();
    const plainPositions = d.positions();
    d.setOptions({ cgMemory: 16 });
    d.reset();
    const learned = d.solve();
    expect(d.options().cgMemory).toBe(16);
    expect(plain.converged && learned.converged).toBe(true);
    expect(learned.iterations.at(-1).energy).toBeCloseTo(plain.iterations.at(-1).energy, 9);
    expect(maxDistance(d.positions(), plainPositions)).toBeLessThan(1e-6);
    expect(products(learned)).toBeLessThanOrEqual(products(plain));
    expect(() => d.setOptions({ cgMemory: -1 })).toThrow(/cgMemory must be an integer from 0 to 500 \(got -1\)/);
    expect(() => d.setOptions({ cgMemory: 501 })).toThrow(/cgMemory must be an integer from 0 to 500/);
    expect(d.options().cgMemory).toBe(16);
  });

  it('cageRegularization (default 1e-3) is part of the merit, reported per iteration, and validated', () => {
    const groups = [ends.left, ends.right];
    expect(d.options().cageRegularization).toBe(1e-3);
    d.setHandles(groups);
    d.setTargets(restTargets(bar.mesh, groups, [0, -1.0, 0.3]));
    const bend = (cageRegularization) => {
      d.setOptions({ cageRegularization });
      d.reset();
      const r = d.solve();
      expect(r.converged).toBe(true);
      return { last: r.iterations.at(-1), positions: d.positions() };
    };
    const on = bend(1e-2);
    // merit = E + R + lambda g, with g = volume - rest volume (1e-12 of the merit: rounding of the sum).
    const { merit, energy, regularizationEnergy, lambda, volume } = on.last;
    expect(regularizationEnergy).toBeGreaterThan(0);
    expect(Math.abs(merit - (energy + regularizationEnergy + lambda * (volume - d.restVolume)))).toBeLessThan(1e-12 * merit);
    const off = bend(0);
    expect(off.last.regularizationEnergy).toBe(0);
    // The bar's cage moves its whole mesh: the term leaves the result where it was (docs/method.md 6.1).
    expect(maxDistance(on.positions, off.positions)).toBeLessThan(1e-4 * BBOX);
    expect(() => d.setOptions({ cageRegularization: 1.5 })).toThrow(/cageRegularization must be a number in \[0, 1\] \(got 1.5\)/);
    expect(() => d.setOptions({ cageRegularization: -1e-3 })).toThrow(/cageRegularization must be/);
    d.setOptions({ cageRegularization: 1e-3 });
  });

  it('arapAcceleration (Anderson depth, default 5) cuts ARAP iterations and is validated', () => {
    const groups = [ends.left, ends.right];
    expect(d.options().arapAcceleration).toBe(5);
    d.setHandles(groups);
    d.setTargets(restTargets(bar.mesh, groups, [0, -1.0, 0.3]));
    const iterationsWith = (depth) => {
      d.setOptions({ method: 'arap', maxIterations: 1000, arapAcceleration: depth });
      d.reset();
      const r = d.solve();
      expect(r.converged).toBe(true);
      return r;
    };
    const plain = iterationsWith(0);
    const accelerated = iterationsWith(5);
    expect(accelerated.iterations.length).toBeLessThan(plain.iterations.length / 2);
    expect(accelerated.iterations.at(-1).energy).toBeLessThanOrEqual(plain.iterations.at(-1).energy * (1 + 1e-3));
    expect(() => d.setOptions({ arapAcceleration: 1.5 })).toThrow(/arapAcceleration must be an integer from 0 to 50 \(got 1.5\)/);
    expect(() => d.setOptions({ arapAcceleration: 51 })).toThrow(/arapAcceleration must be an integer from 0 to 50/);
    d.setOptions({ method: 'subspace', maxIterations: 100 });
  });

  it('rejects bad arguments with messages naming them, leaving the session usable', () => {
    const n = d.vertexCount;
    // Handle and target rules are the C++ session's (one source): InputErrors with code invalid_argument.
    expect(() => d.setHandles([[0, 1], []])).toThrow(/^handles: group 1 is empty$/);
    expect(() => d.setHandles([[0, 1], [2, 1.5]])).toThrow(/^handles: group 1 has a non-integer vertex index 1\.5$/);
    expect(() => d.setHandles([[-1]])).toThrow(new RegExp(`^handles: group 0 has vertex -1 outside \\[0, ${n}\\)$`));
    expect(() => d.setHandles([[2 ** 31]])).toThrow(/^handles: group 0 has vertex 2147483648, beyond what an int holds$/);
    expect(() => d.setHandles([[7, 7]])).toThrow(/^handles: vertex 7 appears twice in group 0$/);
    expect(() => d.setHandles([[0, n]])).toThrow(new RegExp(`vertex ${n} outside \\[0, ${n}\\)`));
    expect(() => d.setHandles([[3, 4], [5, 4]])).toThrow(/vertex 4 is in both group 0 and group 1/);
    expect(() => d.setHandles('0,1')).toThrow(/array/);
    expect(() => d.setTargets(new Float64Array(5))).toThrow(/targets: length 5 is not a multiple of 3/);
    expect(() => d.setTargets([0, 0, 0])).toThrow(/Float64Array/);
    expect(() => d.setOptions({ method: 'magic' })).toThrow(/method must be one of/);
    expect(() => d.setOptions({ maxIters: 3 })).toThrow(/unknown option 'maxIters'/);
    expect(() => d.step(-1)).toThrow(/k must be an integer from 0 to 2147483647 \(got -1\)/);
    expect(() => d.step(2 ** 31)).toThrow(/k must be an integer from 0 to 2147483647 \(got 2147483648\)/);
    expect(() => d.setHandles('0,1')).toThrow(InputError);
    expect(d.step(1).iterations.length).toBeLessThanOrEqual(1);
  });

  it('takes typed arrays as handle groups; the session checks the targets\' count and values', () => {
    const session = Deformer.create(solver, bar.mesh, bar.cage);
    session.setHandles([[0], new Int32Array([5, 6])]);
    expect(session.handleCount).toBe(3);
    expect(() => session.setTargets(new Float64Array(3))).toThrow(/^targets: 1 rows \(3 numbers\) for 3 handle vertices \(expected 9 numbers\)$/);
    const targets = new Float64Array(9);
    targets[4] = NaN;
    expect(() => session.setTargets(targets)).toThrow(/^targets: the target of handle vertex 5 \(row 1\) is not finite$/);
    expect(thrown(() => session.setTargets(targets))).toMatchObject({ name: 'InputError', code: 'invalid_argument' });
    session.dispose();
  });

  // Targets of 1e200 or 1e300 were taken: the solve then overflowed, stopped with numerical_failure and
  // handleDistances() gave Infinity. A scene refuses them (above MAX_MESH_COORDINATE); the library the same way.
  it('refuses targets beyond MAX_MESH_COORDINATE (1e30), worded as a scene refuses them', () => {
    const session = Deformer.create(solver, bar.mesh, bar.cage);
    session.setHandles([[0], [5, 6]]);
    for (const far of [1e300, -1e200, 1.5e30]) {
      const targets = new Float64Array(9);
      targets[7] = far;
      const error = thrown(() => session.setTargets(targets));
      expect(error).toMatchObject({ name: 'InputError', code: 'invalid_argument' });
      expect(error.message).toBe(`setTargets: target row 2 has a coordinate of ${Math.abs(far).toPrecision(3)}, beyond the 1e30 a mesh ` +
        'may have (volumes would overflow): use a smaller target, or rescale the model');
    }
    const targets = new Float64Array(9);
    targets[7] = 1e30; // the limit itself is a coordinate a mesh may have
    session.setTargets(targets);
    session.dispose();
  });

  it('turns C++ errors into typed JS errors carrying the code and the message', () => {
    expect(() => d.setOptions({ positionWeight: -1 })).toThrow(/positionWeight must be a number in \(0, 1000000\]/);
    // The same limit holds at the C++ boundary (the raw session, past the JS check).
    expect(() => d._session.setOptions({ positionWeight: -1 })).toThrow(/positionWeight must be a number in \(0, 1000000\] \(got -1\)/);
    expect(d.options().positionWeight).toBe(1);
    const shifted = bar.cage.positions.slice();
    for (let i = 0; i < shifted.length; i += 3) shifted[i] += 1.0;
    const outside = thrown(() => Deformer.create(solver, bar.mesh, { positions: shifted, indices: bar.cage.indices }));
    expect(outside).toBeInstanceOf(MeshError);
    expect(outside.code).toBe('mesh_outside_cage');
    expect(outside.message).toMatch(/outside/);
    expect(outside.findings.map((f) => f.code)).toContain('outside_cage');
    const noCage = Deformer.create(solver, bar.mesh, null);
    try {
      expect(noCage.options().method).toBe('full');
      const needsCage = thrown(() => noCage.setOptions({ method: 'subspace' }));
      expect(needsCage).toBeInstanceOf(InputError);
      expect(needsCage.code).toBe('no_cage');
      expect(needsCage.message).toMatch(/needs a cage/);
    } finally {
      noCage.dispose();
    }
  });

  it('reports the quality of its cage, and a session without a cage or with the spectral basis says it has none', () => {
    const q = d.cageQuality();
    expect(q.cageVertices).toBe(bar.cage.positions.length / 3);
    expect(q.weakVertices).toBe(0);
    expect(q.minColumnMax).toBeGreaterThan(1e-3);
    expect(q.influenceRatio).toBeGreaterThan(1e-6);
    expect(q.influenceRatio).toBeLessThanOrEqual(1);
    expect(q.sampledRows).toBe(d.vertexCount); // 5042 rows: fewer than the 8192 sampled at most
    expect(q).toMatchObject({ poor: false, warnings: [] });
    const noCage = Deformer.create(solver, bar.mesh, null);
    try {
      const error = thrown(() => noCage.cageQuality());
      expect(error).toBeInstanceOf(InputError);
      expect(error.code).toBe('no_cage');
    } finally {
      noCage.dispose();
    }
    // The spectral basis does not use the cage it is given: there is no cage quality to report.
    const spectral = Deformer.create(solver, bar.mesh, bar.cage, { basis: 'spectral', modes: 8 });
    try {
      expect(thrown(() => spectral.cageQuality()).code).toBe('no_cage');
    } finally {
      spectral.dispose();
    }
  });

  it('says why each call returned with a stop code beside the text', () => {
    const known = new Map(STOP_CODES.map((s) => [s.name, s]));
    d.setOptions({ method: 'subspace', jacobian: 'fast', maxIterations: 100 });
    d.setHandles([]);
    expect(d.step(0)).toMatchObject({ stop: 'no_iterations', converged: false, stopReason: 'no iterations requested' });
    expect(d.solve()).toMatchObject({ stop: 'no_handles', converged: true });
    const groups = [ends.left, ends.right];
    d.setHandles(groups);
    d.setTargets(restTargets(bar.mesh, groups, [0, -0.6, 0.2]));
    d.reset();
    const one = d.step(1);
    expect(one).toMatchObject({ stop: 'iteration_limit', converged: false });
    d.setOptions({ maxIterations: 2 });
    d.reset();
    expect(d.solve()).toMatchObject({ stop: 'max_iterations', converged: false, stopReason: 'max iterations' });
    d.setOptions({ maxIterations: 100 });
    const done = d.solve();
    expect(done.converged).toBe(true);
    expect(known.get(done.stop)).toMatchObject({ converged: true });
    expect(done.stopReason).toMatch(/^converged/);
    d.setOptions({ method: 'arap', maxIterations: 1000 });
    expect(['arap_energy', 'step_tolerance']).toContain(d.solve().stop);
    d.setOptions({ method: 'subspace', maxIterations: 100 });
  });
});

describe('Deformer lifetime', () => {
  it('dispose frees the session; later calls throw; dispose twice is fine', () => {
    const d = Deformer.create(solver, bar.mesh, bar.cage);
    d.dispose();
    expect(d.disposed).toBe(true);
    expect(() => d.positions()).toThrow(/disposed/);
    expect(() => d.dispose()).not.toThrow();
  });

  it('validates create() arguments before entering wasm', () => {
    expect(() => Deformer.create({}, bar.mesh, bar.cage)).toThrow(/loaded wasm module/);
    expect(() => Deformer.create(solver, { positions: [0, 0, 0], indices: new Uint32Array(3) }, null)).toThrow(/Float64Array/);
    expect(() => Deformer.create(solver, { positions: new Float64Array(9), indices: new Uint32Array([0, 1, 7]) }, null)).toThrow(/uses vertex 7/);
    expect(() => Deformer.create(solver, bar.mesh, bar.cage, { memoryBudgetMB: -3 })).toThrow(/memoryBudgetMB/);
  });

  it('refuses an oversized W before checking the pair (that check takes a minute on large models)', () => {
    // The cage shifted off the mesh AND a budget too small for W: the budget is what is reported.
    const shifted = bar.cage.positions.map((x, i) => (i % 3 === 0 ? x + 1 : x));
    expect(() => Deformer.create(solver, bar.mesh, { positions: shifted, indices: bar.cage.indices }, { memoryBudgetMB: 0.01 }))
      .toThrow(/over the memory budget of 0\.01 MB/);
  });

  it('reports binding progress and cancels when onProgress returns false', () => {
    const seen = [];
    const d = Deformer.create(solver, bar.mesh, bar.cage, { onProgress: (f) => { seen.push(f); } });
    d.dispose();
    expect(seen.length).toBeGreaterThan(0);
    const cancelled = thrown(() => Deformer.create(solver, bar.mesh, bar.cage, { onProgress: () => false }));
    expect(cancelled).toBeInstanceOf(CancelledError);
    expect(cancelled.code).toBe('cancelled');
    expect(cancelled.message).toMatch(/cancel/);
  });
});
