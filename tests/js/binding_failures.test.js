// A failing binding call frees what it held. The bindings hand their error to JS only after the C++ frames
// have unwound (cpp/bindings/js_bridge.h), so a throwing progress callback, or any failure, leaves the wasm
// heap and the emval handle table as they were; a callback's own exception reaches the caller as it was
// thrown (not as an 'internal' SolverError). Before this, 300 creates whose progress callback threw grew the
// heap from 64 MB to over 1.1 GB, and every failed call kept its arguments alive through leaked handles.
import { beforeAll, describe, expect, it } from 'vitest';
import {
  CancelledError, Deformer, InputError, computeWeights, generateCage, loadSolver, makeExample, readMesh,
} from 'subspace-deform';
import { thrown } from './support/thrown.js';

let solver, bar;
const heapBytes = () => solver.HEAPU8.buffer.byteLength;
const handles = () => solver.count_emval_handles();

beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
});

// Runs `attempt` `times` times, each expected to throw; returns the growth of the heap and of the handles.
function growth(times, attempt) {
  attempt(); // the first call may size the heap for this workload (free memory is reused after it)
  const heap = heapBytes();
  const table = handles();
  for (let i = 0; i < times; ++i) attempt();
  return { heapMB: (heapBytes() - heap) / 1e6, handles: handles() - table };
}

const boom = new Error('x');
const throwing = () => { throw boom; };
const expectBoom = (body) => expect(thrown(body)).toBe(boom);

describe('a progress callback that throws', () => {
  it('Deformer.create 300 times: the heap does not grow and the caller gets the callback\'s own error', () => {
    const { heapMB, handles: leaked } = growth(300, () => expectBoom(() => Deformer.create(solver, bar.mesh, bar.cage, { onProgress: throwing })));
    expect(heapMB).toBeLessThan(4); // 3.6 MB per throw before: about 1 GB for 300
    expect(leaked).toBe(0);
  });

  it('computeWeights and generateCage: the same', () => {
    const weights = growth(100, () => expectBoom(() => computeWeights(solver, bar.mesh, bar.cage, { progress: throwing })));
    expect(weights.heapMB).toBeLessThan(4);
    expect(weights.handles).toBe(0);
    const cage = growth(30, () => expectBoom(() => generateCage(solver, bar.mesh, { vertices: 40, onProgress: throwing })));
    expect(cage.heapMB).toBeLessThan(4);
    expect(cage.handles).toBe(0);
  });

  it('keeps what was thrown even when it is not an Error, and a callback returning false still cancels', () => {
    expect(thrown(() => Deformer.create(solver, bar.mesh, bar.cage, { onProgress: () => { throw 'stop'; } }))).toBe('stop');
    expect(thrown(() => Deformer.create(solver, bar.mesh, bar.cage, { onProgress: () => false }))).toBeInstanceOf(CancelledError);
  });

  it('the raw module throws the same value (no library wrapper involved)', () => {
    const error = thrown(() => new solver.DeformerSession(bar.mesh.positions, bar.mesh.indices, bar.cage.positions, bar.cage.indices,
      {}, throwing));
    expect(error).toBe(boom);
  });

  it('a callback may call into the module, even a call that fails, and the outer call still succeeds', () => {
    let inner = null;
    const d = Deformer.create(solver, bar.mesh, bar.cage, {
      onProgress: () => {
        inner ??= thrown(() => readMesh(solver, 'not a mesh', 'broken.obj'));
      },
    });
    expect(inner).toBeInstanceOf(InputError);
    expect(inner.code).toBe('parse_error');
    expect(d.vertexCount).toBe(bar.mesh.positions.length / 3);
    d.dispose();
  });
});

describe('any failing binding call', () => {
  it('keeps no emval handle (they kept the call\'s arguments alive) and no heap', () => {
    const bytes = new Uint8Array(1 << 20).fill(120); // 1 MB that is no mesh
    const read = growth(50, () => expect(thrown(() => readMesh(solver, bytes, 'x.obj')).code).toBe('parse_error'));
    expect(read.handles).toBe(0);
    expect(read.heapMB).toBeLessThan(4);
    const d = Deformer.create(solver, bar.mesh, bar.cage);
    // Straight to the binding, past the library's own check, so that the C++ check refuses it.
    const raw = growth(100, () => expect(thrown(() => d._session.setOptions({ maxIterations: 0 })).code).toBe('invalid_argument'));
    expect(raw.handles).toBe(0);
    d.dispose();
  });
});
