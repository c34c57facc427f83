// What the worker hands the page each frame (Deformer.renderBuffers, computed in wasm): Float32 positions and
// the vertex normals of web/lib/normals.js (layoutNormals), smooth across welded seams, for any model layout.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { Deformer, InputError, layoutNormals, loadSolver, makeExample } from 'subspace-deform';
import { normalGroups } from '../../web/lib/normals.js';
import { barEnds, endTargets } from './support/bar_ends.js';

let solver, bar;
beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
});
afterAll(() => solver?.setThreads?.(0));

// The bar with every triangle's corners as vertices of their own (as a flat-shaded export writes it).
function perCorner(mesh) {
  const positions = new Float64Array(3 * mesh.indices.length);
  mesh.indices.forEach((v, c) => positions.set(mesh.positions.subarray(3 * v, 3 * v + 3), 3 * c));
  return { positions, indices: Uint32Array.from(mesh.indices, (_, c) => c) };
}

function bentSession(mesh) {
  const d = Deformer.create(solver, mesh, bar.cage);
  const { left, right } = barEnds(mesh);
  d.setHandles([left, right]);
  d.setTargets(endTargets(mesh, [left, right], [0, -1, 0.3]));
  d.solve();
  return d;
}

function largestDifference(a, b) {
  let worst = 0;
  for (let i = 0; i < a.length; ++i) worst = Math.max(worst, Math.abs(a[i] - b[i]));
  return worst;
}

describe('Deformer.renderBuffers', () => {
  it('gives the deformed positions in single precision and the normals layoutNormals computes', () => {
    const d = bentSession(bar.mesh);
    const positions = d.positions();
    const r = d.renderBuffers();
    expect(r.positions).toBeInstanceOf(Float32Array);
    expect(r.positions).toEqual(Float32Array.from(positions));
    const expected = layoutNormals(positions, bar.mesh.indices);
    expect(largestDifference(r.normals, expected)).toBeLessThan(1e-6);
    for (let v = 0; v < r.normals.length; v += 3) {
      expect(Math.hypot(r.normals[v], r.normals[v + 1], r.normals[v + 2])).toBeCloseTo(1, 6);
    }
    d.dispose();
  });

  it('shares one normal across the copies of a welded point, like layoutNormals with the same groups', () => {
    const split = perCorner(bar.mesh);
    const d = bentSession(split);
    const { solverOfFile } = d.layout();
    const groups = normalGroups(split.positions.length / 3, { solverOfFile });
    const r = d.renderBuffers({ groups });
    const expected = layoutNormals(d.positions(), split.indices, { solverOfFile });
    expect(largestDifference(r.normals, expected)).toBeLessThan(1e-6);
    // Without the groups every corner would carry only its own triangle's normal: the seams would show.
    const faceted = d.renderBuffers();
    expect(largestDifference(faceted.normals, expected)).toBeGreaterThan(0.05);
    d.dispose();
  });

  it('is the same with one thread and with two', () => {
    const d = bentSession(bar.mesh);
    solver.setThreads?.(1);
    const one = d.renderBuffers().normals;
    solver.setThreads?.(2);
    const two = d.renderBuffers().normals;
    expect(two).toEqual(one);
    d.dispose();
  });

  it('refuses groups that do not fit the mesh, by name', () => {
    const d = Deformer.create(solver, bar.mesh, bar.cage);
    expect(() => d.renderBuffers({ groups: new Int32Array(3) })).toThrow(/renderBuffers: groups: 3 entries for \d+ vertices/);
    d.dispose();
  });

  // n vertices make at most n groups. An id of 2^31 - 1 used to trap wasm (memory access out of bounds), 1e9 and
  // 2e8 to grow the heap to 1.66 GB and fail with out_of_memory: the per-group arrays were sized from the largest id.
  it('refuses group ids outside [0, vertexCount) as an InputError naming them, before wasm sizes anything', () => {
    const d = Deformer.create(solver, bar.mesh, bar.cage);
    const n = d.vertexCount;
    for (const id of [2 ** 31 - 1, 1e9, 2e8, n, -1]) {
      const groups = new Int32Array(n).fill(0);
      groups[5] = id;
      expect(() => d.renderBuffers({ groups })).toThrow(InputError);
      expect(() => d.renderBuffers({ groups })).toThrow(`renderBuffers: groups: vertex 5 has group ${id}, outside [0, ${n})`);
    }
    expect(() => d.renderBuffers({ groups: [0, 0.5, ...new Array(n - 2).fill(0)] })).toThrow(/vertex 1 has group 0\.5/);
    expect(() => layoutNormals(bar.mesh.positions, bar.mesh.indices, { groups: new Int32Array(n).fill(1e9) }))
      .toThrow('layoutNormals: groups: vertex 0 has group 1000000000');
    const last = new Int32Array(n).fill(n - 1); // one group for every vertex, with the largest id there is
    expect(d.renderBuffers({ groups: last }).normals.length).toBe(3 * n);
    d.dispose();
  });
});
