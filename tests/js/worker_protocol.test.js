// The solver worker's protocol (web/lib/worker/protocol.js), with the worker running in a Node thread:
// replies carry the typed results, failures arrive as error data ({ code, message, findings }) that
// errorFromData turns back into the classes the worker threw, and the dead requests are gone.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { REQUEST_TYPES } from '../../web/lib/worker/protocol.js';
import { CapsuleGeometry } from 'three';
import {
  CancelledError, InputError, MeshError, errorFromData, loadSolver, makeExample, readModel, writeObj,
} from 'subspace-deform';
import { exportGlb, meshOf } from './support/three_models.js';
import { startWorkerThread } from './support/worker_thread.js';

let worker, request, progress, pending;
let bar;

let solver;
beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
  bar.obj = new TextEncoder().encode(writeObj(solver, bar.mesh));
  ({ worker, request, progress, pending } = await startWorkerThread());
});

afterAll(() => worker?.terminate());

describe('the worker protocol', () => {
  it('answers loadExample with a Model and reports progress while binding', async () => {
    const reply = await request('loadExample', { name: 'bar' });
    expect(reply.ok).toBe(true);
    expect(Object.keys(reply.result).sort()).toEqual(['basis', 'basisSize', 'bindMs', 'cage', 'cageQuality', 'canGenerateCage',
      'coordinates', 'defaultHandles', 'defaultView', 'description', 'exampleNames', 'float32', 'generatedCage', 'gltf', 'layout',
      'mesh', 'modesAsked', 'name', 'notes', 'restVolume', 'solver', 'vertexCount', 'volumePartCount']);
    // A clean closed mesh: its layout is the file's, nothing to note, one global volume.
    expect(reply.result.notes).toEqual([]);
    expect(reply.result.layout).toMatchObject({ welded: 0, unreferenced: 0, solverVertices: bar.mesh.positions.length / 3 });
    expect(reply.result.volumePartCount).toBe(1);
    expect(reply.result.float32).toBe(false); // 5k x 28 in double is 1.1 MB: double precision costs nothing
    // The bar's procedural cage controls its capsule well: the page shows no warning.
    expect(reply.result.cageQuality).toMatchObject({ cageVertices: 28, weakVertices: 0, poor: false, warnings: [] });
    expect(reply.result.vertexCount).toBe(bar.mesh.positions.length / 3);
    // A Node thread is no cross-origin isolated page: the single-threaded build, saying why.
    expect(reply.result.solver).toMatchObject({ build: 'single', threads: 1 });
    expect(reply.result.solver.buildNote).toMatch(/not cross-origin isolated/);
    expect(reply.result.mesh.positions).toBeInstanceOf(Float64Array);
    expect(progress.some((p) => p.phase === 'computing mean value coordinates')).toBe(true);
    expect(reply.result.coordinates).toMatchObject({ coordinates: 'mvc' });
  });

  it('loadExample with generateCage binds the example in a generated cage, and a cage that cannot be made is refused', async () => {
    const reply = await request('loadExample', { name: 'bar', generateCage: { vertices: 12 } });
    expect(reply.ok).toBe(true);
    expect(reply.result.description).toMatch(/^bar in a generated \d+-vertex cage$/);
    const k = reply.result.cage.positions.length / 3;
    expect(k).toBeGreaterThanOrEqual(12);
    expect(k).toBeLessThanOrEqual(15); // K, or at most 20% more (docs/cage.md)
    expect(reply.result.generatedCage).toBeTruthy();
    // The failure comes before the binding: the worker's session is the one bound before (the app keeps its model).
    const failed = await request('loadExample', { name: 'bar', generateCage: { vertices: 4 } });
    expect(failed.ok).toBe(false);
    expect(failed.error.code).toBe('cage_failed');
    expect((await request('loadExample', { name: 'bar', generateCage: { vertices: 1e9 } })).error.message)
      .toMatch(/loadExample\.generateCage\.vertices must be an integer from 4 to 20000/);
    expect((await request('loadExample', { name: 'bar' })).ok).toBe(true); // the bar in its own cage for the tests below
  });

  it('answers step with a Frame whose result carries the stop code', async () => {
    await request('setHandles', { groups: [[0, 1, 2]] });
    const frame = (await request('step', { iterations: 3 })).result;
    expect(frame.result).toMatchObject({ stop: 'step_tolerance', converged: true });
    expect(frame.render.normals).toBeInstanceOf(Float32Array);
    expect((await request('reset')).result.result).toMatchObject({ stop: 'no_iterations', iterations: [] });
  });

  it('deforms a lone mesh with the spectral basis and keeps the volume per part', async () => {
    const lone = await request('loadFiles', { files: [{ name: 'bar.obj', bytes: bar.obj }], subspace: { basis: 'spectral', modes: 16 } });
    expect(lone.ok).toBe(true);
    expect(lone.result).toMatchObject({ basis: 'spectral', basisSize: 20, cageQuality: null }); // no cage to judge
    expect(lone.result.cage.positions).toHaveLength(0);
    expect(progress.some((p) => p.phase === 'computing the spectral basis')).toBe(true);
    const parts = await request('setVolumeParts', { parts: { auto: 3 } });
    expect(parts.result.parts).toHaveLength(bar.mesh.indices.length / 3);
    expect(parts.result.restPartVolumes).toHaveLength(3);
    const left = [], right = [];
    for (let i = 0; i < bar.mesh.positions.length / 3; ++i) {
      if (bar.mesh.positions[3 * i] < -2.2) left.push(i);
      if (bar.mesh.positions[3 * i] > 2.2) right.push(i);
    }
    await request('setHandles', { groups: [left, right] });
    const targets = new Float64Array(3 * (left.length + right.length));
    [...left, ...right].forEach((v, k) => {
      for (let a = 0; a < 3; ++a) targets[3 * k + a] = bar.mesh.positions[3 * v + a] + (k >= left.length && a === 1 ? -0.8 : 0);
    });
    await request('setTargets', { targets });
    const frame = (await request('step', { iterations: 30 })).result;
    for (const change of frame.result.iterations.at(-1).partVolumeChange) expect(Math.abs(change)).toBeLessThanOrEqual(1e-8);
    expect((await request('setVolumeParts', { parts: null })).result.parts).toHaveLength(0);
    const bad = await request('setVolumeParts', { parts: { auto: 0 } });
    expect(errorFromData(bad.error)).toBeInstanceOf(InputError);
    // Handle lines travel with the targets (the app's drags in the screen plane); a bad one is named.
    expect((await request('setTargets', { targets, lines: [null, { along: [0, 0, -1] }] })).ok).toBe(true);
    const held = (await request('step', { iterations: 30 })).result;
    expect(Math.abs(held.result.iterations.at(-1).volumeRelError)).toBeLessThanOrEqual(1e-8);
    const badLine = await request('setTargets', { targets, lines: [null, { along: [0, 0, 0] }] });
    expect(errorFromData(badLine.error).message).toMatch(/lines\[1\]\.along must not be zero/);
  });

  it('binds the cage coordinates asked for and hands a column of W to the page for the influence view', async () => {
    const reply = await request('loadExample', { name: 'c-bar', subspace: { basis: 'cage', coordinates: 'harmonic', harmonicResolution: 16 } });
    expect(reply.ok).toBe(true);
    expect(reply.result.coordinates).toMatchObject({ coordinates: 'harmonic', resolution: 16 });
    expect(progress.some((p) => p.phase === 'computing harmonic coordinates')).toBe(true);
    const column = (await request('basisColumn', { column: 3 })).result;
    expect(column.values).toBeInstanceOf(Float32Array);
    expect(column.values).toHaveLength(reply.result.vertexCount);
    expect(column.min).toBeGreaterThanOrEqual(-1e-7);
    expect(column.max).toBeGreaterThan(0.05);
    expect(column.max).toBeLessThanOrEqual(1);
    const mvc = await request('loadExample', { name: 'c-bar' });
    expect(mvc.result.coordinates.minWeight).toBeLessThan(0);
    const bad = await request('basisColumn', { column: 52 });
    expect(bad.error).toMatchObject({ code: 'invalid_argument' });
    const pmvc = await request('loadExample', { name: 'c-bar', subspace: { basis: 'cage', coordinates: 'pmvc', harmonicResolution: 16 } });
    expect(pmvc.error.message).toMatch(/harmonicResolution is for coordinates 'harmonic'/);
  });

  it('sends failures as error data that come back as the classes the worker threw', async () => {
    // generateCage: null is absent (the app sends it so), not a field of the wrong type.
    const lone = await request('loadFiles', { files: [{ name: 'bar.obj', bytes: bar.obj }], generateCage: null });
    expect(lone.ok).toBe(false);
    expect(lone.error).toMatchObject({ code: 'no_cage' });
    expect(errorFromData(lone.error)).toBeInstanceOf(InputError);
    // A tetrahedron with a fin on one edge: a non-manifold edge no pairing splits (an open mesh would be fine).
    const fin = new TextEncoder().encode('v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 2 3 5\n');
    const broken = await request('loadFiles', { files: [{ name: 'fin.obj', bytes: fin }] });
    const error = errorFromData(broken.error);
    expect(error).toBeInstanceOf(MeshError);
    expect(error.code).toBe('invalid_mesh');
    expect(error.findings.map((f) => f.code)).toContain('non_manifold_edge');
    const shifted = bar.cage.positions.map((x, i) => (i % 3 === 0 ? x + 1 : x));
    const outside = await request('loadMeshes', { name: 'bar', mesh: bar.mesh, cage: { positions: shifted, indices: bar.cage.indices } });
    expect(outside.error.code).toBe('mesh_outside_cage');
    expect(outside.error.message).toMatch(/^bar \/ cage cannot be used:\n/);
    const badOption = await request('setOptions', { options: { maxIterations: 2 ** 31 } });
    expect(badOption.error).toEqual({ code: 'invalid_argument',
      message: 'setOptions: maxIterations must be an integer from 1 to 2147483647 (got 2147483648)' });
    expect(errorFromData({ code: 'cancelled', message: 'cancelled' })).toBeInstanceOf(CancelledError);
  });

  it('answers init and setThreads with the build and the thread count in effect', async () => {
    expect((await request('init', { threads: 4 })).result).toMatchObject({ build: 'single', threads: 1 });
    expect((await request('setThreads', { threads: 3 })).result).toMatchObject({ build: 'single', threads: 1 });
    const bad = await request('setThreads', { threads: -1 });
    expect(bad.error.code).toBe('invalid_argument');
    expect(bad.error.message).toBe('setThreads.threads must be an integer from 0 to 1024 (got -1)');
  });

  it('has no hello or solve request any more', async () => {
    for (const type of ['hello', 'solve']) {
      const reply = await request(type);
      expect(reply.error.code).toBe('invalid_argument');
      expect(reply.error.message).toMatch(new RegExp(`^unknown request "${type}" \\(known: init, setThreads, loadExample`));
    }
  });

  it('describes every request the worker handles, and no other', () => {
    // The worker admits only what protocol.js describes: a handler without an entry there could never run.
    const source = readFileSync(new URL('../../web/lib/worker/solver_worker.js', import.meta.url), 'utf8');
    const body = source.slice(source.indexOf('const handlers = {'), source.indexOf('\n};', source.indexOf('const handlers = {')));
    const handled = [...body.matchAll(/^ {2}async (\w+)\(/gm)].map((m) => m[1]);
    expect(handled.sort()).toEqual([...REQUEST_TYPES].sort());
  });

  // Every request is checked against protocol.js before the worker acts: a malformed one gets an InputError
  // naming the field, never 'internal' and never an answer 'ok' it did not earn.
  it('refuses the names of Object\'s properties as request types', async () => {
    for (const type of ['constructor', 'toString', '__proto__', 'hasOwnProperty']) {
      const reply = await request(type);
      expect(reply.ok, type).toBe(false);
      expect(reply.error.code).toBe('invalid_argument');
    }
  });

  it('refuses malformed payloads by name: an empty file list, wrong types, unknown or missing fields', async () => {
    const cases = [
      ['loadFiles', { files: [] }, /^loadFiles\.files must be one mesh file, or a mesh and its cage \(got 0\)/],
      ['loadFiles', { files: [{ name: 'a.obj', bytes: 'v 0 0 0' }] }, /loadFiles\.files\[0\]\.bytes must be a Uint8Array/],
      ['loadMeshes', { name: 'x', mesh: { positions: [0, 0, 0], indices: new Uint32Array(0) } }, /loadMeshes\.mesh\.positions must be a Float64Array/],
      ['loadExample', { name: 'bar', subspace: { basis: 'spectral' } }, /loadExample\.subspace\.modes must be an integer/],
      ['loadExample', { nme: 'bar' }, /^loadExample: unknown field "nme"/],
      ['step', {}, /^step: "iterations" is missing/],
      ['step', { iterations: 2 ** 31 }, /step\.iterations must be an integer from 0 to 2147483647/],
      ['setTargets', { targets: [1, 2, 3] }, /setTargets\.targets must be a Float64Array/],
      ['exportObj', { what: 'toString' }, /exportObj\.what must be 'mesh', 'cage', 'restCage'/],
    ];
    for (const [type, payload, message] of cases) {
      const reply = await request(type, payload);
      expect(reply.ok, type).toBe(false);
      expect(reply.error.code, type).toBe('invalid_argument');
      expect(reply.error.message).toMatch(message);
    }
    const notAnObject = await new Promise((resolve) => {
      pending.set(undefined, resolve);
      worker.postMessage(42);
    });
    pending.delete(undefined);
    expect(notAnObject.error.message).toMatch(/a request must be an object/);
  });

  // A glTF as the app's file picker hands it over: a capsule split at its UV seam (three's GLTFExporter) with a
  // box cage in OBJ. The worker welds it, says so, solves in the file's numbering, and exports it in its layout.
  it('loads a seam-split glTF with its cage, deforms it in the file\'s numbering and exports it in its own layout', async () => {
    const geometry = new CapsuleGeometry(0.4, 1.2, 6, 16);
    const glb = await exportGlb(meshOf(geometry));
    const cage = 'v -0.8 -1.3 -0.8\nv 0.8 -1.3 -0.8\nv 0.8 1.3 -0.8\nv -0.8 1.3 -0.8\nv -0.8 -1.3 0.8\nv 0.8 -1.3 0.8\nv 0.8 1.3 0.8\nv -0.8 1.3 0.8\n' +
      'f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n';
    const load = await request('loadFiles', { files: [{ name: 'capsule.glb', bytes: glb }, { name: 'cage.obj', bytes: new TextEncoder().encode(cage) }] });
    expect(load.ok, JSON.stringify(load.error)).toBe(true);
    const model = load.result;
    const fileVertices = geometry.getAttribute('position').count;
    expect(model.vertexCount).toBe(fileVertices);
    expect(model.layout.fileVertices).toBe(fileVertices);
    expect(model.layout.solverVertices).toBeLessThan(fileVertices);
    expect(model.notes.map((n) => n.code)).toContain('welded');
    expect(model.gltf.instances).toHaveLength(1);
    // The influence view colours the file's vertices: one weight each, the copies of a welded point alike.
    const column = (await request('basisColumn', { column: 6 })).result;
    expect(column.values).toHaveLength(fileVertices);
    const first = new Map();
    for (let v = 0; v < fileVertices; ++v) {
      const point = model.layout.solverOfFile[v];
      if (!first.has(point)) first.set(point, column.values[v]);
      expect(column.values[v]).toBe(first.get(point));
    }
    const p = model.mesh.positions, bottom = [], top = [];
    for (let i = 0; i < p.length / 3; ++i) {
      if (p[3 * i + 1] < -0.8) bottom.push(i);
      if (p[3 * i + 1] > 0.8) top.push(i);
    }
    expect((await request('setHandles', { groups: [bottom, top] })).ok).toBe(true);
    const targets = Float64Array.from([...bottom, ...top].flatMap((v, r) => [0, 1, 2].map((a) => p[3 * v + a] + (r >= bottom.length && a === 0 ? 0.2 : 0))));
    expect((await request('setTargets', { targets })).ok).toBe(true);
    let frame;
    for (let k = 0; k < 20 && !frame?.result.converged; ++k) frame = (await request('step', { iterations: 5 })).result;
    expect(frame.result.converged).toBe(true);
    expect(Math.abs(frame.result.iterations.at(-1).volumeRelError)).toBeLessThan(1e-6);
    expect(frame.positions.length).toBe(3 * fileVertices);
    expect(frame.positions[3 * top[0]] - p[3 * top[0]]).toBeGreaterThan(0.1);
    const warnings = (await request('resultWarnings')).result;
    expect(warnings).toEqual([]);  // a gentle pull: nothing folds, the box stays simple
    const exported = (await request('exportGlb')).result;
    const back = await readModel(solver, exported, 'back.glb');
    expect(back.mesh.indices).toEqual(model.mesh.indices);
    let gap = 0;
    for (let i = 0; i < frame.positions.length; ++i) gap = Math.max(gap, Math.abs(back.mesh.positions[i] - frame.positions[i]));
    expect(gap).toBeLessThan(1e-6);  // float32 in the file
    expect(back.gltf.json.meshes[0].primitives[0].attributes).toHaveProperty('TEXCOORD_0');
  });

  it('loads a .gltf dropped with its .bin as the same model, and names the .bin when it is missing', async () => {
    const { WebIO } = await import('@gltf-transform/core');
    const io = new WebIO();
    const document = await io.readBinary(await exportGlb(meshOf(new CapsuleGeometry(0.4, 1.2, 6, 16))));
    document.getRoot().listBuffers().forEach((b) => b.setURI('capsule.bin'));
    const { json, resources } = await io.writeJSON(document);
    const gltf = { name: 'capsule.gltf', bytes: new TextEncoder().encode(JSON.stringify(json)) };
    const bin = { name: 'capsule.bin', bytes: resources['capsule.bin'] };
    const cage = { name: 'cage.obj', bytes: new TextEncoder().encode(writeObj(solver, { positions: Float64Array.from([-0.8, -1.3, -0.8, 0.8, -1.3, -0.8, 0.8, 1.3, -0.8, -0.8, 1.3, -0.8,
      -0.8, -1.3, 0.8, 0.8, -1.3, 0.8, 0.8, 1.3, 0.8, -0.8, 1.3, 0.8]), indices: Uint32Array.from([0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
      1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7]) })) };
    const load = await request('loadFiles', { files: [gltf, bin, cage] });
    expect(load.ok, JSON.stringify(load.error)).toBe(true);
    expect(load.result.vertexCount).toBe(new CapsuleGeometry(0.4, 1.2, 6, 16).getAttribute('position').count);
    expect(load.result.notes.map((n) => n.code)).toContain('welded');
    const lost = await request('loadFiles', { files: [gltf, cage] });
    expect(lost.ok).toBe(false);
    expect(lost.error.message).toMatch(/capsule\.gltf: .*"capsule\.bin", which was not given/);
  });

  it('a sparse handle list is a named InputError across the worker too', async () => {
    await request('loadExample', { name: 'bar' });
    // eslint-disable-next-line no-sparse-arrays
    const reply = await request('setHandles', { groups: [[0], , [5]] });
    expect(reply.error).toMatchObject({ code: 'invalid_argument', message: 'handles: group 1 is missing (a hole in the array)' });
  });
});
