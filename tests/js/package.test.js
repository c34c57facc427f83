// The library as a package: Node's self-reference resolves 'subspace-deform' to the Node entry wherever a
// script runs in the project, the browser entry offers the same library plus its loader and the worker
// client, the exports map names files that exist after a build, and the TypeScript declarations generate
// from the JSDoc without errors and type the API (a wrong option name does not compile).
import { describe, expect, it, afterAll } from 'vitest';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import * as browserEntry from '../../web/lib/index.js';
import * as nodeEntry from '../../web/lib/node.js';

const root = resolve(new URL('../..', import.meta.url).pathname);
const pkg = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8'));
const tsc = join(root, 'node_modules/typescript/bin/tsc');
const dirs = [];
afterAll(() => dirs.forEach((d) => rmSync(d, { recursive: true, force: true })));

describe('the subspace-deform package', () => {
  it.each(['.', 'scripts', 'tests/js'])('resolves to the Node entry from %s and loads the solver', (cwd) => {
    const script = `import { loadSolver, exampleNames } from 'subspace-deform';
      const solver = await loadSolver();
      console.log(JSON.stringify({ entry: import.meta.resolve('subspace-deform'), names: exampleNames(solver) }));`;
    const r = spawnSync(process.execPath, ['--input-type=module', '-e', script], { cwd: join(root, cwd), encoding: 'utf8', timeout: 60000 });
    expect(r.stderr).toBe('');
    const out = JSON.parse(r.stdout);
    expect(out.entry).toBe(new URL(`file://${join(root, 'web/lib/node.js')}`).href);
    expect(out.names).toEqual(expect.arrayContaining(['bar', 'bunny']));
  });

  it('offers the same library from both entries, each with its own loader', () => {
    const browserOnly = Object.keys(browserEntry).filter((k) => !(k in nodeEntry));
    const nodeOnly = Object.keys(nodeEntry).filter((k) => !(k in browserEntry));
    expect(browserOnly.sort()).toEqual(['SolverClient', 'pageThreads', 'setPageThreads']);
    expect(nodeOnly.sort()).toEqual(['checkWritable', 'loadNodeSolver', 'parseThreads', 'readFileBytes', 'wasmDir', 'writeFileBytes']);
    expect(nodeEntry.loadSolver).toBe(nodeEntry.loadNodeSolver);
    expect(browserEntry.loadSolver).not.toBe(nodeEntry.loadSolver);
    for (const name of ['Deformer', 'readMesh', 'checkPair', 'parseScene', 'generateCage', 'computeWeights', 'loadExample',
      'OPTIONS', 'InputError', 'MeshError', 'SolverError', 'CancelledError', 'ERROR_CODES', 'STOP_CODES']) {
      expect(nodeEntry[name], name).toBeDefined();
      expect(browserEntry[name], name).toBe(nodeEntry[name]);
    }
  });

  it('has an exports map with node and default conditions whose files exist after a build', () => {
    const main = pkg.exports['.'];
    expect(main.node.default).toBe('./web/lib/node.js');
    expect(main.default.default).toBe('./web/lib/index.js');
    for (const path of [main.node.default, main.default.default, main.node.types, main.default.types, pkg.types]) {
      expect(existsSync(join(root, path)), `${path} (built by scripts/build.sh)`).toBe(true);
    }
  });

  it('generates declarations without errors that type the API', () => {
    const out = mkdtempSync(join(tmpdir(), 'sd-types-'));
    dirs.push(out);
    const emit = spawnSync(process.execPath, [tsc, '-p', join(root, 'web/lib/tsconfig.json'), '--outDir', out], { encoding: 'utf8', timeout: 120000 });
    expect(emit.stdout + emit.stderr).toBe('');
    expect(emit.status).toBe(0);
    expect(readFileSync(join(out, 'web/lib/deformer.d.ts'), 'utf8')).toMatch(/setOptions\(options: SolverOptions\): void/);
    // A consumer type-checked against them: right usage compiles, a misspelt option and an unknown stop code do not.
    const consumer = (body) => {
      writeFileSync(join(out, 'consumer.ts'), `import { Deformer, loadSolver, type StepResult } from './web/lib/index.js';
        export async function use(d: Deformer, r: StepResult) { await loadSolver(); ${body} }\n`);
      return spawnSync(process.execPath, [tsc, '--noEmit', '--strict', '--module', 'nodenext', '--moduleResolution', 'nodenext',
        '--target', 'es2022', '--skipLibCheck', join(out, 'consumer.ts')], { encoding: 'utf8', timeout: 120000 });
    };
    const good = consumer("d.setOptions({ maxIterations: 3, method: 'arap' }); if (r.stop === 'max_iterations') d.reset();");
    expect(good.stdout).toBe('');
    const bad = consumer("d.setOptions({ maxIters: 3 }); if (r.stop === 'diverged') d.reset();");
    expect(bad.status).not.toBe(0);
    expect(bad.stdout).toMatch(/'maxIters' does not exist in type 'SolverOptions'/);
    expect(bad.stdout).toMatch(/'StopCode' and '"diverged"' have no overlap/);
  });
});
