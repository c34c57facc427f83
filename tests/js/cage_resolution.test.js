// The solver worker's one decision on a load (web/lib/worker/cage_resolution.js): the cage given, a generated one,
// none for the spectral basis, or the refusal, with the same words for loadExample, loadFiles and loadMeshes.
import { beforeAll, describe, expect, it } from 'vitest';
import { InputError, MeshError, loadSolver, makeExample } from 'subspace-deform';
import { cageProgress, resolveCage } from '../../web/lib/worker/cage_resolution.js';

let solver, bar, worker, posted;
beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
  posted = [];
  worker = { solver, post: (fraction, phase) => posted.push({ fraction, phase }) };
});

const spectral = { basis: 'spectral', modes: 8 };
const given = () => ({ cage: bar.cage, cageName: 'bar_cage.obj', description: 'bar in bar_cage.obj' });

function refusal(load) {
  try {
    resolveCage(worker, load);
  } catch (error) {
    return error;
  }
  throw new Error('no refusal');
}

describe('resolveCage', () => {
  it('binds the cage given, with either basis, and generates none unless it replaces the given one', () => {
    for (const subspace of [undefined, { basis: 'cage', coordinates: 'pmvc' }, spectral]) {
      expect(resolveCage(worker, { name: 'bar', mesh: bar.mesh, given: given(), generate: { vertices: 12 }, subspace }))
        .toEqual({ cage: bar.cage, cageName: 'bar_cage.obj', description: 'bar in bar_cage.obj', generated: null });
    }
  });

  it('binds no cage with the spectral basis, in the page\'s words if it has some', () => {
    expect(resolveCage(worker, { name: 'lone.obj', mesh: bar.mesh, given: null, generate: { vertices: 12 }, subspace: spectral }))
      .toEqual({ cage: null, cageName: 'no cage', description: 'lone.obj in its spectral basis (8 modes)', generated: null });
    expect(resolveCage(worker, { name: 'lone.obj', mesh: bar.mesh, given: null, subspace: spectral, description: 'the bar' }).description)
      .toBe('the bar');
  });

  it('generates a cage when asked (reporting progress), and in place of the given one when it replaces it', () => {
    posted.length = 0;
    const made = resolveCage(worker, { name: 'lone.obj', mesh: bar.mesh, given: null, generate: { vertices: 12 } });
    expect(made.cage).toBe(made.generated);
    expect(made.cageName).toBe('generated cage');
    expect(made.description).toBe(`lone.obj in a generated ${made.cage.positions.length / 3}-vertex cage`);
    expect(posted[0]).toEqual({ fraction: 0, phase: 'generating a 12-vertex cage' });
    const replaced = resolveCage(worker, { name: 'bar', mesh: bar.mesh, given: given(), generate: { vertices: 12 }, regenerate: true, subspace: spectral });
    expect(replaced.cageName).toBe('generated cage');
    expect(replaced.cage).not.toBe(bar.cage);
  });

  it('refuses a lone mesh with the cage basis and nothing to make, once for every load', () => {
    const error = refusal({ name: 'lone.obj', mesh: bar.mesh, given: null, subspace: { basis: 'cage' } });
    expect(error).toBeInstanceOf(InputError);
    expect(error.code).toBe('no_cage');
    expect(error.message).toBe('lone.obj has no cage. Drop the mesh together with its cage (two files), or use "Generate cage".');
    // A mesh no cage could help: the checker's findings instead.
    const fin = { positions: new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1]),
      indices: new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 1, 2, 4]) };
    const broken = refusal({ name: 'fin.obj', mesh: fin, given: null });
    expect(broken).toBeInstanceOf(MeshError);
    expect(broken.message).toMatch(/^fin\.obj has no cage, and it cannot get a generated one until these are fixed:\n/);
    expect(broken.findings.map((f) => f.code)).toContain('non_manifold_edge');
    expect(refusal({ name: 'fin.obj', mesh: fin, given: null, generate: { vertices: 12 } }).message).toMatch(/^fin\.obj cannot get a cage:\n/);
  });
});

describe('cageProgress', () => {
  it('posts the start and then at most once per percent', () => {
    const seen = [];
    const report = cageProgress((fraction, phase) => seen.push([fraction, phase]), 'making');
    for (let i = 0; i <= 1000; ++i) report(i / 1000);
    expect(seen[0]).toEqual([0, 'making']);
    expect(seen).toHaveLength(1 + 101); // the start, then 0 % .. 100 %
  });
});
