// A model far from the origin, through the library and the CLI: its volume is summed about a point near it
// (docs/method.md section 5), so `check` reads the volume it has at the origin and a solve with the volume kept
// reaches the shape it reaches there, moved. Summed about the origin, the bar 1e3 away stalled after one iteration
// with nothing moved, and 1e6 away `check` refused it as inward.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Deformer, checkMesh, loadSolver, makeExample, writeObj } from 'subspace-deform';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
let solver, bar, dir;

const moved = (mesh, by) => ({
  positions: mesh.positions.map((x, i) => x + by[i % 3]),
  indices: mesh.indices,
});

beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
  dir = mkdtempSync(join(tmpdir(), 'sd-far-'));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

// The bar's right end pulled down and forward; the answer's positions with the offset taken off.
function solveBar(by, method) {
  const mesh = moved(bar.mesh, by), cage = moved(bar.cage, by);
  const d = Deformer.create(solver, mesh, cage);
  try {
    d.setOptions({ method, volume: true });
    const n = mesh.positions.length / 3, left = [], right = [];
    for (let i = 0; i < n; ++i) {
      if (bar.mesh.positions[3 * i] < -2.2) left.push(i);
      if (bar.mesh.positions[3 * i] > 2.2) right.push(i);
    }
    d.setHandles([left, right]);
    const targets = [];
    for (const v of left) for (let a = 0; a < 3; ++a) targets.push(mesh.positions[3 * v + a]);
    for (const v of right) for (let a = 0; a < 3; ++a) targets.push(mesh.positions[3 * v + a] + [0, -0.8, 0.3][a]);
    d.setTargets(Float64Array.from(targets));
    const result = d.solve();
    return { result, positions: d.positions().map((x, i) => x - by[i % 3]), rest: d.restVolume };
  } finally {
    d.dispose();
  }
}

describe('a model far from the origin', () => {
  it('check reads the volume it has at the origin, 1e3 to 1e6 away', () => {
    const here = checkMesh(solver, bar.mesh).summary.volume;
    for (const offset of [1e3, 1e5, 1e6]) {
      const report = checkMesh(solver, moved(bar.mesh, [offset, -offset, 0.5 * offset]));
      expect(report.ok, `${offset}: ${report.text}`).toBe(true);
      expect(Math.abs(report.summary.volume - here) / here, `${offset}`).toBeLessThan(1e-14 * offset);
    }
  });

  it('deform.mjs check accepts the bar 1e6 away with its volume', () => {
    const far = moved(bar.mesh, [1e6, 1e6, 1e6]);
    writeFileSync(join(dir, 'far.obj'), writeObj(solver, far));
    writeFileSync(join(dir, 'far_cage.obj'), writeObj(solver, moved(bar.cage, [1e6, 1e6, 1e6])));
    const r = spawnSync(process.execPath, [cli, 'check', join(dir, 'far.obj'), join(dir, 'far_cage.obj'), '--json'],
      { encoding: 'utf8', timeout: 120000 });
    expect(r.status, r.stdout + r.stderr).toBe(0);
    expect(r.stdout).not.toMatch(/inward/);
  });

  for (const method of ['subspace', 'full']) {
    it(`${method}: solves to the shape at the origin, moved, keeping the volume`, () => {
      const here = solveBar([0, 0, 0], method);
      expect(here.result.converged, here.result.stopReason).toBe(true);
      let diagonal = 0;
      for (let a = 0; a < 3; ++a) {
        const xs = bar.mesh.positions.filter((_, i) => i % 3 === a);
        diagonal += (Math.max(...xs) - Math.min(...xs)) ** 2;
      }
      diagonal = Math.sqrt(diagonal);
      for (const offset of [1e3, 1e5]) {
        const far = solveBar([offset, -0.7 * offset, 0.4 * offset], method);
        expect(far.result.converged, `${offset}: ${far.result.stopReason}`).toBe(true);
        let worst = 0;
        for (let i = 0; i < here.positions.length; ++i) worst = Math.max(worst, Math.abs(far.positions[i] - here.positions[i]));
        expect(worst / diagonal, `${offset}`).toBeLessThan(5e-6);  // the stop rules stop where rounding lets them: as in far_from_origin_test.cpp
        const last = far.result.iterations.at(-1);
        expect(Math.abs(last.volumeRelError), `${offset}`).toBeLessThan(1e-9);
        expect(Math.abs(far.rest - here.rest) / here.rest, `${offset}`).toBeLessThan(1e-9);
      }
    });
  }
});
