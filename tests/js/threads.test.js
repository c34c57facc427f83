// Threads in Node: the threaded build (Node's default) and the single-threaded one solve the same bend to
// the same bits, with 1, 2 and 4 threads, in every method (every parallel kernel of the core combines fixed
// blocks in a fixed order: cpp/core/parallel/parallel_for.h). Also the thread-count API and its errors, and
// the typed errors of the threaded build, including ones thrown on a pool thread (web/lib/errors.js).
import { availableParallelism } from 'node:os';
import { beforeAll, describe, expect, it } from 'vitest';
import {
  CancelledError, Deformer, InputError, MeshError, SolverError, computeWeights, loadSolver, makeExample, maxThreads, parseThreads,
  typedError,
} from 'subspace-deform';
import { thrown } from './support/thrown.js';

let threaded; // the threaded build with a pool of 4 threads
let single;
let bar; // ~5k-vertex capsule in a 28-vertex bar cage (the blocks of every kernel split it)

beforeAll(async () => {
  threaded = await loadSolver({ build: 'threads', threads: 4 });
  single = await loadSolver({ build: 'single' });
  bar = makeExample(threaded, 'bar');
});

function bend(solver, options) {
  const d = Deformer.create(solver, bar.mesh, bar.cage);
  try {
    const p = bar.mesh.positions;
    const left = [], right = [];
    for (let i = 0; i < p.length / 3; ++i) {
      if (p[3 * i] < -2.2) left.push(i);
      if (p[3 * i] > 2.2) right.push(i);
    }
    d.setOptions({ maxIterations: 6, ...options });
    d.setHandles([left, right]);
    const targets = new Float64Array(3 * (left.length + right.length));
    [...left, ...right].forEach((v, row) => {
      const moved = row >= left.length;
      targets[3 * row] = p[3 * v];
      targets[3 * row + 1] = p[3 * v + 1] + (moved ? -0.9 : 0);
      targets[3 * row + 2] = p[3 * v + 2] + (moved ? 0.3 : 0);
    });
    d.setTargets(targets);
    const r = d.solve();
    return {
      positions: d.positions(),
      energies: r.iterations.map((it) => it.energy),
      products: r.iterations.map((it) => it.products),
      stop: r.stop,
      stopReason: r.stopReason,
    };
  } finally {
    d.dispose();
  }
}

const METHODS = [
  { method: 'subspace', jacobian: 'fast' },
  { method: 'subspace', jacobian: 'exact' },
  { method: 'full', jacobian: 'fast' },
  { method: 'arap' },
];

describe('threads (Node)', () => {
  it('Node loads the threaded build with every core unless told otherwise', async () => {
    const solver = await loadSolver();
    expect(solver.build).toBe(process.env.SD_WASM_BUILD ?? 'threads');
    if (solver.build === 'threads' && !process.env.SD_THREADS) expect(solver.threads()).toBe(availableParallelism());
    expect(threaded.threadsSupported()).toBe(true);
    expect(threaded.threads()).toBe(4);
    expect(single.threadsSupported()).toBe(false);
    expect(single.threads()).toBe(1);
  });

  it('setThreads returns the count in effect: at most the pool, 1 without threads', () => {
    expect(threaded.setThreads(2)).toBe(2);
    expect(threaded.setThreads(64)).toBe(4); // the pool was started with 4
    expect(single.setThreads(8)).toBe(1);
    for (const bad of [-1, 2.5, NaN, '3', undefined]) {
      expect(() => threaded.setThreads(bad)).toThrow(/whole number from 0/);
      expect(thrown(() => threaded.setThreads(bad)).code).toBe('invalid_argument');
    }
    const bad = thrown(() => parseThreads('x', '--threads'));
    expect(bad).toBeInstanceOf(InputError);
    expect(bad.message).toMatch(/--threads must be a whole number/);
    expect(thrown(() => loadSolver({ threads: -2 }))).toBeInstanceOf(InputError);
    expect(thrown(() => loadSolver({ build: 'fast' })).message).toMatch(/build must be "threads" or "single"/);
  });

  // setThreads(-1) threw the binding's plain Error, unlike every other entry of the library.
  it('setThreads refuses a bad count with an InputError in both builds', () => {
    for (const solver of [threaded, single]) {
      for (const bad of [-1, 1.5, '3', null]) expect(thrown(() => solver.setThreads(bad))).toBeInstanceOf(InputError);
    }
    threaded.setThreads(4);
  });

  // parseThreads converted anything Number() does: true -> 1, false and null -> 0, [2] -> 2, "0x2" -> 2, "1e0" -> 1.
  it('parseThreads takes whole numbers and decimal digits only', () => {
    expect([3, '3', '0', 0, '16'].map((value) => parseThreads(value))).toEqual([3, 3, 0, 0, 16]);
    for (const bad of [true, false, null, [2], '0x2', '1e0', ' 2 ', '', '-1', '2.0', 2.5]) {
      const error = thrown(() => parseThreads(bad, '--threads'));
      expect(error, JSON.stringify(bad)).toBeInstanceOf(InputError);
      expect(error.message).toMatch(/^--threads must be a whole number from 0 \(every core\) to \d+/);
    }
  });

  // 64 threads on a 2-core machine took 13.5 s and 654 MB to start, 160 took 1.46 GB: the pool starts them all.
  it('refuses more than 4 threads per core (at least 16) before starting any', () => {
    expect([1, 2, 8, 64, 1000].map((cores) => maxThreads(cores))).toEqual([16, 16, 32, 256, 1024]);
    const most = maxThreads();
    expect(most).toBe(Math.min(1024, Math.max(16, 4 * availableParallelism())));
    expect(parseThreads(String(most))).toBe(most);
    const error = thrown(() => loadSolver({ threads: most + 1 }));
    expect(error).toBeInstanceOf(InputError);
    expect(error.message).toBe(`threads must be a whole number from 0 (every core) to ${most} (4 per core, at least 16: ` +
      `more threads than cores only cost start-up time and memory), not ${most + 1}`);
  });

  it.each(METHODS)('1, 2 and 4 threads and the single-threaded build give bit-identical solves (%o)', (options) => {
    threaded.setThreads(1);
    const one = bend(threaded, options);
    expect(one.energies.length).toBeGreaterThan(1);
    const runs = [];
    for (const t of [2, 4]) {
      expect(threaded.setThreads(t)).toBe(t);
      runs.push([`${t} threads`, bend(threaded, options)]);
    }
    runs.push(['single-threaded build', bend(single, options)]);
    for (const [name, run] of runs) {
      expect(run.positions, name).toEqual(one.positions); // Float64Array: every element, exactly
      expect(run.energies, name).toEqual(one.energies);
      expect(run.products, name).toEqual(one.products);
      expect(run.stop, name).toBe(one.stop);
      expect(run.stopReason, name).toBe(one.stopReason);
    }
  });
});

// The bar's cage moved so that the bar sticks out of it.
function shiftedCage() {
  const positions = bar.cage.positions.slice();
  for (let i = 0; i < positions.length; i += 3) positions[i] += 1.0;
  return { positions, indices: bar.cage.indices };
}

describe('typed errors in the threaded build', () => {
  it('a cancelled bind and cancelled weights arrive as CancelledError', () => {
    expect(threaded.threads()).toBeGreaterThan(1);
    for (const body of [
      () => Deformer.create(threaded, bar.mesh, bar.cage, { onProgress: () => false }),
      () => computeWeights(threaded, bar.mesh, bar.cage, { progress: () => false }),
    ]) {
      const error = thrown(body);
      expect(error).toBeInstanceOf(CancelledError);
      expect(error.code).toBe('cancelled');
    }
  });

  it('a mesh outside its cage arrives as MeshError with the same findings as the single-threaded build', () => {
    const errors = [threaded, single].map((solver) => thrown(() => Deformer.create(solver, bar.mesh, shiftedCage())));
    for (const error of errors) {
      expect(error).toBeInstanceOf(MeshError);
      expect(error.code).toBe('mesh_outside_cage');
      expect(error.findings.map((f) => f.code)).toContain('outside_cage');
    }
    // The parallel check lists the vertices in vertex order, so even the messages agree.
    expect(errors[0].findings).toEqual(errors[1].findings);
    expect(errors[0].message).toBe(errors[1].message);
  });

  it('errors thrown on a pool thread reach the caller with their class, code and findings', async () => {
    const bench = await loadSolver({ bench: true, build: 'threads', threads: 2 });
    expect(bench.threads()).toBe(2);
    const outside = thrown(() => bench.benchThrowInPool('outside_cage'));
    expect(outside.code).toBe('mesh_outside_cage');
    expect(outside.findings).toEqual([{ severity: 'error', code: 'outside_cage',
      message: '1 of 8 mesh vertices is outside the cage (first: 7)' }]);
    for (const [kind, Type] of [['outside_cage', MeshError], ['cancelled', CancelledError], ['out_of_memory', SolverError]]) {
      const error = typedError(thrown(() => bench.benchThrowInPool(kind))); // as the library's calls do
      expect(error, kind).toBeInstanceOf(Type);
      expect(error.code, kind).toBe(kind === 'outside_cage' ? 'mesh_outside_cage' : kind);
      // The out-of-memory message speaks of the wasm heap wherever the module runs (it said "the browser" in Node).
      if (kind === 'out_of_memory') expect(error.message).toMatch(/^out of memory: .*the solver's wasm heap \(4 GB in all, one allocation under 2 GiB\)$/);
    }
    // Pool threads that threw keep working.
    expect(bench.setThreads(2)).toBe(2);
    expect(bend(bench, { maxIterations: 2 }).energies.length).toBeGreaterThan(0);
  });
});
