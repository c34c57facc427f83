// The `check` command as a user runs it: a child process, real files, exit codes and messages.
import { describe, expect, it, beforeAll, afterAll } from 'vitest';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { CapsuleGeometry } from 'three';
import { loadSolver, makeExample, writeObj } from 'subspace-deform';
import { welded } from './support/three_models.js';
import { outsideRows, unusedOutside, unusedOutsideText } from '../../scripts/cli/unused_outside.mjs';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const sharedData = new URL('../../../shared/data', import.meta.url).pathname;
let dir;
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 60000 });

beforeAll(async () => {
  const solver = await loadSolver();
  dir = mkdtempSync(join(tmpdir(), 'sd-cli-'));
  const { mesh, cage } = makeExample(solver, 'bar');
  writeFileSync(join(dir, 'bar.obj'), writeObj(solver, mesh));
  writeFileSync(join(dir, 'bar_cage.obj'), writeObj(solver, cage));
  writeFileSync(join(dir, 'open.obj'), 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n');
  // A tetrahedron with a fin on edge 2-3: three faces there, which no pairing can split.
  writeFileSync(join(dir, 'fin.obj'), 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 2 3 5\n');
  // A tetrahedron with each face's own corners (non-indexed, as a flat-shaded export) and a vertex no face uses.
  const corners = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]];
  const faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
  const split = faces.flatMap((f) => f.map((v) => `v ${corners[v].join(' ')}`)).join('\n');
  writeFileSync(join(dir, 'split.obj'), `${split}\nv 0.2 0.2 0.2\n${faces.map((_, k) => `f ${3 * k + 1} ${3 * k + 2} ${3 * k + 3}`).join('\n')}\n`);
  writeFileSync(join(dir, 'nan.obj'), 'v 0 0 nan\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n');
  // Two capsules (seams welded), the second 0.5 along x so that they overlap, joined as one mesh: a valid
  // model of two components whose surfaces cross each other.
  const capsule = welded(new CapsuleGeometry(0.4, 1.2, 6, 16));
  const p = capsule.getAttribute('position').array, f = capsule.index.array, n = p.length / 3;
  const positions = Float64Array.from([...p, ...Array.from(p, (x, k) => (k % 3 === 0 ? x + 0.5 : x))]);
  const indices = Uint32Array.from([...f, ...Array.from(f, (v) => v + n)]);
  writeFileSync(join(dir, 'capsules.obj'), writeObj(solver, { positions, indices }));
  // glTF files that must be refused by name before anything is allocated from them.
  const triangle = { asset: { version: '2.0' }, buffers: [{ byteLength: 36, uri: 'lost.bin' }], bufferViews: [{ buffer: 0, byteLength: 36 }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3' }], meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
    nodes: [{ mesh: 0 }], scenes: [{ nodes: [0] }] };
  writeFileSync(join(dir, 'lost.gltf'), JSON.stringify(triangle));
  writeFileSync(join(dir, 'draco.gltf'), JSON.stringify({ ...triangle, extensionsUsed: ['KHR_draco_mesh_compression'], extensionsRequired: ['KHR_draco_mesh_compression'] }));
  writeFileSync(join(dir, 'huge.gltf'), JSON.stringify({ ...triangle, buffers: [{ byteLength: 36, uri: `data:application/octet-stream;base64,${Buffer.alloc(36).toString('base64')}` }],
    accessors: [{ ...triangle.accessors[0], count: 2 ** 30 }] }));
  writeFileSync(join(dir, 'garbage.stl'), Buffer.from(Array.from({ length: 300 }, (_, i) => (i * 7919) % 256)));
  // The cage shifted so that the bar sticks out of it.
  const shifted = cage.positions.slice();
  for (let i = 0; i < shifted.length; i += 3) shifted[i] += 1.0;
  writeFileSync(join(dir, 'shifted_cage.obj'), writeObj(solver, { positions: shifted, indices: cage.indices }));
  // The cage with one corner pushed through to the far side: its faces cross the others.
  const crossed = cage.positions.slice();
  for (let a = 0; a < 3; ++a) crossed[a] *= -1.6;
  writeFileSync(join(dir, 'crossed_cage.obj'), writeObj(solver, { positions: crossed, indices: cage.indices }));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('deform.mjs check', () => {
  it('prints --help and exits 0', () => {
    const r = run('check', '--help');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/usage: .*check <mesh> \[cage\]/);
  });

  it('summarises a valid mesh in its cage and exits 0', () => {
    const r = run('check', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'));
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/vertices \d+, faces \d+, edges \d+, components 1, genus 0/);
    expect(r.stdout).toMatch(/volume/);
    expect(r.stdout).toMatch(/^valid$/m);
  });

  it('--quality over the memory budget keeps the report: valid, the quality skipped with a warning naming the flag', () => {
    const r = run('check', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'), '--quality', '--memory-budget', '0.5', '--json');
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    const report = JSON.parse(r.stdout);
    expect(report.ok).toBe(true);
    expect(report.cageQuality).toBeUndefined();
    const skipped = report.findings.find((f) => f.code === 'cage_quality_skipped');
    expect(skipped.severity).toBe('warning');
    expect(skipped.message).toMatch(/over the memory budget of 0\.50 MB.*raise the budget \(--memory-budget MB\)/);
    expect(run('check', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'), '--quality', '--memory-budget', '2', '--json').stdout).toMatch(/"cageQuality"/);
  });

  it('a switch given a value is bad usage, not true (--json=no printed JSON, --float32=false wrote float32)', () => {
    const r = run('check', join(dir, 'bar.obj'), '--json=no');
    expect(r.status).toBe(2);
    expect(r.stdout).toBe('');
    expect(r.stderr).toMatch(/^usage error: --json=no is a switch and takes no value/);
    const w = run('weights', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'), '--out', join(dir, 'w32.npy'), '--float32=false');
    expect(w.status).toBe(2);
    expect(existsSync(join(dir, 'w32.npy'))).toBe(false);
  });

  it('--memory-budget is for --quality and at least 0.01 MB (usage errors)', () => {
    expect(run('check', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'), '--memory-budget', '2').status).toBe(2);
    const tiny = run('check', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'), '--quality', '--memory-budget', '1e-300');
    expect(tiny.status).toBe(2);
    expect(tiny.stderr).toMatch(/--memory-budget must be a number from 0\.01/);
  });

  it('--quality needs a cage (a usage error, as --memory-budget without --quality is)', () => {
    const r = run('check', join(dir, 'bar.obj'), '--quality');
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(/--quality needs a cage/);
    expect(r.stdout).toBe('');
  });

  it('reports the cage quality with --quality (a snug bar cage: no warning)', () => {
    const r = run('check', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'), '--quality', '--json');
    expect(r.status).toBe(0);
    const q = JSON.parse(r.stdout).cageQuality;
    expect(q.cageVertices).toBe(28);
    expect(q.weakVertices).toBe(0);
    expect(q.influenceRatio).toBeGreaterThan(1e-6);
    expect(q.volumeRatio).toBeGreaterThan(1);
    expect(q).toMatchObject({ poor: false, warnings: [] });
    expect(run('check', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'), '--quality').stdout)
      .toMatch(/cage quality: 0 of 28 cage vertices weak .* influence ratio \d\.\d+e-\d+, volume ratio \d/);
  });

  it.skipIf(!existsSync(join(sharedData, 'cow.obj')))('warns about the cow\'s cage (skipped without ../shared/data)', () => {
    const r = run('check', join(sharedData, 'cow.obj'), join(sharedData, 'cow_cage.obj'), '--quality');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/warning \(weak_cage_motions\): poor cage: \d+ motions of the cage barely move the mesh \(influence ratio \d\.\de-09/);
  });

  // Issue 31, item 4: handbones and the cow were called valid without a word about their crossing faces.
  it('warns with a code about a mesh whose surface crosses itself, and still calls it valid', () => {
    const r = run('check', join(dir, 'capsules.obj'));
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/warning \(mesh_self_intersecting\): mesh: (at least )?\d+ pairs of faces intersect \(first: faces \d+ and \d+/);
    expect(r.stdout).toMatch(/^valid$/m);
    const json = JSON.parse(run('check', join(dir, 'capsules.obj'), '--json').stdout);
    expect(json.ok).toBe(true);
    expect(json.findings.filter((f) => f.code === 'mesh_self_intersecting')).toHaveLength(1);
    // Meshes that do not cross themselves get no such warning: the bar, alone and in its cage.
    expect(run('check', join(dir, 'bar.obj')).stdout).not.toMatch(/self_intersecting/);
    expect(run('check', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj')).stdout).not.toMatch(/self_intersecting/);
  });

  it('accepts an open mesh with a note on its capped hole', () => {
    const r = run('check', join(dir, 'open.obj'));
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/note \(open\): mesh: the mesh is open: 3 boundary edges around 1 hole/);
    expect(r.stdout).toMatch(/volume 0\.166666\d* \(1 hole capped\)/);
    expect(r.stdout).toMatch(/^valid$/m);
  });

  it('reads a .gltf with its buffer in a .bin beside it', () => {
    // A tetrahedron: 4 float32 positions and 12 uint16 indices in tet.bin, named by the JSON.
    const positions = Buffer.from(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]).buffer);
    const indices = Buffer.from(new Uint16Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]).buffer);
    writeFileSync(join(dir, 'tet.bin'), Buffer.concat([positions, indices]));
    writeFileSync(join(dir, 'tet.gltf'), JSON.stringify({ asset: { version: '2.0' }, buffers: [{ byteLength: 72, uri: 'tet.bin' }],
      bufferViews: [{ buffer: 0, byteLength: 48 }, { buffer: 0, byteOffset: 48, byteLength: 24 }],
      accessors: [{ bufferView: 0, componentType: 5126, count: 4, type: 'VEC3' }, { bufferView: 1, componentType: 5123, count: 12, type: 'SCALAR' }],
      meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }], nodes: [{ mesh: 0 }], scenes: [{ nodes: [0] }] }));
    const r = run('check', join(dir, 'tet.gltf'));
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/vertices 4, faces 4/);
    expect(r.stdout).toMatch(/^valid$/m);
  });

  it('welds split vertices and carries an unreferenced one, saying how many', () => {
    const r = run('check', join(dir, 'split.obj'));
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/for the solver: 4 vertices, 4 faces \(welded 8, unreferenced 1, collapsed faces 0, split 0\)/);
    expect(r.stdout).toMatch(/note \(welded\): mesh: 8 vertices at the same point as another/);
    expect(r.stdout).toMatch(/warning \(unreferenced_vertices\): mesh: 1 vertex used by no face \(first: 12\); they are carried along/);
    expect(r.stdout).toMatch(/genus 0/);
  });

  it('a vertex no face uses outside the cage: check warns that weights refuses it, weights says why (they disagreed)', () => {
    const bar = readFileSync(join(dir, 'bar.obj'), 'utf8');
    const far = bar.split('\n').filter((line) => line.startsWith('v ')).length;  // the new vertex's number
    writeFileSync(join(dir, 'bar_far.obj'), `${bar}\nv 50 50 50\n`);
    const r = run('check', join(dir, 'bar_far.obj'), join(dir, 'bar_cage.obj'));
    expect(r.status).toBe(0);
    expect(r.stdout).toContain(`warning (unused_outside_cage): mesh: 1 vertex used by no face is outside the cage (first: ${far}): ` +
      'deform carries such vertices along with their nearest triangles, but weights (with mean value coordinates, its default) refuses the pair');
    expect(r.stdout).toMatch(/^valid$/m);
    const w = run('weights', join(dir, 'bar_far.obj'), join(dir, 'bar_cage.obj'), '--out', join(dir, 'far.npy'));
    expect(w.status).toBe(1);
    expect(w.stderr).toContain(`error (mesh_outside_cage): mesh ${join(dir, 'bar_far.obj')}: 1 vertex used by no face is outside the cage (first: ${far}): W has a row for every vertex`);
    // Inside the cage, an unused vertex gets its row and no warning.
    writeFileSync(join(dir, 'bar_near.obj'), `${bar}\nv 0 0 0\n`);
    expect(run('check', join(dir, 'bar_near.obj'), join(dir, 'bar_cage.obj')).stdout).not.toContain('unused_outside_cage');
    expect(run('weights', join(dir, 'bar_near.obj'), join(dir, 'bar_cage.obj'), '--out', join(dir, 'near.npy')).status).toBe(0);
  });

  it('binds the unused vertices with the coordinates weights was asked for, and never fails on the message\'s wording', async () => {
    const solver = await loadSolver();
    const { mesh, cage } = makeExample(solver, 'bar');
    const far = { positions: Float64Array.from([...mesh.positions, 50, 50, 50]), indices: mesh.indices };
    const n = mesh.positions.length / 3;
    expect(unusedOutside(solver, far, cage)).toEqual({ count: 1, first: [n] });
    expect(unusedOutside(solver, far, cage, { coordinates: 'pmvc' })).toEqual({ count: 1, first: [n] });
    // The choice reaches the binding: a resolution it refuses is refused there (MVC, bound always, took it).
    expect(() => unusedOutside(solver, far, cage, { coordinates: 'pmvc', pmvcResolution: 1 })).toThrow(/pmvcResolution/);
    // A message in other words: the vertices are reported without a count, not as a failure.
    expect(outsideRows('weights: some mesh vertices lie beyond the cage')).toEqual({ count: null, rows: [] });
    expect(unusedOutsideText({ count: null, first: [] })).toBe('vertices used by no face are outside the cage');
    expect(outsideRows('W: 2 of 9 mesh vertices are outside the cage (first: 3, 7); ...')).toEqual({ count: 2, rows: [3, 7] });
  });

  it('refuses an output that is a .gltf input\'s external file (its buffer, named x.npy here: weights --out x.npy)', () => {
    const bin = Buffer.from(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]).buffer);
    writeFileSync(join(dir, 'ext.npy'), bin);
    writeFileSync(join(dir, 'ext.gltf'), JSON.stringify({ asset: { version: '2.0' }, buffers: [{ byteLength: 48, uri: 'ext.npy' }] }));
    const r = run('weights', join(dir, 'ext.gltf'), join(dir, 'bar_cage.obj'), '--out', join(dir, 'ext.npy'));
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(/--out '.*ext\.npy' is the same file as the mesh's file 'ext\.npy'/);
    expect(readFileSync(join(dir, 'ext.npy'))).toEqual(bin);
  });

  it('a cage split at seams (each face its own corners, as glTF exports a flat box) gets the advice to weld it', () => {
    // A box around the tetrahedra of open.obj: 6 faces of 4 corners each, 24 vertices at 8 points.
    const corner = (k) => [k & 1 ? 2 : -1, k & 2 ? 2 : -1, k & 4 ? 2 : -1];
    const quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    const lines = quads.flatMap((q) => q.map((k) => `v ${corner(k).join(' ')}`));
    quads.forEach((_, f) => lines.push(`f ${4 * f + 1} ${4 * f + 2} ${4 * f + 3}`, `f ${4 * f + 1} ${4 * f + 3} ${4 * f + 4}`));
    writeFileSync(join(dir, 'split_cage.obj'), `${lines.join('\n')}\n`);
    const advice = /16 of its vertices are at the same point as another \(split at seams[^)]*\), so its faces do not join: .*weld it/;
    const r = run('check', join(dir, 'open.obj'), join(dir, 'split_cage.obj'));
    expect(r.status).toBe(1);
    expect(r.stdout).toMatch(new RegExp(`error \\(cage_split_vertices\\): cage: ${advice.source}`));
    expect(r.stdout).not.toMatch(/each is deformed with the same cage/);
    const w = run('weights', join(dir, 'open.obj'), join(dir, 'split_cage.obj'), '--out', join(dir, 'split.npy'));
    expect(w.status).toBe(1);
    expect(w.stderr).toMatch(advice);
    writeFileSync(join(dir, 'split_scene.json'), JSON.stringify({ mesh: 'open.obj', cage: 'split_cage.obj', handles: [{ vertices: [0] }] }));
    const d = run('deform', join(dir, 'split_scene.json'), '--out', join(dir, 'split_out.obj'));
    expect(d.status).toBe(1);
    expect(d.stderr).toMatch(advice);
    expect(d.stderr).not.toMatch(/each is deformed with the same cage/);
  });

  it.each([
    ['a non-manifold edge', ['fin.obj'], /error \(non_manifold_edge\): mesh: 1 non-manifold edge/],
    ['NaN coordinates', ['nan.obj'], /finite|NaN/i],
    ['garbage bytes', ['garbage.stl'], /garbage\.stl/],
    ['vertices outside the cage', ['bar.obj', 'shifted_cage.obj'], /outside/],
    ['a self-intersecting cage', ['bar.obj', 'crossed_cage.obj'], /cage: \d+ pairs? of faces intersect \(first: faces \d+ and \d+/],
    ['missing file', ['nope.obj'], /cannot read .*nope\.obj: no such file/],
    ['a Draco-compressed glTF', ['draco.gltf'], /draco\.gltf: its geometry is compressed \(KHR_draco_mesh_compression\)/],
    ['a glTF whose buffer file is missing', ['lost.gltf'], /lost\.gltf: .*"lost\.bin"/],
    ['a glTF with a huge accessor count', ['huge.gltf'], /huge\.gltf: accessor 0 has count 1073741824/],
  ])('%s: exits 1 with a clear message, no crash', (_, files, pattern) => {
    const r = run('check', ...files.map((f) => join(dir, f)));
    expect(r.status).toBe(1);
    expect(r.stdout + r.stderr).toMatch(pattern);
    expect(r.stdout + r.stderr).not.toMatch(/Aborted|RuntimeError|at .*\.js:\d+/);
  });

  it('shows control characters from the files as escapes, never raw (an ESC sequence could clear the terminal)', () => {
    const esc = '\u001b[2J\u001b]0;PWNED\u0007';
    writeFileSync(join(dir, 'esc_uri.gltf'), JSON.stringify({ asset: { version: '2.0' }, buffers: [{ byteLength: 36, uri: `${esc}x.bin` }] }));
    writeFileSync(join(dir, 'esc_json.gltf'), `${esc}{}`);
    for (const [file, shown] of [['esc_uri.gltf', '"\\u001b[2J\\u001b]0;PWNED\\u0007x.bin"'], ['esc_json.gltf', "'\\u001b'"]]) {
      const r = run('check', join(dir, file));
      expect(r.status).toBe(1);
      expect(r.stderr).toContain(shown);
      expect(r.stderr).not.toMatch(/(?![\t\n])\p{Cc}/u);
    }
  });

  it('bad usage exits 2', () => {
    expect(run('check').status).toBe(2);
    expect(run('frobnicate').status).toBe(2);
    expect(run('check', 'a', '--bogus').status).toBe(2);
    // An empty path ("$MESH" unset) is bad usage too, not the file reader's invalid_argument (exit 1).
    const empty = run('check', join(dir, 'bar.obj'), '');
    expect(empty.status).toBe(2);
    expect(empty.stderr).toMatch(/^usage error: argument 2 is empty: a file path must not be empty/);
  });
});
