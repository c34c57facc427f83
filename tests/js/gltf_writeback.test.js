// glTF written back right and read strictly (issue 32, item 6): a mesh used by several nodes keeps each
// instance's own deformation (with its UVs and material), a node scaled by zero writes no NaN, the spec
// violations that were read without a word are named errors, and what glTF-Transform's internals said
// ("Cannot read properties of undefined (reading 'yfov')", "prevRef.dispose is not a function") is now a
// parse_error naming the object. Documents are built here around one unit box.
import { describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { WebIO } from '@gltf-transform/core';
import { InputError, checkMesh, loadSolver, meshToGlb, readGltf, writeGltf } from 'subspace-deform';
import { readerWarnings } from '../../web/lib/gltf_unknown.js';

const BOX = new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1]);
const UV = new Float32Array([0, 0, 1, 0, 1, 1, 0, 1, 0, 0, 1, 0, 1, 1, 0, 1]);
const FACES = new Uint16Array([0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7]);
const encode = (json) => new TextEncoder().encode(JSON.stringify(json));

// A box mesh (positions, UVs, indices, a material) used by one node per entry of `nodes`.
function boxes(nodes) {
  const bin = Buffer.concat([Buffer.from(BOX.buffer), Buffer.from(UV.buffer), Buffer.from(FACES.buffer)]);
  return {
    asset: { version: '2.0' },
    buffers: [{ byteLength: bin.length, uri: `data:application/octet-stream;base64,${bin.toString('base64')}` }],
    bufferViews: [{ buffer: 0, byteLength: 96 }, { buffer: 0, byteOffset: 96, byteLength: 64 }, { buffer: 0, byteOffset: 160, byteLength: 72 }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: 8, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 1] },
      { bufferView: 1, componentType: 5126, count: 8, type: 'VEC2' },
      { bufferView: 2, componentType: 5123, count: 36, type: 'SCALAR' },
    ],
    materials: [{ name: 'red', pbrMetallicRoughness: { baseColorFactor: [1, 0, 0, 1] } }],
    meshes: [{ name: 'box', primitives: [{ attributes: { POSITION: 0, TEXCOORD_0: 1 }, indices: 2, material: 0 }] }],
    nodes: nodes.map((node) => ({ mesh: 0, ...node })),
    scenes: [{ nodes: nodes.map((_, i) => i) }],
  };
}

// Moves every file vertex of instance k by offsets[k] (scene space).
function moved(mesh, gltf, offsets) {
  const positions = Float64Array.from(mesh.positions);
  gltf.instances.forEach((instance, k) => {
    for (let v = instance.start; v < instance.start + instance.count; ++v) for (let a = 0; a < 3; ++a) positions[3 * v + a] += offsets[k][a];
  });
  return positions;
}

const maxDifference = (a, b) => Math.max(...Array.from(a, (x, i) => Math.abs(x - b[i])));

describe('a mesh used by several nodes is written back per instance', () => {
  it('round-trips two instances deformed differently, each with its UVs and material', async () => {
    const { mesh, gltf } = await readGltf(encode(boxes([{}, { translation: [3, 0, 0], scale: [2, 2, 2] }])), 'two.gltf');
    const positions = moved(mesh, gltf, [[0, 0.5, 0], [0, 0, -1]]);
    positions[0] = -0.25; // and one vertex of instance 0 on its own
    const back = await readGltf(await writeGltf(gltf, positions, mesh.indices), 'two.glb');
    expect(maxDifference(back.mesh.positions, positions)).toBeLessThan(1e-6);
    expect(back.gltf.json.meshes).toHaveLength(2);
    for (const m of back.gltf.json.meshes) {
      const primitive = m.primitives[0];
      expect(primitive.material).toBe(0);
      expect(back.gltf.json.accessors[primitive.attributes.TEXCOORD_0].count).toBe(8);
    }
    // The UVs are shared, not copied.
    expect(back.gltf.json.meshes[0].primitives[0].attributes.TEXCOORD_0).toBe(back.gltf.json.meshes[1].primitives[0].attributes.TEXCOORD_0);
  });

  it('keeps one mesh for instances whose shapes in their node spaces are equal', async () => {
    const { mesh, gltf } = await readGltf(encode(boxes([{}, { translation: [3, 0, 0] }, { translation: [6, 0, 0] }])), 'three.gltf');
    const positions = moved(mesh, gltf, [[0, 1, 0], [0, 1, 0], [0, 0, 2]]);
    const back = await readGltf(await writeGltf(gltf, positions, mesh.indices), 'three.glb');
    expect(maxDifference(back.mesh.positions, positions)).toBeLessThan(1e-6);
    expect(back.gltf.json.meshes).toHaveLength(2);
    expect(back.gltf.json.nodes.map((n) => n.mesh)).toEqual([0, 0, 1]);
  });

  it('deforms only the default scene: a node of another scene using the same mesh keeps it as read (both were deformed)', async () => {
    const json = boxes([{ name: 'other' }, { name: 'model', translation: [3, 0, 0] }]);
    json.scenes = [{ nodes: [0] }, { nodes: [1] }];
    json.scene = 1;
    const { mesh, gltf } = await readGltf(encode(json), 'scenes.gltf');
    expect(gltf.instances.map((i) => i.node)).toEqual([1]);
    const written = await writeGltf(gltf, moved(mesh, gltf, [[0, 1, 0]]), mesh.indices);
    const back = await new WebIO().readBinary(written);
    const [other, model] = back.getRoot().listNodes();
    expect(other.getMesh()).not.toBe(model.getMesh());
    const position = (node) => Array.from(node.getMesh().listPrimitives()[0].getAttribute('POSITION').getArray());
    expect(position(other)).toEqual(Array.from(BOX));
    expect(position(model)).toEqual(Array.from(BOX, (x, i) => (i % 3 === 1 ? x + 1 : x)));
    // The kept copy shares the UVs and material.
    const [keep, deformed] = [other, model].map((n) => n.getMesh().listPrimitives()[0]);
    expect(keep.getAttribute('TEXCOORD_0')).toBe(deformed.getAttribute('TEXCOORD_0'));
    expect(keep.getMaterial()).toBe(deformed.getMaterial());
  });
});

describe('a node scaled by zero', () => {
  it.each([[[0, 0, 0]], [[1, 1, 0]]])('scale %j: read collapsed, written back with the file\'s own positions, no NaN', async (scale) => {
    const { mesh, gltf } = await readGltf(encode(boxes([{}, { scale, translation: [3, 0, 0] }])), 'zero.gltf');
    const positions = moved(mesh, gltf, [[0, 0, 1], [0, 0, 1]]);
    const bytes = await writeGltf(gltf, positions, mesh.indices);
    const back = await readGltf(bytes, 'zero.glb');
    expect(back.mesh.positions.every(Number.isFinite)).toBe(true);
    expect(maxDifference(back.mesh.positions.subarray(0, 24), positions.subarray(0, 24))).toBeLessThan(1e-6);
    expect(maxDifference(back.mesh.positions.subarray(24), mesh.positions.subarray(24))).toBeLessThan(1e-6); // as in the file
  });

  // Flattened on one axis, the instance used to reach the solver as a surface pressed onto itself (duplicate faces,
  // non-manifold edges: the whole model invalid); now, as on every axis, it is left out and carried along.
  it.each([[[1, 1, 0]], [[0, 2, 0]], [[0, 0, 0]]])('scale %j: the instance is left out of the solve, the model valid', async (scale) => {
    const { mesh } = await readGltf(encode(boxes([{}, { scale, translation: [3, 0, 0] }])), 'flat.gltf');
    expect(Array.from(mesh.positions.subarray(24))).toEqual(Array.from({ length: 24 }, (_, i) => (i % 3 === 0 ? 3 : 0)));
    const report = checkMesh(await loadSolver(), mesh);
    expect(report.ok).toBe(true);
    expect(report.findings.map((f) => f.code)).toContain('unreferenced_vertices');
  });

  it('the CLI writes no NaN for it (deform --out x.glb)', () => {
    const dir = mkdtempSync(join(tmpdir(), 'sd-zero-'));
    try {
      writeFileSync(join(dir, 'boxes.gltf'), JSON.stringify(boxes([{}, { scale: [0, 0, 0] }, { translation: [3, 0, 0] }])));
      writeFileSync(join(dir, 'scene.json'), JSON.stringify({ mesh: 'boxes.gltf',
        handles: [{ vertices: [0, 1, 2, 3] }, { vertices: [4, 5, 6, 7], translate: [0, 0, 0.5] }, { vertices: [16, 17, 18, 19] }] }));
      const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
      const r = spawnSync(process.execPath, [cli, 'deform', join(dir, 'scene.json'), '--out', join(dir, 'out.glb')], { encoding: 'utf8', timeout: 60000 });
      expect(r.stderr).toBe('');
      return readGltf(new Uint8Array(readFileSync(join(dir, 'out.glb'))), 'out.glb').then(({ mesh }) => {
        expect(mesh.positions.every(Number.isFinite)).toBe(true);
        expect(Math.max(...mesh.positions.subarray(12, 24).filter((_, i) => i % 3 === 2))).toBeGreaterThan(1.2); // instance 0 stretched
      });
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }
  });

  it('refuses coordinates beyond float32\'s range instead of writing infinity or the file\'s own positions', async () => {
    const { mesh, gltf } = await readGltf(encode(boxes([{}, { translation: [3, 0, 0] }])), 'far.gltf');
    const positions = Float64Array.from(mesh.positions);
    positions[3 * 9] = 1e150;  // vertex 9: the second instance's vertex 1
    await expect(writeGltf(gltf, positions, mesh.indices)).rejects.toThrow(/node 1 \(mesh 0, primitive 0\).*vertex 9 has the coordinate 1e\+150, beyond float32's range/);
    await expect(meshToGlb({ positions, indices: mesh.indices })).rejects.toThrow(/meshToGlb: vertex 9 has the coordinate 1e\+150, beyond float32's range/);
    await expect(meshToGlb({ positions: Float64Array.from(mesh.positions, (x) => x * 1e30), indices: mesh.indices })).resolves.toBeInstanceOf(Uint8Array);
  });

  it('refuses a coordinate that is NaN in its node\'s space although finite in the scene (Math.abs(NaN) > max is false)', async () => {
    // Scaled by 1e-300 along a turned x: the inverse's x row is 1e300 (cos, sin, 0), and 1e10 * 1e300 overflows to
    // +infinity in one term and -infinity in the other.
    const turn = [0, 0, Math.sin(Math.PI / 8), Math.cos(Math.PI / 8)];
    const { mesh, gltf } = await readGltf(encode(boxes([{ rotation: turn, scale: [1e-300, 1, 1] }])), 'thin.gltf');
    const positions = Float64Array.from(mesh.positions);
    positions[0] = 1e10;
    positions[1] = -1e10;
    await expect(writeGltf(gltf, positions, mesh.indices)).rejects.toThrow(/node 0 .*vertex 0 has the coordinate NaN/);
  });

  it('writeGltf refuses positions that are not finite', async () => {
    const { mesh, gltf } = await readGltf(encode(boxes([{}])), 'one.gltf');
    const positions = Float64Array.from(mesh.positions);
    positions[7] = NaN;
    await expect(writeGltf(gltf, positions, mesh.indices)).rejects.toThrow(/writeGltf: vertex 2 has a position that is not finite/);
  });
});

describe('spec violations and what glTF-Transform said are named errors', () => {
  const sparse = (j) => {
    // Sparse indices [900] (uint16) and values for a POSITION of count 8: an index past the accessor.
    const extra = Buffer.concat([Buffer.from(new Uint16Array([900, 0]).buffer), Buffer.from(new Float32Array([9, 9, 9]).buffer)]);
    j.buffers.push({ byteLength: extra.length, uri: `data:application/octet-stream;base64,${extra.toString('base64')}` });
    j.bufferViews.push({ buffer: 1, byteLength: 4 }, { buffer: 1, byteOffset: 4, byteLength: 12 });
    j.accessors[0].sparse = { count: 1, indices: { bufferView: 3, componentType: 5123 }, values: { bufferView: 4 } };
  };
  it.each([
    ['a sparse index >= count', sparse, /accessor 0: sparse index 900 >= count 8/],
    ['byteStride 4 on a VEC3 float view', (j) => { j.bufferViews[0].byteStride = 4; }, /accessor 0 \(VEC3 of 12 bytes\) does not fit in the byteStride 4 of buffer view 0/],
    ['a byteStride on an index view', (j) => { j.bufferViews[2].byteStride = 4; j.accessors[2].count = 18; }, /mesh 0 primitive 0: its indices \(accessor 2\) lie in buffer view 2, which has a byteStride/],
    ['35 triangle indices', (j) => { j.accessors[2].count = 35; }, /mesh 0 primitive 0: 35 indices for triangles \(not a multiple of 3\)/],
    ['8 vertices as unindexed triangles', (j) => { delete j.meshes[0].primitives[0].indices; }, /mesh 0 primitive 0: 8 vertices without indices for triangles/],
    ['a perspective camera without "perspective"', (j) => { j.cameras = [{ type: 'perspective' }]; j.nodes[0].camera = 0; }, /camera 0 is perspective but has no "perspective"/],
    ['an orthographic camera without "orthographic"', (j) => { j.cameras = [{ type: 'orthographic' }]; }, /camera 0 is orthographic but has no "orthographic"/],
    ['an attribute named "constructor"', (j) => { j.meshes[0].primitives[0].attributes.constructor = 1; }, /meshes\[0\]\.primitives\[0\]\.attributes has the key "constructor"/],
    ['a morph target named "toString"', (j) => { j.meshes[0].primitives[0].targets = [{ toString: 0 }]; }, /targets\[0\] has the key "toString"/],
    ['a material\'s missing texture', (j) => { j.materials[0].pbrMetallicRoughness.baseColorTexture = { index: 2 }; }, /material 0: baseColorTexture refers to texture 2, which does not exist/],
    ['a primitive\'s missing material', (j) => { j.meshes[0].primitives[0].material = 4; }, /mesh 0 primitive 0 refers to material 4, which does not exist/],
    ['a skin joint that does not exist', (j) => { j.skins = [{ joints: [5] }]; j.nodes[0].skin = 0; }, /skin 0: a joint refers to node 5/],
    ['an animation channel without a target', (j) => { j.animations = [{ channels: [{ sampler: 0 }], samplers: [{ input: 1, output: 0 }] }]; }, /animation 0 channel 0 has no target with a path/],
  ])('%s', async (_, edit, pattern) => {
    const json = boxes([{}]);
    edit(json);
    const error = await readGltf(encode(json), 'bad.gltf').then(() => null, (e) => e);
    expect(error).toBeInstanceOf(InputError);
    expect(error.code).toBe('parse_error');
    expect(error.message).toMatch(/^bad\.gltf: /);
    expect(error.message).toMatch(pattern);
    expect(error.message).not.toMatch(/Cannot read|is not a function|cannot be read/);
  });
});

// What a viewer shows as the rest shape and the reader would read otherwise: refused by node, not deformed
// silently as another surface (skins posed elsewhere, morph weights, required GPU instancing, a sheared matrix).
describe('a rest shape the reader cannot read as shown is refused', () => {
  const skinned = (nodeTranslation, jointTranslation) => (j) => {
    Object.assign(j.nodes[0], { skin: 0, translation: nodeTranslation });
    j.nodes.push({ name: 'joint', translation: jointTranslation });
    j.scenes[0].nodes.push(1);
    j.skins = [{ joints: [1] }]; // no inverse bind matrices: identity
  };
  const morph = (meshWeights, nodeWeights) => (j) => {
    j.meshes[0].primitives[0].targets = [{ POSITION: 0 }];
    j.meshes[0].weights = meshWeights;
    if (nodeWeights) j.nodes[0].weights = nodeWeights;
  };
  const required = (extension) => (j) => {
    j.extensionsUsed = [extension];
    j.extensionsRequired = [extension];
  };
  const read = async (edit) => {
    const json = boxes([{}]);
    edit(json);
    return readGltf(encode(json), 'shape.gltf').then(({ mesh }) => mesh, (e) => e);
  };

  it.each([
    ['a skinned node its joints place elsewhere', skinned([10, 0, 0], [0, 0, 0]), /node 0 is a skinned mesh whose joint 0 poses it elsewhere than the node's transform places it/],
    ['a skin with fewer inverse bind matrices than joints', (j) => {
      skinned([0, 0, 0], [0, 0, 0])(j);
      j.nodes.push({ name: 'joint 2' });
      j.nodes[1].children = [2];
      j.skins[0].joints.push(2);
      j.skins[0].inverseBindMatrices = 3; // one MAT4 made of the 16 floats of UVs 0-7
      j.accessors.push({ bufferView: 1, componentType: 5126, count: 1, type: 'MAT4' });
    }, /node 0: its skin has 1 inverse bind matrices for 2 joints/],
    ['default morph weights', morph([0.5]), /node 0 \(mesh 0\) gives morph target 0 the weight 0\.5: .*set the weights to 0/],
    ['a node\'s morph weights over the mesh\'s', morph([0], [0.25]), /node 0 \(mesh 0\) gives morph target 0 the weight 0\.25/],
    ['required EXT_mesh_gpu_instancing', required('EXT_mesh_gpu_instancing'), /requires EXT_mesh_gpu_instancing .*only one deformed/],
    ['a sheared node matrix', (j) => { j.nodes[0].matrix = [1, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1]; }, /node 0 has a matrix that is not a translation, rotation and scale/],
    ['a projective node matrix', (j) => { j.nodes[0].matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 1]; }, /node 0 has a matrix that is not a translation, rotation and scale/],
  ])('%s', async (_, edit, pattern) => {
    const error = await read(edit);
    expect(error).toBeInstanceOf(InputError);
    expect(error.code).toBe('parse_error');
    expect(error.message).toMatch(/^shape\.gltf: /);
    expect(error.message).toMatch(pattern);
  });

  it.each([
    ['a skinned node at its bind pose', skinned([10, 0, 0], [10, 0, 0]), 11],
    ['morph weights of 0', morph([0]), 1],
    ['a node\'s zero weights over the mesh\'s', morph([0.5], [0]), 1],
    ['weights that are not a list', (j) => { morph([0])(j); j.nodes[0].weights = 'heavy'; }, 1],
    ['EXT_mesh_gpu_instancing only used', (j) => { j.extensionsUsed = ['EXT_mesh_gpu_instancing']; }, 1],
    ['a matrix of a rotation, scale and translation', (j) => { j.nodes[0].matrix = [0, 1, 0, 0, -2, 0, 0, 0, 0, 0, 3, 0, 10, 2, 3, 1]; }, 10],
  ])('reads %s (the box\'s largest x as shown)', async (_, edit, largestX) => {
    const mesh = await read(edit);
    expect(mesh.positions).toBeInstanceOf(Float64Array);
    expect(Math.max(...mesh.positions.filter((_, i) => i % 3 === 0))).toBeCloseTo(largestX, 5);
  });
});

describe('what glTF-Transform does not know is written back as it was', () => {
  // A VRM-like file: extensions no glTF-Transform class reads, extras everywhere, a camera without zfar (an
  // infinite projection). They used to be dropped (zfar written as 100) and "Missing optional extension" printed.
  const withUnknown = () => {
    const json = boxes([{}, { translation: [3, 0, 0] }]);
    Object.assign(json, { extensionsUsed: ['VRMC_vrm', 'EXT_foo'], extensions: { VRMC_vrm: { specVersion: '1.0', meta: { name: 'avatar' } }, EXT_foo: { a: 1 } },
      extras: { rootExtra: 42 }, cameras: [{ type: 'perspective', perspective: { yfov: 1, znear: 0.1 } }] });
    Object.assign(json.nodes[0], { extras: { nodeExtra: true }, extensions: { EXT_foo: { n: 1 } } });
    json.meshes[0].extras = { meshExtra: 1 };
    Object.assign(json.meshes[0].primitives[0], { extras: { primExtra: 'p' }, extensions: { EXT_foo: { p: 2 } } });
    json.materials[0].extensions = { VRMC_materials_mtoon: { specVersion: '1.0' } };
    return json;
  };

  it('keeps unknown extensions and extras at the root, nodes, meshes (and their copies), primitives and materials, and the camera', async () => {
    const { mesh, gltf } = await readGltf(encode(withUnknown()), 'vrm.gltf');
    expect(gltf.warnings.map((w) => w.code)).toEqual(['gltf_extension_kept_uninterpreted']);
    expect(gltf.warnings[0].message).toMatch(/VRMC_vrm, EXT_foo/);
    const positions = moved(mesh, gltf, [[0, 0.5, 0], [0, 0, -1]]);  // two shapes: the second node gets a copy of the mesh
    const out = (await readGltf(await writeGltf(gltf, positions, mesh.indices), 'vrm.glb')).gltf.json;
    expect(out.extensionsUsed).toEqual(expect.arrayContaining(['VRMC_vrm', 'EXT_foo']));
    expect(out.extensions).toEqual({ VRMC_vrm: { specVersion: '1.0', meta: { name: 'avatar' } }, EXT_foo: { a: 1 } });
    expect(out.extras).toEqual({ rootExtra: 42 });
    expect(out.cameras).toEqual([{ type: 'perspective', perspective: { yfov: 1, znear: 0.1 } }]);
    expect(out.nodes[0]).toMatchObject({ extras: { nodeExtra: true }, extensions: { EXT_foo: { n: 1 } } });
    expect(out.meshes).toHaveLength(2);
    for (const m of out.meshes) {
      expect(m.extras).toEqual({ meshExtra: 1 });
      expect(m.primitives[0]).toMatchObject({ extras: { primExtra: 'p' }, extensions: { EXT_foo: { p: 2 } } });
    }
    expect(out.materials[0].extensions).toEqual({ VRMC_materials_mtoon: { specVersion: '1.0' } });
  });

  it('names an unknown extension it cannot keep (on a texture, a sampler, an accessor) and does not declare one it lost', async () => {
    const json = boxes([{}]);
    // A 1x1 PNG, so that the texture has an image.
    const png = 'iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8DwHwAFBQIAX8jx0gAAAABJRU5ErkJggg==';
    Object.assign(json, { extensionsUsed: ['EXT_foo', 'EXT_bar'], images: [{ uri: `data:image/png;base64,${png}` }],
      samplers: [{ magFilter: 9728, extensions: { EXT_foo: { s: 1 } } }], textures: [{ source: 0, sampler: 0, extensions: { EXT_foo: { t: 1 } } }] });
    json.materials[0].pbrMetallicRoughness.baseColorTexture = { index: 0, texCoord: 0 };
    json.accessors[0].extensions = { EXT_bar: { a: 1 } };
    const { mesh, gltf } = await readGltf(encode(json), 'tex.gltf');
    expect(gltf.warnings[0].message).toMatch(/except EXT_foo on samplers\[0\], EXT_foo on textures\[0\], EXT_bar on accessors\[0\], which the writer leaves out/);
    const out = (await readGltf(await writeGltf(gltf, mesh.positions, mesh.indices), 'tex.glb')).gltf.json;
    expect(out.textures).toHaveLength(1);
    expect(out.extensionsUsed ?? []).not.toContain('EXT_bar');
    expect(out.extensionsUsed ?? []).not.toContain('EXT_foo');
  });

  it('reports every other warning of glTF-Transform\'s reader with a code of its own (they were collected and lost)', () => {
    const logged = ['Missing optional extension, "EXT_foo".', 'Some other thing the reader noticed.'];
    const warnings = readerWarnings({ extensionsUsed: ['EXT_foo'] }, 'x.gltf', logged);
    expect(warnings.map((w) => w.code)).toEqual(['gltf_extension_kept_uninterpreted', 'gltf_reader_warning']);
    expect(warnings[1].message).toBe('x.gltf: glTF reader: Some other thing the reader noticed.');
  });

  it('the CLI prints nothing under --quiet and reports the kept extensions as a warning with a code', () => {
    const dir = mkdtempSync(join(tmpdir(), 'sd-unknown-'));
    try {
      writeFileSync(join(dir, 'vrm.gltf'), JSON.stringify(withUnknown()));
      writeFileSync(join(dir, 'scene.json'), JSON.stringify({ mesh: 'vrm.gltf', handles: [{ vertices: [0, 1, 2, 3] }, { vertices: [4, 5, 6, 7], translate: [0, 0, 0.2] }] }));
      const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
      const r = spawnSync(process.execPath, [cli, 'deform', join(dir, 'scene.json'), '--out', join(dir, 'out.glb'), '--report', join(dir, 'r.json'), '--quiet'],
        { encoding: 'utf8', timeout: 60000 });
      expect(r.stderr).toBe('');
      expect(r.stdout).toBe('');
      expect(r.status).toBe(0);
      const report = JSON.parse(readFileSync(join(dir, 'r.json'), 'utf8'));
      expect(report.warnings.map((w) => w.code)).toContain('gltf_extension_kept_uninterpreted');
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }
  });
});

describe('TANGENT turns with the recomputed NORMAL', () => {
  // The box's area-weighted corner normals (what the writer computes, so that a rigid turn turns them exactly).
  const boxNormals = () => {
    const sums = new Float64Array(24);
    for (let t = 0; t < FACES.length; t += 3) {
      const [a, b, c] = [0, 1, 2].map((k) => [0, 1, 2].map((i) => BOX[3 * FACES[t + k] + i]));
      const u = [0, 1, 2].map((i) => b[i] - a[i]), w = [0, 1, 2].map((i) => c[i] - a[i]);
      const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
      for (let k = 0; k < 3; ++k) for (let i = 0; i < 3; ++i) sums[3 * FACES[t + k] + i] += n[i];
    }
    return Array.from({ length: 8 }, (_, v) => { const n = sums.subarray(3 * v, 3 * v + 3); return Array.from(n, (x) => x / Math.hypot(...n)); });
  };
  // The box with those normals and a tangent perpendicular to each, w = -1.
  const withTangents = () => {
    const json = boxes([{}]);
    const normals = new Float32Array(24), tangents = new Float32Array(32), corner = boxNormals();
    for (let v = 0; v < 8; ++v) {
      const n = corner[v];
      const t = [n[1], -n[0], 0].map((c) => c / Math.hypot(n[0], n[1]));
      normals.set(n, 3 * v);
      tangents.set([...t, -1], 4 * v);
    }
    const old = Buffer.from(json.buffers[0].uri.split(',')[1], 'base64');
    const bin = Buffer.concat([old, Buffer.from(normals.buffer), Buffer.from(tangents.buffer)]);
    json.buffers[0] = { byteLength: bin.length, uri: `data:application/octet-stream;base64,${bin.toString('base64')}` };
    json.bufferViews.push({ buffer: 0, byteOffset: old.length, byteLength: 96 }, { buffer: 0, byteOffset: old.length + 96, byteLength: 128 });
    json.accessors.push({ bufferView: 3, componentType: 5126, count: 8, type: 'VEC3' }, { bufferView: 4, componentType: 5126, count: 8, type: 'VEC4' });
    Object.assign(json.meshes[0].primitives[0].attributes, { NORMAL: 3, TANGENT: 4 });
    return json;
  };
  // The tangents written for the box moved by `move(positions)` (its rest positions, 3 per vertex, changed in
  // place), each checked perpendicular to its new normal, of unit length and with its w kept; 4 numbers per vertex.
  const writtenTangents = async (move) => {
    const { mesh, gltf } = await readGltf(encode(withTangents()), 'tangents.gltf');
    const positions = Float64Array.from(mesh.positions);
    move(positions);
    const primitive = (await new WebIO().readBinary(await writeGltf(gltf, positions, mesh.indices))).getRoot().listMeshes()[0].listPrimitives()[0];
    const n = primitive.getAttribute('NORMAL').getArray(), t = primitive.getAttribute('TANGENT').getArray();
    for (let v = 0; v < 8; ++v) {
      const [nx, ny, nz] = n.subarray(3 * v, 3 * v + 3), [tx, ty, tz, w] = t.subarray(4 * v, 4 * v + 4);
      expect(Math.abs(nx * tx + ny * ty + nz * tz)).toBeLessThan(1e-5);
      expect(Math.hypot(tx, ty, tz)).toBeCloseTo(1, 5);
      expect(w).toBe(-1);
    }
    return t;
  };

  it('a box turned by 90 degrees about z: each tangent perpendicular to its new normal, turned with it, its w kept', async () => {
    const t = await writtenTangents((p) => {
      for (let v = 0; v < 8; ++v) [p[3 * v], p[3 * v + 1]] = [-p[3 * v + 1], p[3 * v]];
    });
    // Each old tangent (n_y, -n_x, 0) normalised, turned by 90 degrees about z: (n_x, n_y, 0) normalised.
    boxNormals().forEach((m, v) => {
      const length = Math.hypot(m[0], m[1]);
      expect(t[4 * v]).toBeCloseTo(m[0] / length, 4);
      expect(t[4 * v + 1]).toBeCloseTo(m[1] / length, 4);
      expect(t[4 * v + 2]).toBeCloseTo(0, 4);
    });
  });

  it('a box stretched 3 times along x: each tangent follows the material (it turns towards x), perpendicular to its normal', async () => {
    // A tangent is a direction along the surface, carried by the deformation gradient F, not by F^-T as a normal is:
    // the old tangents are horizontal ((m_y, -m_x, 0), m the old corner normal), F stretches their x part about 3
    // times against their y part, so each turns towards x.
    const t = await writtenTangents((p) => {
      for (let v = 0; v < 8; ++v) p[3 * v] *= 3;
    });
    boxNormals().forEach((m, v) => {
      // The old tangent's x over y part is |m_y / m_x|; the written one's 2.4-2.9 times that (1.5 if the tangents
      // were only made perpendicular to the new normals).
      expect(Math.abs(t[4 * v] / t[4 * v + 1]) / Math.abs(m[1] / m[0])).toBeGreaterThan(2);
    });
  });
});
