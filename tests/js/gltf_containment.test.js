// Untrusted glTF stays contained (issue 32): a .gltf and a scene name files only in their own folder and below
// (CLI, library, scene parser), and hostile documents -- a 10,000-deep node chain, a malformed % escape, a large
// base64 data: URI, a million objects, a mesh instanced past the vertex limit -- end in a named error or a
// correct read, in seconds and bounded memory. The hostile files are generated here, never committed.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { containedPath, parseScene, readGltf, writeGltf } from 'subspace-deform';
import { MAX_GLTF_OBJECTS } from '../../web/lib/gltf_check.js';
import { resolveResources } from '../../web/lib/gltf_resources.js';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const run = (args, nodeOptions = []) => spawnSync(process.execPath, [...nodeOptions, cli, ...args], { encoding: 'utf8', timeout: 60000 });
const triangleBytes = Buffer.from(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]).buffer);
const dataUri = (bytes) => `data:application/octet-stream;base64,${Buffer.from(bytes).toString('base64')}`;

// One triangle whose buffer is `uri`.
function triangle(uri = dataUri(triangleBytes)) {
  return { asset: { version: '2.0' }, buffers: [{ byteLength: 36, uri }], bufferViews: [{ buffer: 0, byteLength: 36 }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3' }], meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
    nodes: [{ mesh: 0 }], scenes: [{ nodes: [0] }], scene: 0 };
}
const encode = (json) => new TextEncoder().encode(JSON.stringify(json));

let dir;
beforeAll(() => {
  dir = mkdtempSync(join(tmpdir(), 'sd-contain-'));
  mkdirSync(join(dir, 'model', 'sub'), { recursive: true });
  writeFileSync(join(dir, 'secret.bin'), triangleBytes);
  writeFileSync(join(dir, 'model', 'sub', 'tri.bin'), triangleBytes);
});
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('files named outside the folder are refused', () => {
  it.each([
    ['../secret.bin', /climbs out of its folder/],
    ['..%2Fsecret.bin', /climbs out of its folder/],
    ['sub/../../secret.bin', /climbs out of its folder/],
    ['/SECRET', /an absolute path/],
    ['file:///SECRET', /an absolute URI/],
    ['C:%5Csecret.bin', /an absolute URI or drive/],
  ])('the CLI refuses a buffer at %s, and deform writes no --out', (uri, pattern) => {
    const abs = join(dir, 'secret.bin');
    const name = `u${encodeURIComponent(uri).slice(0, 20).replace(/%/g, '_')}.gltf`;
    writeFileSync(join(dir, 'model', name), JSON.stringify(triangle(uri.replace('SECRET', abs.slice(1)))));
    const check = run(['check', join(dir, 'model', name)]);
    expect(check.status).toBe(1);
    expect(check.stderr).toMatch(/^error \(unreadable_file\): .*buffer 0 names ".*secret\.bin", /);
    expect(check.stderr).toMatch(pattern);
    expect(check.stderr).toMatch(/a file may name only files in its own folder and below/);
    writeFileSync(join(dir, 'model', 'scene.json'), JSON.stringify({ mesh: name, handles: [{ vertices: [0] }], subspace: { basis: 'spectral', modes: 2 } }));
    const out = join(dir, 'leak.glb');
    const deform = run(['deform', join(dir, 'model', 'scene.json'), '--out', out]);
    expect(deform.status).toBe(1);
    expect(deform.stderr).toMatch(/a file may name only files in its own folder and below/);
    expect(existsSync(out)).toBe(false);
  });

  it('the CLI reads a buffer in a subfolder', () => {
    writeFileSync(join(dir, 'model', 'inside.gltf'), JSON.stringify(triangle('sub/./tri.bin')));
    const r = run(['check', join(dir, 'model', 'inside.gltf')]);
    expect(r.stdout).toMatch(/vertices 3, faces 1/);
  });

  it('the library refuses an outside file even when it is given by name, and takes one inside', async () => {
    const given = { 'secret.bin': triangleBytes, 'tri.bin': triangleBytes };
    const outside = readGltf(encode(triangle('../secret.bin')), 'm.gltf', { resources: given });
    await expect(outside).rejects.toMatchObject({ name: 'InputError', code: 'unreadable_file' });
    await expect(outside).rejects.toThrow(/m\.gltf: buffer 0 names "\.\.\/secret\.bin", which climbs out of its folder/);
    const image = { ...triangle(), images: [{ uri: '/etc/passwd' }] };
    await expect(readGltf(encode(image), 'm.gltf', { resources: given })).rejects.toThrow(/image 0 names "\/etc\/passwd", an absolute path/);
    const inside = await readGltf(encode(triangle('sub/tri.bin')), 'm.gltf', { resources: given });
    expect(inside.mesh.positions.length).toBe(9);
  });

  it.each(['constructor', 'toString', '__proto__'])('a buffer in a separate file named %s is a file that was not given', async (name) => {
    // Not a member of Object.prototype found in the plain object of given files (that read as a file of NaN GB).
    const read = readGltf(encode(triangle(name)), 'm.gltf', { resources: { 'tri.bin': triangleBytes } });
    await expect(read).rejects.toMatchObject({ name: 'InputError', code: 'unreadable_file' });
    await expect(read).rejects.toThrow(new RegExp(`buffer 0 is in the separate file "${name}", which was not given`));
  });

  it.each([
    ['../m.obj', 'mesh', /scene: "mesh" names "\.\.\/m\.obj", which climbs out of its folder/],
    ['/home/user/m.obj', 'mesh', /an absolute path/],
    ['C:\\m.obj', 'cage', /scene: "cage" names .*an absolute URI or drive/],
    ['a\\..\\..\\m.obj', 'cage', /climbs out of its folder/],
  ])('a scene may not name %s as its %s', (path, key, pattern) => {
    const scene = { mesh: 'm.obj', handles: [], [key]: path };
    expect(() => parseScene(scene)).toThrow(pattern);
  });

  it('a scene may name models in its folder and below', () => {
    expect(parseScene({ mesh: 'models/./m.obj', cage: 'models/cages/../c.obj', handles: [] }).mesh).toBe('models/./m.obj');
    expect(containedPath('a/./b/../c.bin', 'x')).toBe('a/c.bin');
  });
});

describe('hostile documents: a named error or a correct read, in seconds', () => {
  it('reads a 10,000-deep node chain (no call stack overflow) and writes it back', async () => {
    const json = triangle();
    const depth = 10000;
    json.nodes = Array.from({ length: depth }, (_, i) => (i + 1 < depth ? { children: [i + 1], translation: [1, 0, 0] } : { mesh: 0 }));
    const { mesh, gltf } = await readGltf(encode(json), 'deep.gltf');
    expect(Array.from(mesh.positions.subarray(0, 3))).toEqual([depth - 1, 0, 0]); // every ancestor's translation
    const back = await readGltf(await writeGltf(gltf, mesh.positions, mesh.indices), 'deep.glb');
    expect(back.mesh.positions[3]).toBeCloseTo(depth, 6);
  });

  it('names a uri with a malformed % escape (library and CLI)', async () => {
    const bad = readGltf(encode(triangle('a%E0%A4%A.bin')), 'pct.gltf', { resources: {} });
    await expect(bad).rejects.toMatchObject({ name: 'InputError', code: 'parse_error' });
    await expect(bad).rejects.toThrow(/pct\.gltf: buffer 0 has the uri "a%E0%A4%A\.bin", whose % escapes are malformed/);
    writeFileSync(join(dir, 'model', 'pct.gltf'), JSON.stringify(triangle('a%E0%A4%A.bin')));
    expect(run(['check', join(dir, 'model', 'pct.gltf')]).stderr).toMatch(/^error \(parse_error\): pct\.gltf: buffer 0 has the uri "a%E0%A4%A\.bin"/);
  });

  it('decodes a 40 MB base64 image without per-byte arrays: check runs in a 256 MB heap', () => {
    const json = { ...triangle(), images: [{ uri: `data:image/png;base64,${Buffer.alloc(40e6, 7).toString('base64')}` }] };
    writeFileSync(join(dir, 'model', 'image.gltf'), JSON.stringify(json));
    const started = performance.now();
    const r = run(['check', join(dir, 'model', 'image.gltf')], ['--max-old-space-size=256']);
    expect(r.stderr).not.toMatch(/heap|internal/);
    expect(r.stdout).toMatch(/vertices 3, faces 1/);
    expect(performance.now() - started).toBeLessThan(20000);
  }, 60000);

  it('refuses resources beyond the limit by their size, before decoding them', () => {
    const json = { ...triangle(), images: [{ uri: 'data:image/png;base64,' + 'A'.repeat(4000) }] };
    expect(() => resolveResources(json, null, {}, 'big.gltf', { maxBytes: 1000 })).toThrow(
      expect.objectContaining({ code: 'file_too_large', message: expect.stringMatching(/big\.gltf with its resources up to buffer 0 .*is larger|image 0 \(a data: URI\) is 3.04 kB/) }));
    const given = { 'a.bin': new Uint8Array(800) };
    const twice = { ...triangle('a.bin'), images: [{ uri: 'a.bin' }] };
    expect(() => resolveResources(twice, null, given, 'two.gltf', { maxBytes: 1000 })).toThrow(/two\.gltf with its resources up to image 0 \("a\.bin"\) is 1.60 kB/);
  });

  it(`refuses more than ${MAX_GLTF_OBJECTS} objects (a million unused accessors took 40 s and 3 GB) at once`, async () => {
    const json = triangle();
    for (let i = 0; i < MAX_GLTF_OBJECTS; ++i) json.accessors.push(json.accessors[0]);
    const started = performance.now();
    const many = readGltf(encode(json), 'many.gltf');
    await expect(many).rejects.toMatchObject({ name: 'InputError', code: 'parse_error' });
    await expect(many).rejects.toThrow(/many\.gltf: it declares \d+ objects .*more than the 131072 a model may have here/);
    expect(performance.now() - started).toBeLessThan(3000);
  });

  it('refuses a mesh instanced past 2^24 vertices, and a scene listing a node twice or a child', async () => {
    const count = 1026; // whole triangles (a count not a multiple of 3 is refused first)
    const positions = Buffer.from(new Float32Array(3 * count).map((_, i) => i % 7).buffer);
    const json = triangle(dataUri(positions));
    json.buffers[0].byteLength = json.bufferViews[0].byteLength = positions.length;
    json.accessors[0].count = count;
    json.nodes = Array.from({ length: 2 ** 14 + 1 }, () => ({ mesh: 0 }));
    json.scenes = [{ nodes: json.nodes.map((_, i) => i) }];
    await expect(readGltf(encode(json), 'inst.gltf')).rejects.toThrow(/inst\.gltf: its scene has 16811010 vertices \(a mesh counts once per node that uses it\): more than the 16777216/);
    const twice = { ...triangle(), scenes: [{ nodes: [0, 0] }] };
    await expect(readGltf(encode(twice), 't.gltf')).rejects.toThrow(/scene 0 lists node 0 twice/);
    const child = { ...triangle(), nodes: [{ children: [1] }, { mesh: 0 }], scenes: [{ nodes: [0, 1] }] };
    await expect(readGltf(encode(child), 'c.gltf')).rejects.toThrow(/scene 0 lists node 1, which is not a root \(it is a child of node 0\)/);
  });
});
