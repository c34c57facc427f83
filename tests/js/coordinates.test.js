// The three cage coordinates through the library, scenes and the CLI, on the built-in C (a capsule bent
// into a C in its bent cage, concave inside the C): mean value weights go negative there, positive mean value
// and harmonic weights do not; every type binds a session that solves a drag; the choice is checked everywhere.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import {
  COORDINATES, Deformer, InputError, computeWeights, handleTargets, loadSolver, makeExample, parseScene, writeObj,
} from 'subspace-deform';
import { thrown } from './support/thrown.js';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });
let solver, c, dir;

// The C's two ends: 300 vertices nearest to each end of the capsule before bending (the ends of the C, at
// the top and bottom of its opening).
function ends(mesh) {
  const n = mesh.positions.length / 3;
  const angle = (v) => Math.atan2(mesh.positions[3 * v + 1], -mesh.positions[3 * v]);
  const order = [...Array(n).keys()].sort((a, b) => angle(a) - angle(b));
  return { fixed: order.slice(0, 300), moved: order.slice(n - 300) };
}

function rowStats(W, n, m) {
  let min = Infinity, sumError = 0;
  for (let i = 0; i < n; ++i) {
    let sum = 0;
    for (let j = 0; j < m; ++j) {
      min = Math.min(min, W[i * m + j]);
      sum += W[i * m + j];
    }
    sumError = Math.max(sumError, Math.abs(sum - 1));
  }
  return { min, sumError };
}

beforeAll(async () => {
  solver = await loadSolver();
  c = makeExample(solver, 'c-bar');
  dir = mkdtempSync(join(tmpdir(), 'sd-coordinates-'));
  writeFileSync(join(dir, 'c.obj'), writeObj(solver, c.mesh));
  writeFileSync(join(dir, 'c_cage.obj'), writeObj(solver, c.cage));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('cage coordinates (wasm)', () => {
  it('lists the types from the C++ core, the default first', () => {
    expect(COORDINATES.types).toEqual(['mvc', 'pmvc', 'harmonic']);
    expect(COORDINATES.pmvcResolution).toMatchObject({ min: 2, max: 1024, default: 32 });
    expect(COORDINATES.harmonicResolution).toMatchObject({ min: 8, default: 0 });
  });

  it('computeWeights: mean value weights go negative inside the C, positive mean value and harmonic ones do not', () => {
    const n = c.mesh.positions.length / 3, m = c.cage.positions.length / 3;
    const mvc = computeWeights(solver, c.mesh, c.cage);
    expect(mvc.coordinates).toBe('mvc');
    expect(mvc.minWeight).toBeLessThan(-1e-3);
    const pmvc = computeWeights(solver, c.mesh, c.cage, { coordinates: 'pmvc', pmvcResolution: 12 });
    expect(pmvc).toMatchObject({ coordinates: 'pmvc', rows: n, cols: m });
    expect(pmvc.rays).toBeGreaterThan(0);
    const p = rowStats(pmvc.weights, n, m);
    expect(p.min).toBeGreaterThanOrEqual(0);
    expect(p.sumError).toBeLessThanOrEqual(1e-8);
    expect(pmvc.minWeight).toBe(p.min);
    const harmonic = computeWeights(solver, c.mesh, c.cage, { coordinates: 'harmonic', harmonicResolution: 24 });
    expect(harmonic).toMatchObject({ coordinates: 'harmonic', resolution: 24 });
    expect(harmonic.unknowns).toBeGreaterThan(100);
    expect(harmonic.grid).toHaveLength(3);
    const h = rowStats(harmonic.weights, n, m);
    expect(h.min).toBeGreaterThanOrEqual(-1e-9);
    expect(h.sumError).toBeLessThanOrEqual(1e-6);
  });

  it('refuses a bad choice before entering wasm, naming it', () => {
    const cases = [
      [{ coordinates: 'green' }, /coordinates must be one of 'mvc', 'pmvc', 'harmonic'/],
      [{ pmvcResolution: 8 }, /pmvcResolution is for coordinates 'pmvc' \(the coordinates are 'mvc'\)/],
      [{ coordinates: 'harmonic', pmvcResolution: 8 }, /pmvcResolution is for coordinates 'pmvc'/],
      [{ coordinates: 'pmvc', pmvcResolution: 1 }, /pmvcResolution must be an integer from 2 to 1024/],
      [{ coordinates: 'harmonic', harmonicResolution: 4.5 }, /harmonicResolution must be an integer from 8 .*or 0/],
    ];
    for (const [options, message] of cases) {
      const error = thrown(() => computeWeights(solver, c.mesh, c.cage, options));
      expect(error).toBeInstanceOf(InputError);
      expect(error.message).toMatch(message);
    }
    expect(thrown(() => Deformer.create(solver, c.mesh, null, { basis: 'spectral', modes: 8, coordinates: 'pmvc' })).message)
      .toMatch(/coordinates are for the 'cage' basis/);
  });

  it('a harmonic grid over the memory budget is a SolverError with code memory_budget', () => {
    const error = thrown(() => computeWeights(solver, c.mesh, c.cage, { coordinates: 'harmonic', harmonicResolution: 900, memoryBudgetMB: 60 }));
    expect(error.code).toBe('memory_budget');
    expect(error.message).toMatch(/harmonic coordinates: .* over the memory budget of 60 MB at resolution 900/);
  });

  for (const coordinates of COORDINATES.types) {
    it(`a session bound with ${coordinates} solves a drag across the C, fast and exact, keeping the volume`, () => {
      const { fixed, moved } = ends(c.mesh);
      const scene = parseScene({ example: 'c-bar', handles: [{ vertices: fixed }, { vertices: moved, translate: [0.6, 0.5, 0] }] });
      const { groups, targets } = handleTargets(c.mesh.positions, scene.handles);
      const extra = coordinates === 'pmvc' ? { pmvcResolution: 8 } : coordinates === 'harmonic' ? { harmonicResolution: 20 } : {};
      const d = Deformer.create(solver, c.mesh, c.cage, { coordinates, ...extra });
      try {
        expect(d.coordinates).toBe(coordinates);
        expect(d.coordinatesReport()).toMatchObject({ coordinates });
        // Column j of W: cage vertex j's weight at every mesh vertex, as the worker hands it to the page.
        const column = d.basisColumn(5);
        expect(column).toBeInstanceOf(Float32Array);
        expect(column).toHaveLength(d.vertexCount);
        const W = computeWeights(solver, c.mesh, c.cage, { coordinates, ...extra });
        for (const i of [0, 100, d.vertexCount - 1]) expect(column[i]).toBeCloseTo(W.weights[i * W.cols + 5], 6);
        expect(thrown(() => d.basisColumn(d.basisSize)).message).toMatch(/basisColumn: j must be an integer from 0 to 51/);
        d.setHandles(groups);
        const shapes = [];
        for (const jacobian of ['exact', 'fast']) {
          d.setOptions({ method: 'subspace', jacobian, maxIterations: 200 });
          d.reset();
          d.setTargets(targets);
          const result = d.solve();
          expect(result.converged, result.stopReason).toBe(true);
          expect(Math.abs(result.iterations.at(-1).volumeRelError)).toBeLessThanOrEqual(1e-8);
          shapes.push(d.positions());
        }
        let gap = 0;
        for (let k = 0; k < shapes[0].length; ++k) gap = Math.max(gap, Math.abs(shapes[0][k] - shapes[1][k]));
        expect(gap).toBeLessThan(1e-2);
      } finally {
        d.dispose();
      }
    });
  }

  it('basisColumn is in the file\'s numbering, like positions(), when the mesh is welded', () => {
    // The C with every triangle given its own three corners (as a non-indexed export has it): the session welds
    // it back; the page colours the file's vertices, so each corner gets the weight of its welded point.
    const indices = c.mesh.indices;
    const positions = new Float64Array(3 * indices.length);
    for (let k = 0; k < indices.length; ++k) positions.set(c.mesh.positions.subarray(3 * indices[k], 3 * indices[k] + 3), 3 * k);
    const split = { positions, indices: Uint32Array.from(indices.keys()) };
    const welded = Deformer.create(solver, c.mesh, c.cage, { coordinates: 'pmvc', pmvcResolution: 8 });
    const seams = Deformer.create(solver, split, c.cage, { coordinates: 'pmvc', pmvcResolution: 8 });
    try {
      expect(seams.layout().solverVertices).toBe(welded.vertexCount);
      const column = seams.basisColumn(51), reference = welded.basisColumn(51);
      expect(column).toHaveLength(indices.length);
      expect(column.length).toBe(seams.positions().length / 3);
      for (let k = 0; k < indices.length; ++k) expect(column[k]).toBe(reference[indices[k]]);
    } finally {
      welded.dispose();
      seams.dispose();
    }
  });

  it('scenes take the coordinates in "subspace" and refuse what does not fit', () => {
    expect(parseScene({ example: 'c-bar', handles: [], subspace: { basis: 'cage', coordinates: 'pmvc', pmvcResolution: 16 } }).subspace)
      .toEqual({ basis: 'cage', coordinates: 'pmvc', pmvcResolution: 16 });
    expect(parseScene({ example: 'c-bar', handles: [], subspace: { coordinates: 'harmonic' } }).subspace)
      .toEqual({ basis: 'cage', coordinates: 'harmonic' });
    const bad = [
      [{ coordinates: 'pmvc', harmonicResolution: 20 }, /scene: subspace: harmonicResolution is for coordinates 'harmonic'/],
      [{ basis: 'spectral', modes: 8, coordinates: 'harmonic' }, /subspace.coordinates are for the "cage" basis/],
      [{ coordinates: 7 }, /coordinates must be one of/],
      [{ resolution: 7 }, /subspace has unknown field "resolution"/],
    ];
    for (const [subspace, message] of bad) {
      expect(() => parseScene({ example: 'c-bar', handles: [], subspace })).toThrow(message);
    }
  });
});

describe('the CLI with cage coordinates', () => {
  it('weights --coordinates pmvc writes non-negative weights and says how many rays it cast', () => {
    const out = join(dir, 'W.npy');
    const r = run('weights', join(dir, 'c.obj'), join(dir, 'c_cage.obj'), '--out', out, '--coordinates', 'pmvc', '--resolution', '8');
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/W \(pmvc\): \d+ x 52/);
    expect(r.stdout).toMatch(/rays per vertex into the hidden parts/);
    const bytes = readFileSync(out);
    const start = 10 + bytes.readUInt16LE(8);
    const W = new Float64Array(bytes.buffer.slice(bytes.byteOffset + start, bytes.byteOffset + bytes.length));
    expect(W.reduce((a, b) => Math.min(a, b), Infinity)).toBeGreaterThanOrEqual(0);
  });

  it('weights --coordinates harmonic reports its grid; a resolution for mvc is bad usage', () => {
    const r = run('weights', join(dir, 'c.obj'), join(dir, 'c_cage.obj'), '--out', join(dir, 'H.npy'), '--coordinates', 'harmonic', '--resolution', '16');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/W \(harmonic\).*\n.*resolution 16: \d+ x \d+ x \d+ grid, \d+ nodes inside/);
    const bad = run('weights', join(dir, 'c.obj'), join(dir, 'c_cage.obj'), '--out', join(dir, 'X.npy'), '--resolution', '16');
    expect(bad.status).toBe(2);
    expect(bad.stderr).toMatch(/--resolution is for --coordinates pmvc or harmonic/);
    const unknown = run('weights', join(dir, 'c.obj'), join(dir, 'c_cage.obj'), '--out', join(dir, 'X.npy'), '--coordinates', 'green');
    expect(unknown.status).toBe(2);
    expect(unknown.stderr).toMatch(/--coordinates must be mvc, pmvc, harmonic/);
  });

  it('deform binds the scene\'s coordinates (or --coordinates over them) and reports them', () => {
    const { fixed, moved } = ends(c.mesh);
    const scene = { mesh: 'c.obj', cage: 'c_cage.obj', subspace: { basis: 'cage', coordinates: 'harmonic', harmonicResolution: 16 },
      handles: [{ vertices: fixed }, { vertices: moved, translate: [0.6, 0.5, 0] }] };
    writeFileSync(join(dir, 'c.json'), JSON.stringify(scene));
    const report = join(dir, 'report.json');
    const r = run('deform', join(dir, 'c.json'), '--report', report);
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/cage basis, harmonic coordinates, 52 columns/);
    const rep = JSON.parse(readFileSync(report, 'utf8'));
    expect(rep.coordinates).toMatchObject({ coordinates: 'harmonic', resolution: 16 });
    expect(rep.coordinates.minWeight).toBeGreaterThanOrEqual(-1e-9);
    expect(rep.converged).toBe(true);
    const over = run('deform', join(dir, 'c.json'), '--coordinates', 'pmvc', '--resolution', '6', '--report', report);
    expect(over.status).toBe(0);
    const pmvc = JSON.parse(readFileSync(report, 'utf8')).coordinates;
    expect(pmvc.coordinates).toBe('pmvc');
    expect(pmvc.minWeight).toBeGreaterThanOrEqual(0);
  });

  it('a cage that does not enclose the mesh is a named failure with every type, in weights and deform', () => {
    // The C's cage shrunk about its centre: part of the mesh is outside it.
    const small = { positions: c.cage.positions.map((x) => 0.8 * x), indices: c.cage.indices };
    writeFileSync(join(dir, 'small_cage.obj'), writeObj(solver, small));
    for (const coordinates of COORDINATES.types) {
      const r = run('weights', join(dir, 'c.obj'), join(dir, 'small_cage.obj'), '--out', join(dir, 'S.npy'), '--coordinates', coordinates);
      expect(r.status, `${coordinates}: ${r.stderr}`).toBe(1);
      expect(r.stderr).toMatch(/\d+ of \d+ mesh vertices are outside the cage/);
    }
    const scene = { mesh: 'c.obj', cage: 'small_cage.obj', subspace: { basis: 'cage', coordinates: 'harmonic' }, handles: [{ vertices: [0] }] };
    writeFileSync(join(dir, 'small.json'), JSON.stringify(scene));
    const r = run('deform', join(dir, 'small.json'));
    expect(r.status).toBe(1);
    expect(r.stderr).toMatch(/outside/);
  });
});
