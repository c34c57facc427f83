// What an attack on the library and the CLI found, each kept as a repro: every case gets a named error (its
// own code, never 'internal') at once, or a correct result.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import {
  Deformer, InputError, MAX_VOLUME_PARTS, STOP_CODES, SolverError, errorFromData, loadExample, loadSolver, makeExample,
  parseScene, parseSceneHandles, typedError, volumeParts, writeObj,
} from 'subspace-deform';
import { thrown } from './support/thrown.js';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });
let solver, bar, dir;

beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
  dir = mkdtempSync(join(tmpdir(), 'sd-hostile-'));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

const inputError = (body, code = 'invalid_argument') => {
  const error = thrown(body);
  expect(error).toBeInstanceOf(InputError);
  expect(error.code).toBe(code);
  return error;
};

describe('prototype keys never reach a lookup', () => {
  const keys = ['constructor', '__proto__', 'toString', 'hasOwnProperty', 'valueOf'];

  it('an example named after one of Object\'s properties is an unknown example', async () => {
    for (const name of keys) {
      const error = await loadExample(solver, name).then(() => null, (e) => e);
      expect(error, name).toBeInstanceOf(InputError);
      expect(error.message).toMatch(/unknown example/);
    }
    // Every built-in example is named, those loaded from packages and files (bunny, spot) too.
    const error = await loadExample(solver, 'cow').then(() => null, (e) => e);
    expect(error.message).toMatch(/built-in examples: .*bunny.*spot/);
  });

  it('the CLI: a scene with such an example, a command or a flag of that name', () => {
    writeFileSync(join(dir, 'proto.json'), JSON.stringify({ example: 'constructor', handles: [] }));
    const scene = run('deform', join(dir, 'proto.json'));
    expect(scene.status).toBe(1);
    expect(scene.stderr).toMatch(/^error \(invalid_argument\): .*unknown example/);
    expect(run('constructor').status).toBe(2);
    expect(run('check', 'x.obj', '--constructor', '1').stderr).toMatch(/unknown option --constructor/);
    expect(run('check', 'x.obj', '--__proto__', '1').status).toBe(2);
  });

  it('error data with such a code is an internal SolverError, not a crash', () => {
    for (const code of keys) {
      expect(errorFromData({ code, message: 'm' })).toBeInstanceOf(SolverError);
      expect(typedError(Object.assign(new Error('m'), { code })).code).toBe('internal');
    }
  });
});

describe('ordinary conditions have their own codes', () => {
  it('setHandles with a sparse array names the hole', () => {
    const d = Deformer.create(solver, bar.mesh, bar.cage);
    // eslint-disable-next-line no-sparse-arrays
    expect(inputError(() => d.setHandles([[0], , [5]])).message).toBe('handles: group 1 is missing (a hole in the array)');
    // eslint-disable-next-line no-sparse-arrays
    expect(inputError(() => d.setHandles([[0, , 2]])).message).toMatch(/group 0 has no vertex at position 1/);
    // The check is the binding's (it used to fail inside with a TypeError): the raw session gives the same error.
    // eslint-disable-next-line no-sparse-arrays
    expect(thrown(() => d._session.setHandles([[0], , [5]])).code).toBe('invalid_argument');
    d.setHandles([[0], [5]]);
    expect(d.handleCount).toBe(2);
    d.dispose();
  });

  it('a scene with more handle vertices than any mesh has is refused before its indices are read', () => {
    const huge = { vertices: new Array(20_000_000) }; // holes: nothing is allocated per index
    expect(inputError(() => parseSceneHandles([huge])).message)
      .toBe('scene: "handles" list 20000000 vertices: more than the 16777215 any mesh can have');
    expect(inputError(() => parseScene({ example: 'bar', handles: [{ vertices: [0] }, huge] })).message).toMatch(/20000001 vertices/);
  });

  it('explicit volume parts are bounded like the automatic ones, before any work', () => {
    const triangles = bar.mesh.indices.length / 3;
    const onePerTriangle = Array.from({ length: triangles }, (_, t) => [t]);
    expect(inputError(() => parseScene({ example: 'bar', handles: [], volumeParts: { triangles: onePerTriangle } })).message)
      .toMatch(new RegExp(`has ${triangles} lists: a partition may have at most ${MAX_VOLUME_PARTS} parts`));
    expect(inputError(() => volumeParts(solver, bar.mesh, { auto: MAX_VOLUME_PARTS + 1 })).message).toMatch(new RegExp(`from 1 to ${MAX_VOLUME_PARTS}`));
    const d = Deformer.create(solver, bar.mesh, bar.cage);
    const each = Int32Array.from({ length: triangles }, (_, t) => t);
    // The C++ limit (partition.h) is the library's: the message names the same number.
    expect(inputError(() => d.setVolumeParts(each)).message).toMatch(new RegExp(`ask for ${triangles} parts, more than the ${MAX_VOLUME_PARTS} `));
    expect(d.volumeParts()).toHaveLength(0); // the session is as it was
    d.dispose();
    // The raw bindings refuse the same without the library's checks.
    expect(thrown(() => solver.autoVolumeParts(bar.mesh.positions, bar.mesh.indices, 2147483647)).message).toMatch(/got 2147483647/);
  });
});

describe('messages', () => {
  it('a spectral basis of 2147483647 modes names that number', () => {
    const error = thrown(() => Deformer.create(solver, bar.mesh, null, { basis: 'spectral', modes: 2147483647 }));
    expect(error.code).toBe('invalid_argument');
    expect(error.message).toMatch(/got 2147483647$/);
  });

  it('writeObj refuses a NaN instead of writing "v nan 0 0"', () => {
    const positions = bar.mesh.positions.slice();
    positions[3] = NaN;
    expect(inputError(() => writeObj(solver, { positions, indices: bar.mesh.indices })).message)
      .toMatch(/vertex 1 has a NaN or infinite coordinate/);
  });

  it('a cage beyond 1e30 is refused for its coordinates, not as "all vertices outside the cage"', () => {
    const cage = { positions: bar.cage.positions.map((x) => x * 1e31), indices: bar.cage.indices };
    const error = thrown(() => Deformer.create(solver, bar.mesh, cage));
    expect(error.findings.map((f) => f.code)).toContain('coordinates_too_large');
    expect(error.findings.map((f) => f.code)).not.toContain('outside_cage');
  });

  it('targets at 1e150 to 1e155 end with a named stop and finite positions, never "nan" in the reason', () => {
    const fixed = [0, 1, 2];
    for (const method of ['subspace', 'full', 'arap']) {
      const d = Deformer.create(solver, bar.mesh, bar.cage);
      d.setOptions({ method });
      for (const scale of [1e150, 1e154, 1.3e154, 1e155]) {
        d.reset();
        // The core's own robustness: a scene and Deformer.setTargets refuse targets beyond MAX_MESH_COORDINATE, so
        // they are set on the raw session, past the JS check (as a caller of the bindings could).
        const groups = [fixed, [57]];
        const targets = Float64Array.from([...fixed, 57].flatMap((v) => [0, 1, 2].map((a) => bar.mesh.positions[3 * v + a])));
        targets[9] += scale;
        d.setHandles(groups);
        expect(() => d.setTargets(targets)).toThrow(/beyond the 1e30 a mesh may have/);
        d._session.setTargets(targets);
        const result = d.solve();
        expect(result.stopReason, `${method} at ${scale}`).not.toMatch(/\bnan\b|\binf\b/i);
        expect(STOP_CODES.map((c) => c.name), `${method} at ${scale}`).toContain(result.stop);
        expect(d.positions().every(Number.isFinite)).toBe(true);
      }
      d.dispose();
    }
  });
});

describe('rotation axes near the largest double', () => {
  it('are made unit length without overflowing to a zero axis (the scene parser rotated by cos(angle) times I)', () => {
    const [handle] = parseSceneHandles([{ vertices: [0], rotate: { axis: [-8.147165508355817e+300, -1.797693134862314e+308, 0], angle: 0.5 } }]);
    expect(Math.hypot(...handle.rotate.axis)).toBeCloseTo(1, 12);
    expect(handle.rotate.axis[1]).toBeCloseTo(-1, 12);
  });
});
