// Mean value coordinates through the wasm API and the `weights` command: partition of unity, linear
// precision, errors, and the .npy file the CLI writes (parsed back by a small reader below).
import { describe, expect, it, beforeAll, afterAll } from 'vitest';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { InputError, computeWeights, loadSolver, makeExample, readMesh, writeModel, writeObj } from 'subspace-deform';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const sharedData = new URL('../../../shared/data', import.meta.url).pathname;
const haveSharedData = existsSync(join(sharedData, 'gargoyle.obj'));
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });

let solver, dir, bar;

beforeAll(async () => {
  solver = await loadSolver();
  dir = mkdtempSync(join(tmpdir(), 'sd-weights-'));
  bar = makeExample(solver, 'bar');
  writeFileSync(join(dir, 'bar.obj'), writeObj(solver, bar.mesh));
  writeFileSync(join(dir, 'bar_cage.obj'), writeObj(solver, bar.cage));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

// max over rows of |sum_j W_ij - 1| and of |(W P0)_i - x_i| (Euclidean), for W n x m row-major.
function properties(W, n, m, cage, points) {
  let sumError = 0, reproduction = 0;
  for (let i = 0; i < n; ++i) {
    let sum = 0;
    const r = [0, 0, 0];
    for (let j = 0; j < m; ++j) {
      const w = W[i * m + j];
      sum += w;
      for (let a = 0; a < 3; ++a) r[a] += w * cage.positions[3 * j + a];
    }
    sumError = Math.max(sumError, Math.abs(sum - 1));
    reproduction = Math.max(reproduction, Math.hypot(r[0] - points[3 * i], r[1] - points[3 * i + 1], r[2] - points[3 * i + 2]));
  }
  return { sumError, reproduction };
}

function bboxDiagonal(p) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i += 3) for (let a = 0; a < 3; ++a) { lo[a] = Math.min(lo[a], p[i + a]); hi[a] = Math.max(hi[a], p[i + a]); }
  return Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

// Minimal .npy reader (v1.0/2.0, little-endian '<f8' / '<f4', C order) written from the format description.
function readNpy(bytes) {
  expect(bytes[0]).toBe(0x93);
  expect(Buffer.from(bytes.subarray(1, 6)).toString('latin1')).toBe('NUMPY');
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const major = bytes[6];
  const headerLength = major === 1 ? view.getUint16(8, true) : view.getUint32(8, true);
  const start = (major === 1 ? 10 : 12) + headerLength;
  const header = Buffer.from(bytes.subarray(major === 1 ? 10 : 12, start)).toString('latin1');
  const descr = /'descr':\s*'([^']+)'/.exec(header)[1];
  const fortran = /'fortran_order':\s*(True|False)/.exec(header)[1];
  const shape = /'shape':\s*\((\d+),\s*(\d+)\)/.exec(header).slice(1, 3).map(Number);
  const payload = bytes.slice(start).buffer;
  const data = descr === '<f8' ? new Float64Array(payload) : descr === '<f4' ? new Float32Array(payload) : null;
  return { descr, fortran, shape, data, headerEnd: start, version: major };
}

describe('computeWeights', () => {
  it('has partition of unity and linear precision on the bar example', () => {
    const { mesh, cage } = bar;
    const result = computeWeights(solver, mesh, cage);
    const n = mesh.positions.length / 3, m = cage.positions.length / 3;
    expect(result.rows).toBe(n);
    expect(result.cols).toBe(m);
    expect(result.weights).toBeInstanceOf(Float64Array);
    expect(result.weights.length).toBe(n * m);
    expect(result.bytes).toBe(8 * n * m);
    const { sumError, reproduction } = properties(result.weights, n, m, cage, mesh.positions);
    expect(sumError).toBeLessThanOrEqual(1e-12);
    expect(reproduction).toBeLessThanOrEqual(1e-10 * bboxDiagonal(mesh.positions));
    expect(result.minWeight).toBe(result.weights.reduce((a, b) => Math.min(a, b), Infinity));
    expect(result.bindMs).toBeGreaterThan(0);
  });

  it('stores float32 at half the size with ~1e-7 accuracy', () => {
    const { mesh, cage } = bar;
    const result = computeWeights(solver, mesh, cage, { float32: true });
    const n = result.rows, m = result.cols;
    expect(result.weights).toBeInstanceOf(Float32Array);
    expect(result.bytes).toBe(4 * n * m);
    const { sumError, reproduction } = properties(result.weights, n, m, cage, mesh.positions);
    expect(sumError).toBeLessThanOrEqual(1e-6);
    expect(reproduction).toBeLessThanOrEqual(1e-6 * bboxDiagonal(mesh.positions));
  });

  it('reports progress and can be cancelled', () => {
    const { mesh, cage } = bar;
    const fractions = [];
    computeWeights(solver, mesh, cage, { progress: (f) => { fractions.push(f); } });
    expect(fractions.at(-1)).toBe(1);
    expect(() => computeWeights(solver, mesh, cage, { progress: () => false })).toThrow(/binding cancelled/);
  });

  it('refuses over the memory budget and names outside vertices', () => {
    const { mesh, cage } = bar;
    expect(() => computeWeights(solver, mesh, cage, { memoryBudgetMB: 0.001 })).toThrow(/MB.*coarser cage.*float32/);
    const moved = mesh.positions.slice();
    moved[3 * 2] += 100;
    moved[3 * 5 + 1] -= 100;
    expect(() => computeWeights(solver, { positions: moved }, cage)).toThrow(/2 of \d+ mesh vertices are outside the cage \(first: 2, 5\)/);
  });

  it('validates its arguments before entering wasm', () => {
    const { mesh, cage } = bar;
    expect(() => computeWeights(solver, { positions: [0, 0, 0] }, cage)).toThrow(InputError);
    expect(() => computeWeights(solver, mesh, { positions: cage.positions, indices: new Uint32Array([0, 1, 99999]) })).toThrow(InputError);
    expect(() => computeWeights(solver, mesh, cage, { float32: 'yes' })).toThrow(InputError);
    expect(() => computeWeights(solver, mesh, cage, { memoryBudgetMB: -1 })).toThrow(InputError);
  });
});

describe('deform.mjs weights', () => {
  it('prints --help', () => {
    const r = run('weights', '--help');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/usage: .*weights <mesh> <cage> --out W\.npy \[--float32\]/);
  });

  it('needs --out', () => {
    const r = run('weights', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'));
    expect(r.status).toBe(2);
  });

  it.each([['float64', [], '<f8', 1e-12], ['float32', ['--float32'], '<f4', 1e-6]])(
    'writes a .npy (%s) that parses back with the right shape and values',
    (_, extra, descr, tolerance) => {
      const out = join(dir, `W_${descr.slice(1)}.npy`);
      const r = run('weights', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'), '--out', out, ...extra);
      expect(r.stderr).toBe('');
      expect(r.status).toBe(0);
      expect(r.stdout).toMatch(/W \(mvc\): \d+ x \d+/);
      expect(r.stdout).toMatch(/min weight/);
      expect(r.stdout).toMatch(/bind [\d.]+ m?s\b/);  // a readable time: ms, or s past a second
      const npy = readNpy(new Uint8Array(readFileSync(out)));
      expect(npy.version).toBe(1);
      expect(npy.headerEnd % 64).toBe(0);
      expect(npy.descr).toBe(descr);
      expect(npy.fortran).toBe('False');
      // The file's mesh is the OBJ round trip of the example (exact), so compare with the API directly.
      const mesh = readMesh(solver, readFileSync(join(dir, 'bar.obj')), 'bar.obj');
      const cage = readMesh(solver, readFileSync(join(dir, 'bar_cage.obj')), 'bar_cage.obj');
      const n = mesh.positions.length / 3, m = cage.positions.length / 3;
      expect(npy.shape).toEqual([n, m]);
      expect(npy.data.length).toBe(n * m);
      const direct = computeWeights(solver, mesh, cage, { float32: descr === '<f4' }).weights;
      expect(Array.from(npy.data)).toEqual(Array.from(direct));
      const { sumError } = properties(npy.data, n, m, cage, mesh.positions);
      expect(sumError).toBeLessThanOrEqual(tolerance);
    },
  );

  it('reads the mesh and the cage in any format: a .glb cage gives the same W as its OBJ (float32 positions)', async () => {
    writeFileSync(join(dir, 'bar_cage.glb'), await writeModel(solver, { mesh: bar.cage }, bar.cage.positions, 'bar_cage.glb'));
    const fromObj = join(dir, 'W_obj.npy'), fromGlb = join(dir, 'W_glb.npy');
    expect(run('weights', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'), '--out', fromObj).status).toBe(0);
    const r = run('weights', join(dir, 'bar.obj'), join(dir, 'bar_cage.glb'), '--out', fromGlb);
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    const a = readNpy(new Uint8Array(readFileSync(fromObj))), b = readNpy(new Uint8Array(readFileSync(fromGlb)));
    expect(b.shape).toEqual(a.shape);
    let gap = 0;
    for (let i = 0; i < a.data.length; ++i) gap = Math.max(gap, Math.abs(a.data[i] - b.data[i]));
    expect(gap).toBeLessThan(1e-5);
  });

  it('fails with a readable message when the mesh sticks out of the cage', () => {
    const shifted = bar.cage.positions.slice();
    for (let i = 0; i < shifted.length; i += 3) shifted[i] += 1.0;
    writeFileSync(join(dir, 'shifted_cage.obj'), writeObj(solver, { positions: shifted, indices: bar.cage.indices }));
    const r = run('weights', join(dir, 'bar.obj'), join(dir, 'shifted_cage.obj'), '--out', join(dir, 'bad.npy'));
    expect(r.status).toBe(1);
    expect(r.stderr).toMatch(/outside the cage \(first: /);
  });
});

describe('deform.mjs weights checks the pair first, as check and deform do', () => {
  // W of such a cage is computed without complaint by the binding but does not reproduce the mesh.
  const cube = 'v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n';
  const faces = ['1 4 3', '1 3 2', '5 6 7', '5 7 8', '1 2 6', '1 6 5', '2 3 7', '2 7 6', '3 4 8', '3 8 7', '4 1 5', '4 5 8'];
  const obj = (scale, faceList, extra = '') => `${cube.replace(/-?1/g, (x) => String(Number(x) * scale))}${extra}${faceList.map((f) => `f ${f}`).join('\n')}\n`;

  it.each([
    ['an open cage (a face missing)', obj(5, faces.slice(0, -1)), /^error \(invalid_mesh\): cage \S*open_cage\.obj: the mesh is open/m],
    ['a cage with a stray far vertex', obj(5, faces, '').replace('v 5 5 5', 'v 1e14 1e14 1e14'), /^error \(invalid_mesh\): cage .*degenerate faces/m],
  ])('refuses %s with exit 1 naming the problem, writing nothing', (_, cageText, pattern) => {
    writeFileSync(join(dir, 'cube.obj'), obj(1, faces));
    writeFileSync(join(dir, 'open_cage.obj'), cageText);
    const out = join(dir, 'refused.npy');
    const r = run('weights', join(dir, 'cube.obj'), join(dir, 'open_cage.obj'), '--out', out);
    expect(r.status).toBe(1);
    expect(r.stderr).toMatch(pattern);
    expect(existsSync(out)).toBe(false);
  });

  it('names the mesh file when the mesh itself is invalid', () => {
    writeFileSync(join(dir, 'nan_cube.obj'), obj(1, faces).replace('v 1 1 1', 'v 1 nan 1'));
    writeFileSync(join(dir, 'big_cage.obj'), obj(5, faces));
    const r = run('weights', join(dir, 'nan_cube.obj'), join(dir, 'big_cage.obj'), '--out', join(dir, 'nan.npy'));
    expect(r.status).toBe(1);
    expect(r.stderr).toMatch(/^error \(invalid_mesh\): mesh .*nan_cube\.obj: NaN or infinite coordinates/m);
  });
});

describe.skipIf(!haveSharedData)('real pairs in ../shared/data (skipped when that folder is absent)', () => {
  // Subsampled rows keep the test short; the binding is the same code for every row.
  const pairs = [['gargoyle.obj', 'gargoyle_cage.obj', 1000], ['armadillo.obj', 'armadillo_cage.obj', 1000],
    ['moomoo.obj', 'moomoo_cage.obj', 500], ['handbones.obj', 'handbones_cage.obj', 500], ['cow.obj', 'cow_cage.obj', 1000],
    ['boy.obj', 'boy_cage.obj', 400], ['spikybox.obj', 'spikybox_cage.obj', 2000], ['wiresphere.obj', 'wiresphere_cage.obj', 2000]];
  it.each(pairs)('%s in %s: partition of unity and linear precision', (meshName, cageName, rows) => {
    const mesh = readMesh(solver, readFileSync(join(sharedData, meshName)), meshName);
    const cage = readMesh(solver, readFileSync(join(sharedData, cageName)), cageName);
    const n = mesh.positions.length / 3, stride = Math.max(1, Math.ceil(n / rows));
    const points = [];
    for (let i = 0; i < n; i += stride) points.push(mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]);
    const positions = new Float64Array(points);
    const result = computeWeights(solver, { positions }, cage);
    const { sumError, reproduction } = properties(result.weights, result.rows, result.cols, cage, positions);
    expect(sumError).toBeLessThanOrEqual(1e-12);
    expect(reproduction).toBeLessThanOrEqual(1e-10 * bboxDiagonal(mesh.positions));
  });
});

describe('W is limited to one wasm allocation (about 2 GiB), not the heap\'s 4 GB', () => {
  it('computeWeights refuses a W over 2146 MB with out_of_memory and the true limit, before the module allocates', () => {
    // 300,000 points in a "cage" of 1000 vertices: W would be 2.4 GB in float64 (1.2 GB in float32).
    const cage = { positions: new Float64Array(3000), indices: new Uint32Array([0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2]) };
    const points = { positions: new Float64Array(3 * 300000) };
    let error;
    try {
      computeWeights(solver, points, cage, { memoryBudgetMB: 1e6 });
    } catch (e) {
      error = e;
    }
    expect(error?.code).toBe('out_of_memory');
    expect(error.message).toMatch(/W \(300000 x 1000 float64\) would need 2400 MB, more than the 2146 MB one allocation .*no memory budget changes that.*float32/);
  });

  it('says where the limit lies: 2.10 GB fits, 2.18 GB does not, float32 halves W', async () => {
    const { MAX_WASM_ALLOCATION_BYTES, checkWeightsAllocation } = await import('../../web/lib/wasm_allocation.js');
    expect(MAX_WASM_ALLOCATION_BYTES).toBeLessThan(2 ** 31);
    expect(() => checkWeightsAllocation(2625000, 100, false, 'x')).not.toThrow();  // 2.10 GB
    expect(() => checkWeightsAllocation(2725000, 100, false, 'x')).toThrow(/2180 MB, more than the 2146 MB/);
    expect(() => checkWeightsAllocation(2725000, 100, true, 'x')).not.toThrow();
  });
});
