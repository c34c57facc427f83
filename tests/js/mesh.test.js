// The mesh layer through the wasm module: parsing, writing, checks, examples, and readable errors.
import { describe, expect, it, beforeAll } from 'vitest';
import { InputError, loadSolver } from 'subspace-deform';
import { checkMesh, checkPair, exampleNames, makeExample, readMesh, writeObj } from '../../web/lib/mesh.js';

let solver;
beforeAll(async () => {
  solver = await loadSolver();
});

const encoder = new TextEncoder();
const TETRA_OBJ = `# tetrahedron, outward
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
`;

describe('readMesh / writeObj', () => {
  it('parses OBJ bytes into typed arrays and round-trips through writeObj exactly', () => {
    const mesh = readMesh(solver, encoder.encode(TETRA_OBJ), 'tetra.obj');
    expect(mesh.positions).toBeInstanceOf(Float64Array);
    expect(mesh.indices).toBeInstanceOf(Uint32Array);
    expect(mesh.positions.length).toBe(12);
    expect(Array.from(mesh.indices.slice(0, 3))).toEqual([0, 2, 1]);
    const again = readMesh(solver, writeObj(solver, mesh), 'again.obj');
    expect(Array.from(again.positions)).toEqual(Array.from(mesh.positions));
    expect(Array.from(again.indices)).toEqual(Array.from(mesh.indices));
  });

  it('turns parser failures into Errors that name the file and line', () => {
    const bad = encoder.encode('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n');
    expect(() => readMesh(solver, bad, 'bad.obj')).toThrow(/bad\.obj.*line 4/);
    expect(() => readMesh(solver, new Uint8Array([0xff, 0x00, 0x13, 0x37]), 'garbage.stl')).toThrow(/garbage\.stl/);
  });

  it('rejects wrong argument types before entering wasm', () => {
    expect(() => readMesh(solver, 42, 'x.obj')).toThrow(InputError);
    expect(() => checkMesh(solver, { positions: [0, 0, 0], indices: new Uint32Array() })).toThrow(/Float64Array/);
    expect(() => checkMesh(solver, { positions: new Float64Array(9), indices: new Uint32Array([0, 1, 7]) })).toThrow(/vertex 7/);
  });
});

describe('checks', () => {
  it('accepts a closed outward tetrahedron with volume 1/6 and genus 0', () => {
    const report = checkMesh(solver, readMesh(solver, encoder.encode(TETRA_OBJ), 'tetra.obj'));
    expect(report.ok).toBe(true);
    expect(report.summary.volume).toBeCloseTo(1 / 6, 12);
    expect(report.summary.genus).toBe(0);
    expect(report.summary.components).toBe(1);
  });

  it('notes an open mesh (its hole capped), refuses it as a cage, and reports a flipped mesh', () => {
    const open = readMesh(solver, encoder.encode(TETRA_OBJ.split('\n').slice(0, -2).join('\n')), 'open.obj');
    const openReport = checkMesh(solver, open);
    expect(openReport.ok).toBe(true);
    expect(openReport.findings).toMatchObject([{ severity: 'note', code: 'open' }]);
    expect(openReport.summary.holes).toBe(1);
    expect(openReport.summary.volume).toBeCloseTo(1 / 6, 12);  // the hole's fan closes the tetrahedron again
    const asCage = checkMesh(solver, open, 'cage');
    expect(asCage.ok).toBe(false);
    expect(asCage.findings.map((f) => f.code)).toContain('open');

    const flipped = readMesh(solver, encoder.encode(TETRA_OBJ.replace(/f (\d) (\d) (\d)/g, 'f $1 $3 $2')), 'flip.obj');
    const flippedReport = checkMesh(solver, flipped);
    expect(flippedReport.ok).toBe(false);
    expect(flippedReport.text).toMatch(/inward|flip|orient/i);
  });

  it('finds mesh vertices outside the cage and names them', () => {
    const { mesh, cage } = makeExample(solver, 'bar');
    expect(checkPair(solver, mesh, cage).ok).toBe(true);
    const moved = { positions: mesh.positions.slice(), indices: mesh.indices };
    moved.positions[3 * 5] += 10; // push vertex 5 far along x
    const report = checkPair(solver, moved, cage);
    expect(report.ok).toBe(false);
    expect(report.text).toMatch(/outside/);
    expect(report.text).toMatch(/\b5\b/);
  });
});

describe('built-in examples', () => {
  it('every example is a valid mesh strictly inside a valid cage', () => {
    const names = exampleNames(solver);
    expect(names[0]).toBe('bar');
    for (const name of names) {
      const example = makeExample(solver, name);
      const report = checkPair(solver, example.mesh, example.cage);
      expect(report.ok, `${name}: ${report.text}`).toBe(true);
      expect(report.summary.genus).toBe(0);
    }
  });

  it('an unknown example is an Error listing the known ones', () => {
    expect(() => makeExample(solver, 'teapot')).toThrow(/unknown example 'teapot'.*bar/);
  });
});
