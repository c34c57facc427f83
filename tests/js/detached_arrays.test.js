// Issue 32, item 8: a typed array whose buffer was transferred (structuredClone or postMessage with `transfer`)
// is detached and reads as empty. Every library entry that takes typed arrays names it as an InputError (it used
// to be 'internal' from inside wasm, or to pass silently as an empty partition); and a mesh too small for the
// spectral basis or an automatic partition is told the smallest size, not "must be from 1 to 0".
import { beforeAll, describe, expect, it } from 'vitest';
import {
  Deformer, InputError, checkMesh, checkPair, computeWeights, generateCage, handleTargets, layoutNormals, loadSolver,
  makeExample, readMesh, readModel, volumeParts, writeModel, writeObj,
} from 'subspace-deform';
import { SolverClient } from '../../web/lib/worker/solver_client.js';
import { isDetached } from '../../web/lib/typed_arrays.js';
import { thrown } from './support/thrown.js';

let solver, bar, obj;
beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
  obj = new TextEncoder().encode(writeObj(solver, bar.mesh));
});

/** A copy of `array` whose buffer has been transferred away. */
function detached(array) {
  const copy = array.slice();
  structuredClone(copy, { transfer: [copy.buffer] });
  return copy;
}

const DETACHED = /is a detached (Float64Array|Uint32Array|Int32Array|Float32Array|Uint8Array|ArrayBuffer): its buffer was transferred/;

function expectNamed(error, what) {
  expect(error).toBeInstanceOf(InputError);
  expect(error.code).toBe('invalid_argument');
  expect(error.message).toMatch(DETACHED);
  expect(error.message).toContain(what);
}

describe('a detached typed array is an InputError naming it, at every entry', () => {
  it('tells detached buffers from empty ones', () => {
    expect(isDetached(detached(new Float64Array(3)))).toBe(true);
    expect(isDetached(new Float64Array(0))).toBe(false);
    expect(isDetached(new ArrayBuffer(0))).toBe(false);
    expect(isDetached([1, 2])).toBe(false);
    const buffer = new ArrayBuffer(8);
    structuredClone(buffer, { transfer: [buffer] });
    expect(isDetached(buffer)).toBe(true);
  });

  it('a Deformer session: setTargets, setHandles, setVolumeParts, renderBuffers', () => {
    const d = Deformer.create(solver, bar.mesh, bar.cage);
    d.setHandles([[0, 1, 2], [57]]);
    expectNamed(thrown(() => d.setTargets(detached(new Float64Array(12)))), 'setTargets: targets');
    expectNamed(thrown(() => d.setHandles([[0], detached(new Int32Array([1, 2]))])), 'setHandles: group 1');
    // A detached partition used to pass as "no parts" (the default ones), silently.
    expectNamed(thrown(() => d.setVolumeParts(detached(new Int32Array(bar.mesh.indices.length / 3)))), 'setVolumeParts: parts');
    expectNamed(thrown(() => d.renderBuffers({ restNormals: detached(new Float32Array(bar.mesh.positions.length)) })), 'renderBuffers: restNormals');
    d.dispose();
  });

  it('mesh data: Deformer.create, checkMesh, checkPair, writeObj, computeWeights, generateCage, volumeParts', () => {
    const noPositions = { positions: detached(bar.mesh.positions), indices: bar.mesh.indices };
    const noIndices = { positions: bar.mesh.positions, indices: detached(bar.mesh.indices) };
    expectNamed(thrown(() => Deformer.create(solver, noPositions, bar.cage)), 'Deformer.create: mesh.positions');
    expectNamed(thrown(() => Deformer.create(solver, noIndices, bar.cage)), 'Deformer.create: mesh.indices');
    expectNamed(thrown(() => Deformer.create(solver, bar.mesh, noIndices)), 'Deformer.create: cage.indices');
    expectNamed(thrown(() => checkMesh(solver, noPositions)), 'mesh.positions');
    expectNamed(thrown(() => checkPair(solver, bar.mesh, noIndices)), 'cage.indices');
    expectNamed(thrown(() => writeObj(solver, noIndices)), 'mesh.indices');
    expectNamed(thrown(() => computeWeights(solver, noPositions, bar.cage)), 'computeWeights: mesh.positions');
    expectNamed(thrown(() => generateCage(solver, noIndices, { vertices: 50 })), 'generateCage: mesh.indices');
    expectNamed(thrown(() => volumeParts(solver, noPositions, { auto: 2 })), 'volumeParts: mesh.positions');
    expectNamed(thrown(() => volumeParts(solver, bar.mesh, { triangles: [detached(new Int32Array([0]))] })), 'volumeParts.triangles[0]');
    expectNamed(thrown(() => layoutNormals(detached(bar.mesh.positions), bar.mesh.indices)), 'layoutNormals: positions');
    expectNamed(thrown(() => handleTargets(detached(bar.mesh.positions), [{ vertices: [0], translate: [0, 0, 0] }])), 'handleTargets: restPositions');
  });

  it('file bytes and positions: readMesh, readModel, writeModel', async () => {
    expectNamed(thrown(() => readMesh(solver, detached(obj), 'bar.obj')), 'readMesh: bytes');
    const buffer = obj.slice().buffer;
    structuredClone(buffer, { transfer: [buffer] });
    expectNamed(thrown(() => readMesh(solver, buffer, 'bar.obj')), 'readMesh: bytes');
    expectNamed(await readModel(solver, detached(obj), 'bar.obj').catch((e) => e), 'readModel: bytes');
    expectNamed(await readModel(solver, obj, 'm.gltf', { resources: { 'm.bin': detached(obj) } }).catch((e) => e), 'readModel: resources["m.bin"]');
    expectNamed(await writeModel(solver, { mesh: bar.mesh }, detached(bar.mesh.positions), 'x.obj').catch((e) => e), 'writeModel: positions');
  });

  it('SolverClient.request names a detached array in its payload (postMessage cannot clone it)', async () => {
    // The client without its browser worker: a stand-in that clones the message as postMessage does.
    const client = Object.assign(Object.create(SolverClient.prototype), {
      terminated: false, pending: new Map(), worker: { postMessage: (message, transfer) => structuredClone(message, { transfer }) },
    });
    const error = await client.request('setTargets', { targets: detached(new Float64Array(6)) }).catch((e) => e);
    expect(error).toBeInstanceOf(InputError);
    expect(error.message).toMatch(/^setTargets: targets is a detached typed array/);
    const files = await client.request('loadFiles', { files: [{ name: 'a.obj', bytes: obj }, { name: 'b.obj', bytes: detached(obj) }] }).catch((e) => e);
    expect(files.message).toMatch(/^loadFiles: files\[1\]\.bytes is a detached/);
    expect(client.pending.size).toBe(0);
  });
});

describe('a mesh too small for the spectral basis or automatic parts is told the smallest size', () => {
  const tetrahedron = {
    positions: new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]),
    indices: new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]),
  };
  const octahedron = {
    positions: new Float64Array([1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1]),
    indices: new Uint32Array([0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5]),
  };

  it('the spectral basis: at least 6 vertices (a 6-vertex mesh binds one mode)', () => {
    for (const modes of [1, 3]) {
      const error = thrown(() => Deformer.create(solver, tetrahedron, null, { basis: 'spectral', modes }));
      expect(error).toBeInstanceOf(InputError);
      expect(error.message).toBe('Deformer.create: the spectral basis needs a mesh of at least 6 vertices; this one has 4');
      expect(error.message).not.toMatch(/from 1 to 0/);
    }
    const d = Deformer.create(solver, octahedron, null, { basis: 'spectral', modes: 1 });
    expect(d.basisEigenvalues().length).toBeGreaterThan(0);
    d.dispose();
  });

  it('automatic volume parts: at least 5 vertices (a 6-vertex mesh takes them)', () => {
    const error = thrown(() => volumeParts(solver, tetrahedron, { auto: 2 }));
    expect(error).toBeInstanceOf(InputError);
    expect(error.message).toBe('volumeParts: the automatic partition needs a mesh of at least 5 vertices; this one has 4');
    expect(volumeParts(solver, octahedron, { auto: 1 })).toHaveLength(8);
  });
});
