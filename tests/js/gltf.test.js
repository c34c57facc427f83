// glTF models as three.js users make them (three's GLTFExporter in Node): read in the file's own vertex
// numbering with node transforms applied, deformed like the welded mesh, written back with their own layout
// and materials; and every kind of broken file refused by name, quickly.
import { beforeAll, describe, expect, it } from 'vitest';
import { CapsuleGeometry, Mesh, Scene } from 'three';
import {
  Deformer, InputError, checkMesh, loadSolver, readGltf, readMesh, readModel, writeModel,
} from 'subspace-deform';
import {
  exportGlb, exportGltfJson, exportObj, meshOf, nodeScene, nonIndexed, seamSphere, segmentedBox, welded, withHoles,
  worldPositions,
} from './support/three_models.js';

let solver;
beforeAll(async () => {
  solver = await loadSolver();
});

function maxDifference(a, b) {
  let d = 0;
  for (let i = 0; i < a.length; ++i) d = Math.max(d, Math.abs(a[i] - b[i]));
  return d;
}

function diagonal(positions) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; ++i) {
    lo[i % 3] = Math.min(lo[i % 3], positions[i]);
    hi[i % 3] = Math.max(hi[i % 3], positions[i]);
  }
  return Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

// The file vertices within `test` of their position: one handle group per region.
function where(positions, test) {
  const out = [];
  for (let i = 0; i < positions.length / 3; ++i) if (test(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2])) out.push(i);
  return out;
}

// Handles at both ends of a shape along y, the top end moved: groups and targets (3 per vertex).
function stretch(positions, move) {
  const ys = where(positions, () => true).map((i) => positions[3 * i + 1]);
  const lo = Math.min(...ys), hi = Math.max(...ys), span = hi - lo;
  const bottom = where(positions, (x, y) => y < lo + 0.15 * span), top = where(positions, (x, y) => y > hi - 0.15 * span);
  const targets = new Float64Array(3 * (bottom.length + top.length));
  [...bottom, ...top].forEach((v, r) => {
    for (let a = 0; a < 3; ++a) targets[3 * r + a] = positions[3 * v + a] + (r >= bottom.length ? move[a] : 0);
  });
  return { groups: [bottom, top], targets };
}

// A box cage around the capsules and spheres below (y from -1 to 1, radius 0.4).
function boxCage() {
  const positions = new Float64Array([-0.8, -1.3, -0.8, 0.8, -1.3, -0.8, 0.8, 1.3, -0.8, -0.8, 1.3, -0.8,
    -0.8, -1.3, 0.8, 0.8, -1.3, 0.8, 0.8, 1.3, 0.8, -0.8, 1.3, 0.8]);
  const indices = new Uint32Array([0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6,
    3, 0, 4, 3, 4, 7]);
  return { positions, indices };
}

function solveFull(mesh, move) {
  return solveWith(mesh, move, 'full');
}

// Handles at both ends, the top moved by `move`, solved in the full space or in the box cage's subspace.
function solveWith(mesh, move, method) {
  const d = Deformer.create(solver, mesh, method === 'full' ? null : boxCage());
  d.setOptions({ method, maxIterations: 100 });
  const { groups, targets } = stretch(mesh.positions, move);
  d.setHandles(groups);
  d.setTargets(targets);
  const result = d.solve();
  return { d, result };
}

describe('reading glTF', () => {
  it('reads three\'s GLTFExporter output in the file\'s vertex order, node transforms applied', async () => {
    const { scene, meshes } = nodeScene();
    const { mesh, gltf } = await readGltf(await exportGlb(scene), 'scene.glb');
    const expected = new Float64Array([...worldPositions(meshes[0]), ...worldPositions(meshes[1])]);
    expect(mesh.positions.length).toBe(expected.length);
    expect(maxDifference(mesh.positions, expected)).toBeLessThan(1e-6);  // float32 in the file
    expect(gltf.instances.map((i) => [i.start, i.count])).toEqual([[0, meshes[0].geometry.attributes.position.count],
      [meshes[0].geometry.attributes.position.count, meshes[1].geometry.attributes.position.count]]);
    // The mirrored sphere's triangles are flipped so that the welded model is outward: positive volumes.
    const report = checkMesh(solver, mesh);
    expect(report.ok, report.text).toBe(true);
    expect(report.summary.components).toBe(2);
    const volume = 8 * 1.5 ** 3 * (1 / 8) + (4 / 3) * Math.PI * (0.4 * 1.5) ** 3;  // box 1^3 and sphere r 0.4, scaled 1.5
    expect(report.summary.volume).toBeGreaterThan(0.95 * volume);
    expect(report.summary.volume).toBeLessThan(volume);
  });

  it('reads .gltf JSON with an embedded buffer, and non-indexed geometry, the same as .glb', async () => {
    const sphere = meshOf(seamSphere());
    const fromGlb = (await readModel(solver, await exportGlb(sphere), 'a.glb')).mesh;
    const fromJson = (await readModel(solver, await exportGltfJson(sphere), 'a.gltf')).mesh;
    expect(fromJson.positions).toEqual(fromGlb.positions);
    expect(fromJson.indices).toEqual(fromGlb.indices);
    const flat = (await readModel(solver, await exportGlb(meshOf(nonIndexed(seamSphere()))), 'flat.glb')).mesh;
    expect(flat.positions.length / 3).toBe(flat.indices.length);  // one vertex per corner
    const report = checkMesh(solver, flat);
    expect(report.ok).toBe(true);
    expect(report.summary.layout.solverVertices).toBe(16 * 11 + 2);  // the sphere's own points
  });

  // What Blender's "glTF Separate" and glTF-Transform's writeJSON give: the JSON, its .bin and its images as
  // files of their own, handed over by name (the CLI reads them from beside the file, the app from the drop).
  it('reads a .gltf whose buffer and texture are separate files, given by name, and writes them into the .glb', async () => {
    const { Document, WebIO } = await import('@gltf-transform/core');
    const geometry = seamSphere();
    const document = new Document();
    const buffer = document.createBuffer().setURI('sphere.bin');
    const accessor = (type, array) => document.createAccessor().setType(type).setArray(array).setBuffer(buffer);
    const png = Uint8Array.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 1, 2, 3]);  // the bytes travel as they are
    const texture = document.createTexture('skin').setMimeType('image/png').setImage(png).setURI('skin.png');
    const primitive = document.createPrimitive()
      .setAttribute('POSITION', accessor('VEC3', geometry.getAttribute('position').array))
      .setAttribute('TEXCOORD_0', accessor('VEC2', geometry.getAttribute('uv').array))
      .setIndices(accessor('SCALAR', Uint32Array.from(geometry.getIndex().array)))
      .setMaterial(document.createMaterial('skin').setBaseColorTexture(texture));
    document.createScene().addChild(document.createNode().setMesh(document.createMesh().addPrimitive(primitive)));
    const { json, resources } = await new WebIO().writeJSON(document);
    expect(Object.keys(resources).sort()).toEqual(['skin.png', 'sphere.bin']);
    const bytes = new TextEncoder().encode(JSON.stringify(json));
    const model = await readModel(solver, bytes, 'sphere.gltf', { resources });
    expect(model.mesh.positions.length / 3).toBe(geometry.getAttribute('position').count);
    expect(checkMesh(solver, model.mesh).summary.layout.solverVertices).toBe(16 * 11 + 2);
    const glb = await writeModel(solver, model, model.mesh.positions, 'sphere.glb');
    const back = await readModel(solver, glb, 'sphere.glb');
    expect(back.mesh.indices).toEqual(model.mesh.indices);
    expect(back.gltf.json.images).toHaveLength(1);
    // Without its .bin: a named error, the file it needs in the message.
    const lost = await readModel(solver, bytes, 'sphere.gltf').then(() => null, (e) => e);
    expect(lost).toBeInstanceOf(InputError);
    expect(lost.message).toMatch(/sphere\.gltf: .*"sphere\.bin", which was not given/);
  });

  it('reads normalised integer positions (KHR_mesh_quantization)', async () => {
    const { Document, WebIO } = await import('@gltf-transform/core');
    const { KHRMeshQuantization } = await import('@gltf-transform/extensions');
    const document = new Document();
    document.createExtension(KHRMeshQuantization).setRequired(true);
    const buffer = document.createBuffer();
    const corners = new Int16Array([0, 0, 0, 32767, 0, 0, 0, 32767, 0, 0, 0, 32767]);
    const position = document.createAccessor().setType('VEC3').setArray(corners).setNormalized(true).setBuffer(buffer);
    const index = document.createAccessor().setType('SCALAR').setArray(new Uint16Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3])).setBuffer(buffer);
    const primitive = document.createPrimitive().setAttribute('POSITION', position).setIndices(index);
    const node = document.createNode().setMesh(document.createMesh().addPrimitive(primitive)).setScale([2, 2, 2]);
    document.createScene().addChild(node);
    const bytes = await new WebIO().registerExtensions([KHRMeshQuantization]).writeBinary(document);
    const { mesh } = await readModel(solver, bytes, 'quantised.glb');
    expect(Array.from(mesh.positions)).toEqual([0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 0, 2]);
    expect(checkMesh(solver, mesh).summary.volume).toBeCloseTo(8 / 6, 12);
  });
});

describe('deforming and writing glTF back', () => {
  // The goal: a glTF whose sphere is split at its UV seam and poles deforms to the same shape as its welded OBJ,
  // within 1e-5 of the diagonal, and is written back with its own vertex layout.
  it('deforms a UV-seam glTF like its welded OBJ and writes it back in its own layout', async () => {
    const geometry = new CapsuleGeometry(0.4, 1.2, 6, 16);
    const glb = await exportGlb(meshOf(geometry));
    const model = await readModel(solver, glb, 'capsule.glb');
    const obj = readMesh(solver, new TextEncoder().encode(exportObj(new Mesh(welded(geometry)))), 'capsule.obj');
    expect(obj.positions.length).toBeLessThan(model.mesh.positions.length);  // the seam copies are gone
    const move = [0.3, 0.25, -0.1];
    // Each file vertex against the welded OBJ vertex at the same rest position (the seam's copies differ in the
    // last bits of their sines: the key rounds them away, as welding does).
    const key = (p, i) => Array.from(p.subarray(3 * i, 3 * i + 3), (x) => Math.round(x * 1e6) + 0).join(',');
    const byPosition = new Map();
    for (let i = 0; i < obj.positions.length / 3; ++i) byPosition.set(key(obj.positions, i), i);
    let seams;
    for (const method of ['subspace', 'full']) {
      seams?.d.dispose();
      seams = solveWith(model.mesh, move, method);
      const plain = solveWith(obj, move, method);
      const X = seams.d.positions(), Y = plain.d.positions();
      let worst = 0, moved = 0;
      for (let v = 0; v < model.mesh.positions.length / 3; ++v) {
        const w = byPosition.get(key(model.mesh.positions, v));
        for (let a = 0; a < 3; ++a) worst = Math.max(worst, Math.abs(X[3 * v + a] - Y[3 * w + a]));
        for (let a = 0; a < 3; ++a) moved = Math.max(moved, Math.abs(X[3 * v + a] - model.mesh.positions[3 * v + a]));
      }
      expect(moved).toBeGreaterThan(0.2);  // a real deformation, compared
      expect(worst / diagonal(obj.positions), method).toBeLessThan(1e-5);
      console.log(`capsule (${method}): seam glTF (${model.mesh.positions.length / 3} vertices) vs welded OBJ (${obj.positions.length / 3}), ` +
        `max difference ${(worst / diagonal(obj.positions)).toExponential(2)} of the diagonal`);
      plain.d.dispose();
    }
    const X = seams.d.positions();
    // Written back: same vertex count per primitive, the deformed positions, the UVs and material kept.
    const out = await writeModel(solver, model, X, 'capsule-deformed.glb', { solverOfFile: seams.d.layout().solverOfFile });
    const back = await readModel(solver, out, 'capsule-deformed.glb');
    expect(back.mesh.indices).toEqual(model.mesh.indices);
    expect(maxDifference(back.mesh.positions, X)).toBeLessThan(1e-6);
    const json = back.gltf.json;
    expect(json.meshes[0].primitives[0].attributes).toHaveProperty('TEXCOORD_0');
    expect(json.meshes[0].primitives[0].attributes).toHaveProperty('NORMAL');
    expect(json.materials).toHaveLength(1);
    // The written normals are unit vectors of the deformed surface, one per welded point: the copies on both
    // sides of the seam (whose rest normals agree) get the same normal, so the seam does not show.
    const normals = back.gltf.restNormals;
    const normalAt = new Map();
    let seamGap = 0;
    for (let v = 0; v < back.mesh.positions.length / 3; ++v) {
      const n = Array.from(normals.subarray(3 * v, 3 * v + 3));
      expect(Math.hypot(...n)).toBeCloseTo(1, 5);
      const point = byPosition.get(key(model.mesh.positions, v));
      if (normalAt.has(point)) seamGap = Math.max(seamGap, maxDifference(normalAt.get(point), n));
      else normalAt.set(point, n);
    }
    expect(seamGap).toBeLessThan(1e-6);
    seams.d.dispose();
  });

  it('round-trips a multi-node scene: unchanged positions come back, each instance in its own node space', async () => {
    const { scene } = nodeScene();
    const model = await readModel(solver, await exportGlb(scene), 'scene.glb');
    const out = await writeModel(solver, model, model.mesh.positions, 'same.glb');
    const back = await readModel(solver, out, 'same.glb');
    expect(maxDifference(back.mesh.positions, model.mesh.positions)).toBeLessThan(1e-6);
    // The nodes are as they were (the positions went back into each node's own space).
    expect(back.gltf.instances.map((i) => [i.node, i.mesh, i.primitive])).toEqual(model.gltf.instances.map((i) => [i.node, i.mesh, i.primitive]));
    back.gltf.instances.forEach((instance, k) => expect(maxDifference(instance.matrix, model.gltf.instances[k].matrix)).toBeLessThan(1e-6));
  });

  it('writes a plain .glb for a model read from OBJ', async () => {
    const obj = readMesh(solver, new TextEncoder().encode(exportObj(new Mesh(welded(seamSphere())))), 's.obj');
    const glb = await writeModel(solver, { mesh: obj }, obj.positions, 's.glb');
    const back = await readModel(solver, glb, 's.glb');
    expect(maxDifference(back.mesh.positions, obj.positions)).toBeLessThan(1e-6);
    await expect(writeModel(solver, { mesh: obj }, obj.positions, 's.fbx')).rejects.toThrow(/cannot write \.fbx/);
  });
});

describe('the meshes people have', () => {
  it('keeps an open glTF mesh\'s capped volume within 1e-6', async () => {
    const holed = withHoles(new CapsuleGeometry(0.4, 1.2, 6, 16), (c) => Math.abs(c[1]) < 0.25 && c[2] > 0.2);
    const { mesh } = await readModel(solver, await exportGlb(meshOf(holed)), 'open.glb');
    const report = checkMesh(solver, mesh);
    expect(report.ok, report.text).toBe(true);
    expect(report.findings.map((f) => f.code)).toEqual(expect.arrayContaining(['open', 'welded']));
    const { d, result } = solveFull(mesh, [0.3, 0.2, 0]);
    const rest = d.restPartVolumes(), now = d.partVolumes();
    expect(rest).toHaveLength(1);
    expect(Math.abs(now[0] - rest[0]) / rest[0]).toBeLessThan(1e-6);
    expect(result.iterations.at(-1).partVolumeChange).toHaveLength(1);
    d.dispose();
  });

  it('keeps each of two components\' volume within 1e-6', async () => {
    const scene = new Scene();
    const a = meshOf(seamSphere(0.5)), b = meshOf(seamSphere(0.5));
    a.position.set(0, -0.7, 0);
    b.position.set(0, 0.7, 0);
    scene.add(a, b);
    const { mesh } = await readModel(solver, await exportGlb(scene), 'two.glb');
    const { d } = solveFull(mesh, [0.2, 0.4, 0]);
    const rest = d.restPartVolumes(), now = d.partVolumes();
    expect(rest).toHaveLength(2);
    for (let k = 0; k < 2; ++k) expect(Math.abs(now[k] - rest[k]) / rest[k]).toBeLessThan(1e-6);
    d.dispose();
  });

  // The capped volume and the components' volumes in the cage subspace: with reduced integration (sampled
  // Laplacian rows, boundary rows among them) and with each of the coordinate types that bind the cage.
  it.each([
    ['mean value coordinates, reduced integration', { coordinates: 'mvc' }, { integration: 'reduced' }],
    ['positive mean value coordinates', { coordinates: 'pmvc', pmvcResolution: 8 }, {}],
    ['harmonic coordinates', { coordinates: 'harmonic', harmonicResolution: 16 }, {}],
  ])('keeps the capped volume of an open glTF and the volumes of two components within 1e-6 in the cage subspace: %s', async (_, subspace, options) => {
    const holed = withHoles(new CapsuleGeometry(0.4, 1.2, 6, 16), (c) => Math.abs(c[1]) < 0.25 && c[2] > 0.2);
    const scene = new Scene();
    const a = meshOf(seamSphere(0.3)), b = meshOf(seamSphere(0.3));
    a.position.set(0, -0.6, 0);
    b.position.set(0, 0.6, 0);
    scene.add(a, b);
    for (const [name, object, parts] of [['open.glb', meshOf(holed), 1], ['two.glb', scene, 2]]) {
      const { mesh } = await readModel(solver, await exportGlb(object), name);
      const d = Deformer.create(solver, mesh, boxCage(), subspace);
      d.setOptions({ method: 'subspace', maxIterations: 100, ...options });
      const { groups, targets } = stretch(mesh.positions, [0.15, 0.15, 0]);
      d.setHandles(groups);
      d.setTargets(targets);
      const result = d.solve();
      const rest = d.restPartVolumes(), now = d.partVolumes();
      expect(rest).toHaveLength(parts);
      for (let k = 0; k < parts; ++k) expect(Math.abs(now[k] - rest[k]) / rest[k], `${name}, part ${k}: ${result.stopReason}`).toBeLessThan(1e-6);
      if (options.integration === 'reduced') expect(result.iterations[0].samples).toBeGreaterThan(0);
      const top = groups[1][0];
      expect(Math.abs(d.positions()[3 * top] - mesh.positions[3 * top])).toBeGreaterThan(0.05);  // it moved
      d.dispose();
    }
  });

  // What OBJExporter writes for three's BoxGeometry: every face with its own vertices (24 + seams), which
  // read as 6 open components before welding; now one closed box, said to be welded, that deforms.
  it('loads an OBJExporter box (faces with their own vertices) as one closed mesh, with a note on the welding', () => {
    const text = exportObj(meshOf(segmentedBox()));
    const mesh = readMesh(solver, new TextEncoder().encode(text), 'box.obj');
    expect(mesh.positions.length / 3).toBe(6 * 9);  // 3 x 3 vertices per face
    const report = checkMesh(solver, mesh);
    expect(report.ok, report.text).toBe(true);
    expect(report.findings.filter((f) => f.severity === 'error')).toEqual([]);
    expect(report.findings.map((f) => f.code)).toContain('welded');
    expect(report.findings.map((f) => f.code)).not.toContain('open');
    expect(report.summary.layout).toMatchObject({ fileVertices: 54, solverVertices: 26, welded: 28 });
    expect(report.summary.components).toBe(1);
    expect(report.summary.volume).toBeCloseTo(1, 12);
    const { d, result } = solveFull(mesh, [0.2, 0.3, 0]);
    expect(result.converged).toBe(true);
    expect(Math.abs(d.partVolumes()[0] - 1)).toBeLessThan(1e-6);
    // The copies of one corner stay together (they are one solver vertex).
    const X = d.positions(), solverOfFile = d.layout().solverOfFile;
    const at = new Map();
    for (let v = 0; v < 54; ++v) {
      const p = Array.from(X.subarray(3 * v, 3 * v + 3));
      if (at.has(solverOfFile[v])) expect(maxDifference(at.get(solverOfFile[v]), p)).toBe(0);
      else at.set(solverOfFile[v], p);
    }
    d.dispose();
  });

  it('loads a sphere with holes (open, 2 holes) with a note, not an error', () => {
    const holed = withHoles(seamSphere(), (c) => Math.abs(c[1]) < 0.2 && Math.abs(c[2]) > 0.7);
    const mesh = readMesh(solver, new TextEncoder().encode(exportObj(meshOf(holed))), 'holes.obj');
    const report = checkMesh(solver, mesh);
    expect(report.ok, report.text).toBe(true);
    const open = report.findings.find((f) => f.code === 'open');
    expect(open.severity).toBe('note');
    expect(open.message).toMatch(/around 2 holes/);
    expect(report.summary.holes).toBe(2);
  });

  // Two tetrahedra touching at one corner (a non-manifold vertex): split into one vertex per solid, each keeps
  // its own volume; a fin (three faces on one edge) cannot be split: an error naming the edge in file numbers.
  it('splits a vertex two solids share, and names an edge no pairing can split', () => {
    const tetra = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1];
    const positions = new Float64Array([...tetra, ...tetra.slice(3).map((x) => -x)]);  // the second mirrored through 0
    const indices = new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 4, 5, 0, 6, 4, 0, 5, 6, 4, 6, 5]);
    const report = checkMesh(solver, { positions, indices });
    expect(report.ok, report.text).toBe(true);
    expect(report.findings.map((f) => f.code)).toEqual(expect.arrayContaining(['split_vertices', 'components']));
    expect(report.summary.layout.splitVertices).toBe(1);
    const d = Deformer.create(solver, { positions, indices }, null);
    d.setOptions({ method: 'full', maxIterations: 100 });
    d.setHandles([[1, 2, 3], [4, 5, 6]]);
    d.setTargets(Float64Array.from([...tetra.slice(3), ...tetra.slice(3).map((x, i) => -x + (i % 3 === 0 ? 0.3 : 0))]));
    d.solve();
    const rest = d.restPartVolumes(), now = d.partVolumes();
    expect(rest).toHaveLength(2);
    for (let k = 0; k < 2; ++k) expect(Math.abs(now[k] - rest[k]) / rest[k]).toBeLessThan(1e-6);
    d.dispose();
    const fin = checkMesh(solver, { positions: new Float64Array([...tetra, 1, 1, 1]), indices: new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 1, 2, 4]) });
    expect(fin.ok).toBe(false);
    const edge = fin.findings.find((f) => f.code === 'non_manifold_edge');
    expect(edge.message).toMatch(/first: 1-2/);
    expect(() => Deformer.create(solver, { positions: new Float64Array([...tetra, 1, 1, 1]), indices: new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 1, 2, 4]) }, null))
      .toThrow(/non-manifold edge .*first: 1-2/);
  });

  it('carries a vertex no face uses along, and refuses it as a handle by name', () => {
    const positions = new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.2, 0.2, 0.2]);
    const indices = new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]);
    expect(checkMesh(solver, { positions, indices }).ok).toBe(true);
    for (const method of ['full', 'arap']) {
      const d = Deformer.create(solver, { positions, indices }, null);
      d.setOptions({ method });
      d.setHandles([[0, 1, 2, 3]]);
      d.setTargets(Float64Array.from(positions.subarray(0, 12), (x, i) => x + (i % 3 === 0 ? 0.5 : 0)));
      d.solve();
      expect(d.positions()[12]).toBeCloseTo(0.7, 6);
      expect(() => d.setHandles([[4]])).toThrow(/vertex 4, which no triangle uses/);
      d.dispose();
    }
  });
});

describe('broken glTF is refused by name, quickly', () => {
  // Minimal documents around one triangle whose buffer is given as a data: URI.
  const triangle = () => ({
    asset: { version: '2.0' },
    buffers: [{ byteLength: 36, uri: `data:application/octet-stream;base64,${Buffer.from(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]).buffer).toString('base64')}` }],
    bufferViews: [{ buffer: 0, byteLength: 36 }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3' }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
    nodes: [{ mesh: 0 }],
    scenes: [{ nodes: [0] }],
  });
  const encode = (json) => new TextEncoder().encode(JSON.stringify(json));

  it('reads the well-formed one', async () => {
    const { mesh } = await readModel(solver, encode(triangle()), 't.gltf');
    expect(mesh.indices).toEqual(new Uint32Array([0, 1, 2]));
  });

  it.each([
    ['malformed JSON', () => new TextEncoder().encode('{"asset": '), /not valid glTF JSON/, 'parse_error'],
    ['glTF 1.0', () => encode({ ...triangle(), asset: { version: '1.0' } }), /only 2\.x/, 'parse_error'],
    ['a truncated .glb', () => new Uint8Array([0x67, 0x6c, 0x54, 0x46, 2, 0, 0, 0, 200, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]), /truncated/, 'parse_error'],
    ['a missing buffer file', () => encode({ ...triangle(), buffers: [{ byteLength: 36, uri: 'triangle.bin' }] }), /"triangle\.bin", which was not given/, 'unreadable_file'],
    ['Draco compression', () => encode({ ...triangle(), extensionsUsed: ['KHR_draco_mesh_compression'], extensionsRequired: ['KHR_draco_mesh_compression'] }), /compressed \(KHR_draco_mesh_compression\)/, 'parse_error'],
    ['meshopt compression', () => encode({ ...triangle(), extensionsRequired: ['EXT_meshopt_compression'] }), /compressed \(EXT_meshopt_compression\)/, 'parse_error'],
    ['a huge accessor count', () => { const j = triangle(); j.accessors[0].count = 2 ** 30; return encode(j); }, /accessor 0 has count 1073741824/, 'parse_error'],
    ['an accessor past its view', () => { const j = triangle(); j.accessors[0].count = 4; return encode(j); }, /does not fit in buffer view 0/, 'parse_error'],
    ['a view past its buffer', () => { const j = triangle(); j.bufferViews[0].byteLength = 360; return encode(j); }, /lies outside buffer 0/, 'parse_error'],
    ['a buffer shorter than declared', () => { const j = triangle(); j.buffers[0].byteLength = 3600; return encode(j); }, /truncated/, 'parse_error'],
    ['a node that is its own ancestor', () => ({ ...triangle(), nodes: [{ mesh: 0, children: [1] }, { children: [0] }] }), /its own ancestor/, 'parse_error'],
    ['an index past the vertices', () => { const j = triangle(); j.buffers.push({ byteLength: 6, uri: `data:application/octet-stream;base64,${Buffer.from(new Uint16Array([0, 1, 7]).buffer).toString('base64')}` }); j.bufferViews.push({ buffer: 1, byteLength: 6 }); j.accessors.push({ bufferView: 1, componentType: 5123, count: 3, type: 'SCALAR' }); j.meshes[0].primitives[0].indices = 1; return encode(j); }, /uses vertex 7 of its 3/, 'parse_error'],
    ['points only', () => { const j = triangle(); j.meshes[0].primitives[0].mode = 0; return encode(j); }, /no triangle mesh/, 'parse_error'],
    // Read as a rotation with a skewing scale, and with the translation ignored: glTF forbids both.
    ['a rotation that is no unit quaternion', () => { const j = triangle(); j.nodes[0].rotation = [0, 0, 2, 0]; return encode(j); }, /node 0 has a rotation \[0, 0, 2, 0\] of length 2\.00: glTF rotations are unit quaternions/, 'parse_error'],
    ['a matrix with a translation', () => { const j = triangle(); j.nodes[0].matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]; j.nodes[0].translation = [1, 0, 0]; return encode(j); }, /node 0 has both a matrix and translation/, 'parse_error'],
  ])('%s', async (_, make, pattern, code) => {
    const made = make();
    const bytes = made instanceof Uint8Array ? made : encode(made);
    const error = await readModel(solver, bytes, 'bad.gltf').then(() => null, (e) => e);
    expect(error).toBeInstanceOf(InputError);
    expect(error.code).toBe(code);
    expect(error.message).toMatch(/^bad\.gltf: /);
    expect(error.message).toMatch(pattern);
  });
  // These said "not valid glTF JSON (Unexpected token 'g', "glTF...")" and quoted a binary file's bytes.
  const junk = Uint8Array.from({ length: 64 }, (_, i) => 0x80 + ((i * 37) % 128));
  it.each([
    ['an empty .glb', 'e.glb', new Uint8Array(0), /^e\.glb: the file is empty$/],
    ['a .glb cut inside its header', 'h.glb', new Uint8Array([0x67, 0x6c, 0x54, 0x46, 2, 0, 0, 0, 16, 9]), /^h\.glb: truncated: a \.glb needs at least 20 bytes.* has 10$/],
    ['a .glb that is no glTF', 'junk.glb', junk, /^junk\.glb: not a binary glTF: a \.glb starts with the bytes "glTF", and this file does not$/],
    ['a binary file named .gltf', 'junk.gltf', junk, /^junk\.gltf: not valid glTF JSON: not UTF-8 text \(a binary file\?\)$/],
    ['an empty .gltf', 'e.gltf', new Uint8Array(0), /^e\.gltf: the file is empty$/],
  ])('%s is called what it is, quoting no bytes', async (_, name, bytes, pattern) => {
    const error = await readModel(solver, bytes, name).then(() => null, (e) => e);
    expect(error).toBeInstanceOf(InputError);
    expect(error.code).toBe('parse_error');
    expect(error.message).toMatch(pattern);
  });

  it('still reads a .glb that holds JSON text', async () => {
    const { mesh } = await readModel(solver, new TextEncoder().encode(`\ufeff \n${JSON.stringify(triangle())}`), 'json.glb');
    expect(mesh.indices).toEqual(new Uint32Array([0, 1, 2]));
  });
});
