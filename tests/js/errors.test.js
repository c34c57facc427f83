// Errors with codes end to end: each kind of failure arrives in JS with its class and its code (from the
// C++ core through the bindings, or from the library's own checks), survives the trip through the
// worker's messages as data, and reaches the command line as an exit status and "error (code): ...".
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import {
  CODES_BY_CLASS, CancelledError, Deformer, ERROR_CODES, InputError, MeshError, SolverError, SubspaceDeformError, computeWeights,
  errorFromData, errorToData, generateCage, loadSolver, makeExample, readMesh, typedError, writeObj,
} from 'subspace-deform';
import { thrown } from './support/thrown.js';
import { failure } from '../../scripts/lib/cli_support.mjs';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });
let solver, bar, sphere, dir;

beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
  sphere = makeExample(solver, 'sphere').mesh;
  dir = mkdtempSync(join(tmpdir(), 'sd-errors-'));
  writeFileSync(join(dir, 'bar.obj'), writeObj(solver, bar.mesh));
  writeFileSync(join(dir, 'bar_cage.obj'), writeObj(solver, shiftedCage()));
  writeFileSync(join(dir, 'garbage.stl'), Buffer.from(Array.from({ length: 300 }, (_, i) => (i * 7919) % 256)));
  writeFileSync(join(dir, 'huge.json'), JSON.stringify({ example: 'bar', handles: [], solver: { maxIterations: 1e300 } }));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

// The bar's cage moved so that the bar sticks out of it.
function shiftedCage() {
  const positions = bar.cage.positions.slice();
  for (let i = 0; i < positions.length; i += 3) positions[i] += 1.0;
  return { positions, indices: bar.cage.indices };
}

// Every triangle turned around: an inward mesh (an open one would be accepted, its hole capped).
function flipped(indices) {
  const out = indices.slice();
  for (let f = 0; f < out.length; f += 3) [out[f + 1], out[f + 2]] = [out[f + 2], out[f + 1]];
  return out;
}

// A closed, outward tetrahedron of 4 vertices around the origin, well inside the bar's cage: far fewer rows
// than one progress step.
function smallTetrahedron() {
  const positions = new Float64Array([0, 0, 0, 0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]).map((x) => x - 0.025);
  return { positions, indices: new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]) };
}

describe('typed errors', () => {
  it.each([
    ['a file that is no mesh', () => readMesh(solver, new Uint8Array([0xff, 0, 0x13, 0x37]), 'garbage.stl'), InputError, 'parse_error'],
    ['an inward mesh', () => Deformer.create(solver, { positions: bar.mesh.positions, indices: flipped(bar.mesh.indices) }, bar.cage),
      MeshError, 'invalid_mesh'],
    ['a mesh outside its cage (bind)', () => Deformer.create(solver, bar.mesh, shiftedCage()), MeshError, 'mesh_outside_cage'],
    ['a mesh outside its cage (weights)', () => computeWeights(solver, bar.mesh, shiftedCage()), MeshError, 'mesh_outside_cage'],
    ['a cancelled bind', () => Deformer.create(solver, bar.mesh, bar.cage, { onProgress: () => false }), CancelledError, 'cancelled'],
    ['cancelled weights', () => computeWeights(solver, bar.mesh, bar.cage, { progress: () => false }), CancelledError, 'cancelled'],
    ['cancelled weights of a few rows (one progress call, the last)', () => computeWeights(solver, smallTetrahedron(), bar.cage,
      { progress: () => false }), CancelledError, 'cancelled'],
    ['a cancelled cage', () => generateCage(solver, sphere, { vertices: 40, onProgress: () => false }), CancelledError, 'cancelled'],
    ['W over the memory budget', () => computeWeights(solver, bar.mesh, bar.cage, { memoryBudgetMB: 0.001 }), SolverError,
      'memory_budget'],
    ['a bad argument (JS check)', () => Deformer.create(solver, { positions: [0, 0, 0], indices: new Uint32Array(3) }, null),
      InputError, 'invalid_argument'],
    ['a bad argument (C++ check)', () => makeExample(solver, 'teapot'), InputError, 'invalid_argument'],
  ])('%s arrives with its class and code', (_, body, Type, code) => {
    const error = thrown(body);
    expect(error).toBeInstanceOf(Type);
    expect(error).toBeInstanceOf(SubspaceDeformError);
    expect(error.code).toBe(code);
    expect(error.message.length).toBeGreaterThan(5);
  });

  it('carries the findings of a mesh that failed its checks', () => {
    const error = thrown(() => Deformer.create(solver, bar.mesh, shiftedCage()));
    const codes = error.findings.filter((f) => f.severity === 'error').map((f) => f.code);
    expect(codes).toContain('outside_cage');
    expect(codes.every((c) => c === 'outside_cage' || c === 'on_cage')).toBe(true); // only the placement is wrong
    for (const finding of error.findings) expect(error.message).toContain(finding.message);
  });

  it('puts every C++ error code in exactly one class', () => {
    const all = Object.values(CODES_BY_CLASS).flat();
    expect([...all].sort()).toEqual([...ERROR_CODES].sort());
    expect(new Set(all).size).toBe(all.length);
  });

  // The table in docs/library.md is where a caller looks up which class a code belongs to.
  it('lists each class\'s codes in library.md\'s table of errors as errors.js maps them', () => {
    const library = readFileSync(new URL('../../docs/library.md', import.meta.url), 'utf8');
    for (const [type, codes] of Object.entries(CODES_BY_CLASS)) {
      const row = library.match(new RegExp(`^\\| \`${type}\` \\| (.*?) \\|`, 'm'));
      expect(row, type).not.toBeNull();
      expect([...row[1].matchAll(/`(\w+)`/g)].map((m) => m[1]).sort(), type).toEqual([...codes].sort());
    }
  });

  it('crosses the worker boundary as data and comes back with the same class, code and findings', () => {
    const original = thrown(() => Deformer.create(solver, bar.mesh, shiftedCage()));
    const data = structuredClone(errorToData(original)); // what postMessage delivers
    const rebuilt = errorFromData(data);
    expect(rebuilt).toBeInstanceOf(MeshError);
    expect(rebuilt.code).toBe(original.code);
    expect(rebuilt.message).toBe(original.message);
    expect(rebuilt.findings).toEqual(original.findings);
    expect(errorFromData(errorToData(new CancelledError()))).toBeInstanceOf(CancelledError);
    expect(errorFromData({ code: 'no_cage', message: 'bar.obj has no cage' })).toMatchObject({ name: 'InputError', code: 'no_cage' });
  });

  it('types what the raw module throws by its code, and anything else as an internal SolverError', () => {
    const raw = thrown(() => solver.readMesh('v 1 2\n', 'x.obj')); // straight from the bindings
    expect(raw).not.toBeInstanceOf(SubspaceDeformError);
    expect(raw.code).toBe('parse_error');
    expect(typedError(raw)).toBeInstanceOf(InputError);
    const bug = new TypeError('x is undefined');
    const typed = typedError(bug);
    expect(typed).toBeInstanceOf(SolverError);
    expect(typed.code).toBe('internal');
    expect(typed.cause).toBe(bug);
    expect(errorToData(bug)).toEqual({ code: 'internal', message: 'x is undefined' });
  });
});

describe('the command line exit path', () => {
  it.each([
    ['a file that is no mesh', ['check', 'garbage.stl'], 1, /^error \(parse_error\): garbage\.stl: /m],
    ['a mesh outside its cage', ['weights', 'bar.obj', 'bar_cage.obj', '--out', 'W.npy'], 1, /^error \(mesh_outside_cage\): /m],
    ['a missing file', ['check', 'nope.obj'], 1, /^error \(unreadable_file\): cannot read .*nope\.obj: no such file/m],
    ['a scene option past its limit', ['deform', 'huge.json'], 1,
      /^error \(invalid_argument\): scene: solver\.maxIterations must be an integer from 1 to 2147483647 \(got 1e\+300\)/m],
    ['a flag past its limit', ['deform', 'huge.json', '--max-iterations', '2147483648'], 2,
      /^usage error: --max-iterations must be an integer from 1 to 2147483647 \(got "2147483648"\)/m],
  ])('%s: exit status and the code on stderr', (_, args, status, pattern) => {
    const r = run(...args.map((a) => (/\.(obj|stl|json|npy)$/.test(a) ? join(dir, a) : a)));
    expect(r.status).toBe(status);
    expect(r.stderr).toMatch(pattern);
    expect(r.stderr).not.toMatch(/at .*\.js:\d+/);
  });

  // The bind's mesh check throws the core's report text ("error: ...\n"), which used to be printed as it was:
  // "error (mesh_outside_cage): error: ..." and an empty line.
  it('prints a failed mesh check once, without the report\'s own prefix or an empty line', () => {
    writeFileSync(join(dir, 'outside.json'), JSON.stringify({ mesh: 'bar.obj', cage: 'bar_cage.obj', handles: [{ vertices: [0] }] }));
    const r = run('deform', join(dir, 'outside.json'));
    expect(r.status).toBe(1);
    // Two findings (the shifted cage leaves some vertices outside and some on its surface): one line each.
    expect(r.stderr).toMatch(/^error \(mesh_outside_cage\): \d+ of \d+ mesh vertices are outside the cage [^\n]*\n {2}error: \d+ of \d+ mesh vertices lie on the cage surface [^\n]*\n$/);
    const several = failure(new MeshError('error: cage: a\nerror: cage: b\nwarning: cage: c\n', { code: 'invalid_mesh' }));
    expect(several).toEqual({ status: 1, message: 'error (invalid_mesh): cage: a\n  error: cage: b\n  warning: cage: c' });
    expect(failure(new InputError('error: a name\n')).message).toBe('error (invalid_argument): error: a name\n'); // not a check's report
  });
});
