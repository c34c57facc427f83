// Automatic cage generation through the wasm API and the `cage` command. The cage's properties are checked
// here in JS, independently of the C++ validation: closed and consistently oriented (each directed edge
// once, its twin present), outward (positive volume), every mesh vertex at winding number 1, K within 20%,
// and that mean value coordinates bind on it with rows summing to 1.
import { describe, expect, it, beforeAll, afterAll } from 'vitest';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import bunny from 'bunny';
import {
  InputError, checkPair, computeWeights, generateCage, loadSolver, makeExample, meshFromCells, readMesh, readModel, writeObj,
} from 'subspace-deform';
import { volume as meshVolume } from '../e2e/geometry.mjs';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const sharedData = new URL('../../../shared/data', import.meta.url).pathname;
const haveSpot = existsSync(join(sharedData, 'spot.obj'));
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });

let solver, dir, sphere;

beforeAll(async () => {
  solver = await loadSolver();
  dir = mkdtempSync(join(tmpdir(), 'sd-cage-'));
  sphere = makeExample(solver, 'sphere').mesh;
  writeFileSync(join(dir, 'sphere.obj'), writeObj(solver, sphere));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

const volume = ({ positions, indices }) => meshVolume(positions, indices);

function closedAndOriented({ indices: F }) {
  const directed = new Set();
  for (let f = 0; f < F.length; f += 3) {
    for (let k = 0; k < 3; ++k) {
      const key = `${F[f + k]},${F[f + ((k + 1) % 3)]}`;
      if (directed.has(key)) return false;
      directed.add(key);
    }
  }
  for (const key of directed) {
    const [a, b] = key.split(',');
    if (!directed.has(`${b},${a}`)) return false;
  }
  return true;
}

// Solid-angle winding number of point p (Van Oosterom and Strackee).
function winding({ positions: P, indices: F }, p) {
  let w = 0;
  for (let f = 0; f < F.length; f += 3) {
    const v = [0, 1, 2].map((k) => [0, 1, 2].map((a) => P[3 * F[f + k] + a] - p[a]));
    const [a, b, c] = v;
    const n = v.map((x) => Math.hypot(...x));
    const dot = (x, y) => x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    const cross = (x, y) => [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]];
    w += 2 * Math.atan2(dot(a, cross(b, c)), n[0] * n[1] * n[2] + dot(a, b) * n[2] + dot(b, c) * n[0] + dot(c, a) * n[1]);
  }
  return w / (4 * Math.PI);
}

function expectValidCage(mesh, cage, K) {
  const m = cage.positions.length / 3;
  expect(m).toBeGreaterThanOrEqual(0.8 * K);
  expect(m).toBeLessThanOrEqual(1.2 * K);
  expect(closedAndOriented(cage)).toBe(true);
  expect(volume(cage)).toBeGreaterThan(volume(mesh));
  let outside = 0;
  const n = mesh.positions.length / 3;
  for (let i = 0; i < n; ++i) {
    if (Math.abs(winding(cage, mesh.positions.subarray(3 * i, 3 * i + 3)) - 1) > 1e-6) ++outside;
  }
  expect(outside).toBe(0);
  const W = computeWeights(solver, mesh, cage);
  let worst = 0;
  for (let i = 0; i < W.rows; ++i) {
    let sum = 0;
    for (let j = 0; j < W.cols; ++j) sum += W.weights[i * W.cols + j];
    worst = Math.max(worst, Math.abs(sum - 1));
  }
  expect(worst).toBeLessThan(1e-9);
}

describe('generateCage (wasm)', () => {
  it('makes a valid 40-vertex cage around the sphere example, reporting progress', () => {
    const fractions = [];
    const cage = generateCage(solver, sphere, { vertices: 40, onProgress: (f) => { fractions.push(f); } });
    expectValidCage(sphere, cage, 40);
    expect(cage.volumeRatio).toBeGreaterThan(1);
    expect(cage.minClearance).toBeGreaterThan(0);
    expect(fractions.length).toBeGreaterThan(2);
    expect(fractions.at(-1)).toBe(1);
  });

  it('cages the npm bunny (the built-in example) with 100 vertices', () => {
    const mesh = meshFromCells(bunny);
    expectValidCage(mesh, generateCage(solver, mesh, { vertices: 100 }), 100);
  });

  it('cancels when onProgress returns false', () => {
    expect(() => generateCage(solver, sphere, { vertices: 40, onProgress: () => false })).toThrow(/cancelled/);
  });

  it('rejects bad arguments before entering wasm, and bad meshes with a readable Error', () => {
    expect(() => generateCage(solver, sphere, { vertices: 2 })).toThrow(InputError);
    expect(() => generateCage(solver, sphere, { vertices: 40.5 })).toThrow(InputError);
    expect(() => generateCage(solver, sphere, { offset: -1 })).toThrow(InputError);
    expect(() => generateCage(solver, { positions: new Float64Array(9), indices: new Uint32Array([0, 1, 2]) })).toThrow(InputError);
    expect(() => generateCage(solver, { positions: sphere.positions, indices: new Uint32Array([0, 1, 99999]) })).toThrow(/vertex 99999/);
    // Every vertex at one point: every face collapses when welded, and nothing is left to enclose.
    const point = { positions: new Float64Array(15), indices: new Uint32Array([0, 1, 2, 0, 2, 3, 0, 3, 4, 1, 2, 3]) };
    expect(() => generateCage(solver, point)).toThrow(/valid mesh[\s\S]*no faces[\s\S]*4 faces whose corners are one point/);
  });
});

// The sphere example broken in one of the ways a user's file can be: [mesh, the checker's finding].
function brokenSphere(how) {
  const { positions, indices } = sphere;
  const flipped = indices.slice();
  for (let f = 0; f < flipped.length; f += 3) [flipped[f + 1], flipped[f + 2]] = [flipped[f + 2], flipped[f + 1]];
  // Corner 2 of face 0 on the midpoint of its opposite edge: zero area (moving it onto a corner would weld).
  const degenerate = positions.slice();
  for (let a = 0; a < 3; ++a) degenerate[3 * indices[2] + a] = (positions[3 * indices[0] + a] + positions[3 * indices[1] + a]) / 2;
  // The upper half pressed flat: an open sheet that encloses nothing even with its rim capped.
  const upper = [];
  for (let f = 0; f < indices.length; f += 3) {
    if ([0, 1, 2].every((k) => positions[3 * indices[f + k] + 2] >= -1e-9)) upper.push(indices[f], indices[f + 1], indices[f + 2]);
  }
  const withDuplicate = new Uint32Array(indices.length + 3);
  withDuplicate.set(indices);
  withDuplicate.set(indices.subarray(0, 3), indices.length);
  return {
    inward: [{ positions, indices: flipped }, /oriented inward/],
    degenerate: [{ positions: degenerate, indices }, /degenerate face/],
    duplicate: [{ positions, indices: withDuplicate }, /duplicate face/],
    flat: [{ positions: positions.map((x, i) => (i % 3 === 2 ? 0 : x)), indices: Uint32Array.from(upper) }, /encloses no volume/],
    huge: [{ positions: positions.map((x) => x * 1e300), indices }, /beyond 1e30[\s\S]*rescale/],
  }[how];
}

describe('cage command', () => {
  it.each([['1e8'], ['1e30'], ['1e300']])('refuses --offset %s at once, naming the limit (it used to trap or allocate)', (offset) => {
    const result = run('cage', join(dir, 'sphere.obj'), '--vertices', '30', '--offset', offset, '--out', join(dir, 'x.obj'));
    expect(result.status).toBe(1);
    expect(result.stderr).toMatch(/offset must be a length of at most the mesh's bounding-box diagonal \(3\.464/);
    expect(result.stderr).not.toMatch(/memory access|RuntimeError|vector/);
    expect(existsSync(join(dir, 'x.obj'))).toBe(false);
    // Refused before any work: no progress was reported (such offsets used to run into a wasm trap or into
    // minutes of voxel work, which prints its progress every 10%).
    expect(result.stderr).not.toMatch(/^cage: \d+%$/m);
  });

  // 8..512 is the range, but a grid holds at most 64M voxels: a sphere (as deep as it is long) at 512 needs about
  // 531^3. The message spoke only of "a larger voxel size or a smaller offset", neither of them a flag.
  it('names the flags that shrink a voxel grid over the memory budget', () => {
    const out = join(dir, 'fine_cage.obj');
    const result = run('cage', join(dir, 'sphere.obj'), '--vertices', '30', '--resolution', '512', '--out', out);
    expect(result.status).toBe(1);
    expect(result.stderr).toMatch(/^error \(memory_budget\): .* voxels is over the limit of 67108864 voxels; .*\(here: a lower --resolution than 512, or a smaller --offset\)$/m);
    expect(existsSync(out)).toBe(false);
  });

  it('makes a cage a third of the diagonal away, printing progress to stderr', () => {
    const out = join(dir, 'far_cage.obj');
    const result = run('cage', join(dir, 'sphere.obj'), '--vertices', '30', '--offset', '1', '--out', out);
    expect(result.status, result.stderr).toBe(0);
    expect(result.stderr).toMatch(/^cage: 10%$/m);
    const cage = readMesh(solver, readFileSync(out), 'far_cage.obj');
    expectValidCage(sphere, cage, 30);
  });

  it.each(['inward', 'degenerate', 'duplicate', 'flat', 'huge'])('refuses the %s sphere with the checker\'s finding, writing nothing', (name) => {
    const [mesh, finding] = brokenSphere(name);
    const file = join(dir, `${name}.obj`);
    writeFileSync(file, writeObj(solver, mesh));
    const out = join(dir, `${name}_cage.obj`);
    const result = run('cage', file, '--vertices', '30', '--out', out);
    expect(result.status).toBe(1);
    expect(result.stderr).toMatch(/cage generation needs a valid mesh/);
    expect(result.stderr).toMatch(finding);
    expect(existsSync(out)).toBe(false);
  });

  it('cages an open sphere around its surface with the hole capped', () => {
    const { positions, indices } = sphere;
    const open = { positions, indices: indices.slice(3 * 4) };  // four triangles gone: a hole
    writeFileSync(join(dir, 'open.obj'), writeObj(solver, open));
    const out = join(dir, 'open_cage.obj');
    const result = run('cage', join(dir, 'open.obj'), '--vertices', '30', '--out', out);
    expect(result.status, result.stderr).toBe(0);
    const cage = readMesh(solver, readFileSync(out), 'open_cage.obj');
    expect(checkPair(solver, open, cage).ok).toBe(true);
  });

  it('writes a cage that reads back with the requested size and prints the volume ratio', () => {
    const out = join(dir, 'sphere_cage.obj');
    const result = run('cage', join(dir, 'sphere.obj'), '--vertices', '30', '--resolution', '32', '--out', out);
    expect(result.status, result.stderr).toBe(0);
    expect(result.stdout).toMatch(/cage: \d+ vertices/);
    expect(result.stdout).toMatch(/volume ratio \d/);
    const cage = readMesh(solver, readFileSync(out), 'sphere_cage.obj');
    expectValidCage(sphere, cage, 30);
  });

  // A .glb name used to get OBJ text, which no glTF reader opens; a .gltf (its buffers in other files) is refused.
  it('writes binary glTF under a .glb name, and refuses a .gltf before any work', async () => {
    const out = join(dir, 'sphere_cage.glb');
    const result = run('cage', join(dir, 'sphere.obj'), '--vertices', '30', '--resolution', '32', '--out', out);
    expect(result.status, result.stderr).toBe(0);
    const { mesh } = await readModel(solver, readFileSync(out), 'sphere_cage.glb');
    expectValidCage(sphere, mesh, 30);
    const gltf = join(dir, 'sphere_cage.gltf');
    const refused = run('cage', join(dir, 'sphere.obj'), '--vertices', '30', '--out', gltf);
    expect(refused.status).toBe(2);
    expect(refused.stderr).toMatch(/--out must name a \.obj or \.glb file \(got '.*sphere_cage\.gltf': \.gltf cannot be written\)/);
    expect(refused.stderr).not.toMatch(/^cage: \d+%$/m);
    expect(existsSync(gltf)).toBe(false);
  });

  it('prints help, and exits 2 on bad usage', () => {
    expect(run('cage', '--help').stdout).toMatch(/--vertices K/);
    expect(run('cage', join(dir, 'sphere.obj'), '--out', join(dir, 'x.obj')).status).toBe(2);
    expect(run('cage', join(dir, 'sphere.obj'), '--vertices', 'ten', '--out', join(dir, 'x.obj')).status).toBe(2);
  });

  it.skipIf(!haveSpot)('cages ../shared/data/spot.obj with 50 vertices (skipped when ../shared/data is absent)', () => {
    const out = join(dir, 'spot_cage.obj');
    const result = run('cage', join(sharedData, 'spot.obj'), '--vertices', '50', '--out', out);
    expect(result.status, result.stderr).toBe(0);
    const mesh = readMesh(solver, readFileSync(join(sharedData, 'spot.obj')), 'spot.obj');
    expectValidCage(mesh, readMesh(solver, readFileSync(out), 'spot_cage.obj'), 50);
  });
});
