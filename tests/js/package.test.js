// The library as a package: Node's self-reference resolves 'subspace-deform' to the Node entry wherever a
// script runs in the project, the browser entry offers the same library plus its loader and the worker
// client, the exports map names files that exist after a build, and the TypeScript declarations generate
// from the JSDoc without errors and type the API (a wrong option name does not compile). And as published:
// `npm pack` (its prepack builds what is missing) gives a tarball with the library, the wasm it loads, the
// schema and the declarations and nothing else; installed into a fresh project it solves from Node, and a
// strict TypeScript consumer type-checks against it without skipLibCheck. And the embed element from it: a page
// that does `import 'subspace-deform/element'`, bundled by Vite in a fresh project that installs three.js and
// lil-gui itself (the package's optional peers), shows <subspace-deformer> in Chromium and a mouse drag on its
// gizmo bends the bar, with the wasm found beside the bundled module; with the threaded build copied to the
// site's threads/ folder, a cross-origin isolated page runs it.
import { describe, expect, it, afterAll, beforeAll } from 'vitest';
import { spawnSync } from 'node:child_process';
import { cpSync, existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import * as browserEntry from '../../web/lib/index.js';
import * as nodeEntry from '../../web/lib/node.js';
import { dragUp, project } from '../e2e/app_probe.mjs';

const root = resolve(new URL('../..', import.meta.url).pathname);

// The lowest version a range '^a.b.c' or '>=a.b.c' takes, as a number that orders versions (parts below 1000).
function lowest(range) {
  const [major, minor, patch] = range.replace(/^(\^|>=)/, '').split('.').map(Number);
  return (major * 1000 + minor) * 1000 + patch;
}
const pkg = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8'));
const tsc = join(root, 'node_modules/typescript/bin/tsc');
const dirs = [];
afterAll(() => dirs.forEach((d) => rmSync(d, { recursive: true, force: true })));

/** `npm pack` (prepack first) into a fresh folder, once for every test of this file. */
let packing = null;
function pack() {
  if (!packing) {
    const dir = mkdtempSync(join(tmpdir(), 'sd-pack-'));
    dirs.push(dir);
    const r = spawnSync('npm', ['pack', '--json', '--pack-destination', dir], { cwd: root, encoding: 'utf8', timeout: 300000 });
    expect(r.status, r.stderr).toBe(0);
    const packed = JSON.parse(r.stdout)[0];
    packing = { dir, packed, tarball: join(dir, packed.filename) };
  }
  return packing;
}

/**
 * A fresh project in `dir` with `dependencies` in its package.json that installs the tarball, offline: what it
 * needs is copied from this repository's node_modules first, where npm finds it satisfied.
 */
function installInto(dir, tarball, copied, dependencies = {}) {
  mkdirSync(join(dir, 'node_modules'), { recursive: true });
  writeFileSync(join(dir, 'package.json'), JSON.stringify({ name: 'consumer', private: true, type: 'module', dependencies }));
  for (const dep of copied) cpSync(join(root, 'node_modules', dep), join(dir, 'node_modules', dep), { recursive: true });
  const install = spawnSync('npm', ['install', '--offline', '--no-audit', '--no-fund', tarball], { cwd: dir, encoding: 'utf8', timeout: 300000 });
  expect(install.status, install.stderr).toBe(0);
}
const PACKAGE_DEPENDENCIES = ['@gltf-transform/core', '@gltf-transform/extensions', 'property-graph', 'ktx-parse'];

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
    expect(nodeOnly.sort()).toEqual(['checkWritable', 'loadNodeSolver', 'maxThreads', 'parseThreads', 'readFileBytes', 'wasmDir', 'writeFileBytes']);
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

  it('declares every member of <subspace-deformer> in the element\'s hand-written types', () => {
    expect(pkg.exports['./element']).toEqual({ types: './web/app/embed/index.d.ts', default: './web/app/embed/index.js' });
    const source = readFileSync(join(root, 'web/app/embed/subspace_deformer_element.js'), 'utf8');
    const body = source.slice(source.indexOf('class SubspaceDeformerElement'), source.indexOf('export function defineElement'));
    const members = [...body.matchAll(/^ {2}(?:get |async )?([a-zA-Z]\w*)\(/gm)].map((m) => m[1]);
    expect(members.length).toBeGreaterThan(25);
    const types = readFileSync(join(root, pkg.exports['./element'].types), 'utf8');
    // The class's own members and those it shares with the app (interface DeformerControls, merged into the class).
    const declared = types.slice(types.indexOf('export interface DeformerControls'), types.indexOf('export interface DeformerApp')) +
      types.slice(types.indexOf('export class SubspaceDeformerElement'), types.indexOf('export function defineElement'));
    expect(types).toMatch(/export interface SubspaceDeformerElement extends DeformerControls \{\}/);
    expect(members.filter((name) => !new RegExp(`^ {2}(readonly )?${name}[(:]`, 'm').test(declared))).toEqual([]);
    for (const name of ['mount', 'SubspaceDeformerElement', 'defineElement']) expect(types).toMatch(new RegExp(`export (function|class) ${name}\\b`));
  });

  it('type-checks every file of the library under strict (each starts with // @ts-check)', () => {
    const lib = join(root, 'web/lib');
    const files = readdirSync(lib, { recursive: true }).filter((f) => f.endsWith('.js')).map((f) => f.split('\\').join('/'));
    expect(files.length).toBeGreaterThan(30);
    const unchecked = files.filter((f) => !readFileSync(join(lib, f), 'utf8').startsWith('// @ts-check\n'));
    expect(unchecked).toEqual([]);
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
        '--target', 'es2022', join(out, 'consumer.ts')], { encoding: 'utf8', timeout: 120000 });
    };
    const good = consumer("d.setOptions({ maxIterations: 3, method: 'arap' }); if (r.stop === 'max_iterations') d.reset();");
    expect(good.stdout).toBe('');
    const bad = consumer("d.setOptions({ maxIters: 3 }); if (r.stop === 'diverged') d.reset();");
    expect(bad.status).not.toBe(0);
    expect(bad.stdout).toMatch(/'maxIters' does not exist in type 'SolverOptions'/);
    expect(bad.stdout).toMatch(/'StopCode' and '"diverged"' have no overlap/);
  });
});

// What a user of the published package gets. The install runs offline: the package's only dependencies
// (glTF-Transform and theirs) are copied from this repository's node_modules, where npm finds them satisfied.
describe('the packed subspace-deform tarball', () => {
  let project;
  let packed;
  beforeAll(() => {
    const { dir, tarball } = pack();
    packed = pack().packed;
    project = join(dir, 'project');
    installInto(project, tarball, PACKAGE_DEPENDENCIES);
  }, 600000);

  it('is publishable and installs none of the app\'s packages', () => {
    expect(pkg.private).toBeUndefined();
    for (const name of ['three', 'lil-gui', 'bunny', 'coi-serviceworker']) {
      expect(pkg.dependencies[name], name).toBeUndefined();
      expect(pkg.devDependencies[name], `${name}: npm ci installs it for the app and the tests`).toBeDefined();
      expect(existsSync(join(project, 'node_modules', name)), name).toBe(false);
    }
    // The embed element's packages: a page that uses it installs them itself (docs/embed.md, from npm). The peer
    // ranges take the versions the tests run (the dev ranges' lowest) and later ones: a caret range on a 0.x
    // three.js (^0.187.0) refused every page on another minor version, though the element works on 0.170 too.
    for (const name of ['three', 'lil-gui', 'bunny']) {
      expect(lowest(pkg.peerDependencies[name]) <= lowest(pkg.devDependencies[name]), name).toBe(true);
      expect(pkg.peerDependencies[name].startsWith('>=') || pkg.peerDependencies[name].startsWith('^1.'), name).toBe(true);
      expect(pkg.peerDependenciesMeta[name].optional, name).toBe(true);
    }
  });

  it('holds the library, the embed element, the wasm it loads, the schema, the types, README and licence, and nothing else', () => {
    const files = packed.files.map((f) => f.path);
    for (const file of ['package.json', 'README.md', 'LICENSE', 'web/lib/index.js', 'web/lib/node.js', 'web/lib/worker/solver_worker.js',
      'web/lib/data/spot.obj', 'build/wasm/solver_schema.js', 'build/wasm/subspace_deform.js', 'build/wasm/subspace_deform.wasm',
      'build/wasm/threads/subspace_deform.js', 'build/wasm/threads/subspace_deform.wasm', 'build/wasm/threads/subspace_deform.worker.js',
      'build/wasm/node-threads/package.json', 'build/wasm/node-threads/subspace_deform.js',
      'build/wasm/node-threads/subspace_deform.worker.js',
      'build/types/web/lib/index.d.ts', 'build/types/web/lib/node.d.ts', 'build/types/build/wasm/solver_schema.d.ts',
      pkg.exports['./element'].default.slice(2), pkg.exports['./element'].types.slice(2), 'web/app/embed/subspace_deformer_element.js',
      'web/app/lessons/volume.json']) {
      expect(files, file).toContain(file);
    }
    const unwanted = files.filter((f) => /^(tests|cpp|docs|scripts|node_modules|dist)\/|CMake|\.(a|o|cpp|h|map)$|_bench\.|tsconfig/.test(f));
    expect(unwanted).toEqual([]);
    expect(packed.files.length).toBeLessThan(200);
    expect(packed.size).toBeLessThan(2.2e6);  // 1.85 MB: the threaded .wasm once (2.57 MB with it twice)
  });

  it('ships the threaded .wasm once: Node\'s threaded glue loads the browsers\' bytes (the same module)', () => {
    expect(packed.files.map((f) => f.path)).not.toContain('build/wasm/node-threads/subspace_deform.wasm');
    // web/lib/node.js reads threads/' .wasm when node-threads/ has none: valid only while the two builds are one binary.
    const bytes = (dir) => readFileSync(join(root, 'build/wasm', dir, 'subspace_deform.wasm'));
    expect(Buffer.compare(bytes('threads'), bytes('node-threads'))).toBe(0);
  });

  it('solves from Node', () => {
    const script = `import { loadSolver, Deformer, makeExample, loadExample } from 'subspace-deform';
      const report = { entry: import.meta.resolve('subspace-deform') };
      for (const build of ['threads', 'single']) {
        const solver = await loadSolver({ build, threads: 2 });
        const { mesh, cage } = makeExample(solver, 'bar');
        const x = (i) => mesh.positions[3 * i];
        const n = mesh.positions.length / 3;
        const ids = [...Array(n).keys()];
        const lo = Math.min(...ids.map(x)), hi = Math.max(...ids.map(x));
        const left = ids.filter((i) => x(i) < lo + 1e-9), right = ids.filter((i) => x(i) > hi - 1e-9);
        const d = Deformer.create(solver, mesh, cage);
        d.setHandles([left, right]);
        const targets = new Float64Array([...left, ...right].flatMap((i, k) =>
          [mesh.positions[3 * i], mesh.positions[3 * i + 1] + (k < left.length ? 0 : 0.5), mesh.positions[3 * i + 2]]));
        d.setTargets(targets);
        const r = d.solve();
        report[build] = { build: solver.build, converged: r.converged, lift: d.positions()[3 * right[0] + 1] - mesh.positions[3 * right[0] + 1] };
        d.dispose();
      }
      const solver = await loadSolver();
      report.spot = (await loadExample(solver, 'spot')).mesh.positions.length / 3;
      report.bunny = await loadExample(solver, 'bunny').then(() => 'loaded', (e) => e.name + ': ' + e.message);
      console.log(JSON.stringify(report));`;
    const r = spawnSync(process.execPath, ['--input-type=module', '-e', script], { cwd: project, encoding: 'utf8', timeout: 120000 });
    expect(r.stderr).toBe('');
    const out = JSON.parse(r.stdout);
    expect(out.entry).toBe(new URL(`file://${join(project, 'node_modules/subspace-deform/web/lib/node.js')}`).href);
    for (const build of ['threads', 'single']) {
      expect(out[build], build).toMatchObject({ build, converged: true });
      expect(out[build].lift, build).toBeCloseTo(0.5, 3);
    }
    expect(out.spot).toBe(2930);
    expect(out.bunny).toBe('InputError: the bunny example needs the optional package "bunny": npm install bunny');
  });

  it('type-checks a strict TypeScript consumer without skipLibCheck', () => {
    const check = (body, lib = []) => {
      writeFileSync(join(project, 'consumer.ts'), `import { Deformer, loadSolver, loadExample, makeExample, readMesh, parseScene,
          type SolverModule, type StepResult } from 'subspace-deform';
        export async function use(r: StepResult): Promise<number> {
          const solver: SolverModule = await loadSolver({ threads: 2 });
          const { mesh, cage } = makeExample(solver, 'bar');
          const d = Deformer.create(solver, mesh, cage);
          ${body}
          const scene = parseScene('{"example": "bar"}');
          return readMesh(solver, 'v 0 0 0', 'a.obj').positions.length + (scene.example === 'bar' ? 0 : 1);
        }\n`);
      return spawnSync(process.execPath, [tsc, '--noEmit', '--strict', '--module', 'nodenext', '--moduleResolution', 'nodenext',
        '--target', 'es2022', ...lib, join(project, 'consumer.ts')], { cwd: project, encoding: 'utf8', timeout: 120000 });
    };
    const body = `d.setOptions({ maxIterations: 3, method: 'arap' });
      if (r.stop === 'max_iterations') d.reset();
      const example = await loadExample(solver, 'spot', { onProgress: (f: number) => f < 1 });
      const ratio: number | undefined = example.cageInfo?.volumeRatio;
      if (solver.build === 'single' && ratio) d.step(1);`;
    for (const lib of [[], ['--lib', 'es2022']]) {
      const good = check(body, lib);
      expect(good.stdout + good.stderr, lib.join(' ')).toBe('');
      expect(good.status).toBe(0);
    }
    const bad = check("await loadExample(solver, 'spot', { onProgres: () => true }); if (solver.build === 'wasm') d.reset();");
    expect(bad.status).not.toBe(0);
    expect(bad.stdout).toMatch(/'onProgres' does not exist/);
    expect(bad.stdout).toMatch(/'"threads" \| "single"' and '"wasm"' have no overlap/);
  });

  it('type-checks a strict TypeScript page that uses the element, without skipLibCheck', () => {
    const check = (body) => {
      writeFileSync(join(project, 'page.ts'), `import { mount, defineElement, type ViewStats } from 'subspace-deform/element';
        export async function use(): Promise<number> {
          defineElement('my-deformer');
          ${body}
        }\n`);
      return spawnSync(process.execPath, [tsc, '--noEmit', '--strict', '--module', 'nodenext', '--moduleResolution', 'nodenext',
        '--target', 'es2022', join(project, 'page.ts')], { cwd: project, encoding: 'utf8', timeout: 120000 });
    };
    const good = check(`const el = document.querySelector('subspace-deformer');
      if (!el) return 0;
      await el.ready;
      el.setOptions({ maxIterations: 30, method: 'arap', wireframe: true });
      const stats: ViewStats = await el.drag(1, [0, 0.5, 0], { axis: [0, 0, 1], angle: 0.1 });
      const app = mount(document.body, { example: 'bar', compare: ['arap', 'subspace'], noCage: 'spectral', settings: { jacobian: 'exact' } });
      app.addEventListener('load', (e) => console.log(e.type));
      return stats.volumeRelError + (el.positions()?.length ?? 0) + (app.stats.converged ? 1 : 0);`);
    expect(good.stdout + good.stderr).toBe('');
    expect(good.status).toBe(0);
    const bad = check(`const el = document.querySelector('subspace-deformer');
      mount(document.body, { noCage: 'never' });
      el?.setOptions({ maxIters: 3 });
      return el?.drag('1', [0, 1]) ? 1 : 0;`);
    expect(bad.status).not.toBe(0);
    expect(bad.stdout).toMatch(/'"never"' is not assignable to type 'NoCageChoice/);
    expect(bad.stdout).toMatch(/'maxIters'/);
    expect(bad.stdout).toMatch(/'string' is not assignable to parameter of type 'number'/);
  });
});

// A course page built with a bundler: the element from the tarball, three.js and lil-gui installed by the page (the
// package's optional peers), bundled by Vite with the settings docs/embed.md names (its default worker format), served by a plain static
// server from a sub-folder, and dragged with the mouse in Chromium; and served with the isolation headers, where
// it runs the threaded build that the page copied from the package to public/threads/. Runs once per `npm test`
// (in the threaded Node run: the page is the same for both) and where Chromium is installed.
const chromium = process.env.CHROMIUM ?? '/usr/bin/chromium';
const pageSkip = process.env.SD_WASM_BUILD === 'single' ? 'it runs in the threaded run (the page does not depend on the Node build)' : null;
const browserSkip = pageSkip ?? (existsSync(chromium) ? null : `Chromium is not installed at ${chromium} (set CHROMIUM to its path)`);
if (pageSkip) console.warn(`skipped: the packed element in a Vite-bundled page: ${pageSkip}`);
else if (browserSkip) console.warn(`skipped: the drag on the packed element in Chromium: ${browserSkip}`);

describe.skipIf(pageSkip)('the packed element in a page bundled by Vite', () => {
  const site = {};
  beforeAll(() => {
    const { dir, tarball } = pack();
    const page = join(dir, 'page');
    installInto(page, tarball, [...PACKAGE_DEPENDENCIES, 'three', 'lil-gui'],
      { three: pkg.devDependencies.three, 'lil-gui': pkg.devDependencies['lil-gui'] });
    // docs/embed.md, "From npm, in a bundled page": the page's own files.
    writeFileSync(join(page, 'vite.config.js'),
      "export default { base: './', optimizeDeps: { exclude: ['subspace-deform'] } };\n");
    writeFileSync(join(page, 'main.js'), "import 'subspace-deform/element';\n");
    cpSync(join(page, 'node_modules/subspace-deform/build/wasm/threads'), join(page, 'public/threads'), { recursive: true });
    writeFileSync(join(page, 'index.html'), `<!doctype html>
      <html><head><meta charset="utf-8"><link rel="icon" href="data:,"><script type="module" src="./main.js"></script></head>
      <body><h1>A figure</h1><subspace-deformer example="bar" style="height: 400px"></subspace-deformer></body></html>\n`);
    const build = spawnSync(process.execPath, [join(root, 'node_modules/vite/bin/vite.js'), 'build', '--logLevel', 'error'],
      { cwd: page, encoding: 'utf8', timeout: 120000, env: { ...process.env, NO_COLOR: '1' } });
    expect(build.status, build.stdout + build.stderr).toBe(0);
    site.dist = join(page, 'dist');
  }, 600000);

  it('bundles the element with the wasm and the solver worker beside it', () => {
    const assets = readdirSync(join(site.dist, 'assets'));
    expect(assets.filter((f) => /^subspace_deform-.*\.wasm$/.test(f))).toHaveLength(1);
    expect(assets.filter((f) => /^solver_worker-.*\.js$/.test(f))).toHaveLength(1);
    // Vite's default worker format: a classic script, which has no import.meta.url and finds the wasm relative
    // to self.location, which the worker's bootstrap blob sets to the script's URL (worker_start.js), not the page's.
    const worker = readFileSync(join(site.dist, 'assets', assets.find((f) => f.startsWith('solver_worker-'))), 'utf8');
    expect(worker).not.toMatch(/import\.meta/);
    expect(worker).toMatch(/new URL\(`subspace_deform-[\w-]+\.wasm`,self\.location\.href\)/);
    // The threaded build as the package holds it, at the site's root (where the bundled loader looks: ../threads/).
    expect(readdirSync(join(site.dist, 'threads')).sort()).toEqual(['subspace_deform.js', 'subspace_deform.wasm', 'subspace_deform.worker.js']);
  });

  /** Opens the built page on a fresh static server (with COOP/COEP when isolated) and runs `check(page)`. */
  async function onPage(isolated, check) {
    const { serveStatic } = await import('../e2e/static_server.mjs');
    const { launchBrowser, watchErrors } = await import('../e2e/browser.mjs');
    const server = await serveStatic(site.dist, { prefix: '/course/week1/', isolated });
    const browser = await launchBrowser();
    try {
      const page = await browser.context.newPage();
      const errors = watchErrors(page);
      await page.goto(server.url + 'index.html');
      await page.waitForFunction(() => document.querySelector('subspace-deformer')?.app, null, { timeout: 30000 });
      await page.evaluate(() => document.querySelector('subspace-deformer').ready);
      await check(page);
      expect(errors).toEqual([]);
    } finally {
      await browser.close();
      await server.close();
    }
  }
  const restPositions = (page) => page.evaluate(() => [...document.querySelector('subspace-deformer').positions()]);
  /** The largest rise of a vertex from `rest` after the solve has settled, and the settled stats. */
  const settled = async (page, rest) => {
    const after = await page.evaluate(async () => {
      const el = document.querySelector('subspace-deformer');
      const stats = await el.solve();
      return { positions: [...el.positions()], state: stats.state, stopReason: stats.stopReason, volumeRelError: stats.volumeRelError,
        solver: stats.solver };
    });
    let lift = 0;
    for (let i = 1; i < rest.length; i += 3) lift = Math.max(lift, after.positions[i] - rest[i]);
    return { ...after, lift };
  };

  it.skipIf(browserSkip)('shows <subspace-deformer> and a mouse drag on its gizmo bends the bar', async () => {
    await onPage(false, async (page) => {
      const rest = await restPositions(page);
      // The gizmo's centre (free translation), on screen, dragged 48 px up.
      await dragUp(page, await project(page, 'app.views[0].gizmo.pivot.position.clone()', 0, "document.querySelector('subspace-deformer').app"));
      // The element took the drag: the moving group follows the mouse up, and the mesh with it.
      const translate = await page.evaluate(() => {
        const { handles } = document.querySelector('subspace-deformer').app;
        return handles.groups[handles.active].translate;
      });
      expect(translate[1], `the group moved by ${translate}`).toBeGreaterThan(0.1);
      const dragged = await settled(page, rest);
      expect(dragged.positions.some((x, i) => Math.abs(x - rest[i]) > 0.1), 'the mesh moved').toBe(true);
      // The solve warm-started from the drag's intermediate shapes depends on their timing (it has ended
      // 'stopped' in 2 of about 25 runs on a loaded machine): what this test checks is the package, so the
      // settled shape is the one solved from rest for the same targets, which does not.
      if (dragged.state !== 'converged') console.warn(`the solve after the mouse drag ended ${dragged.state}: ${dragged.stopReason}`);
      await page.evaluate(() => document.querySelector('subspace-deformer').resolveFromRest());
      const after = await settled(page, rest);
      expect(after.state, after.stopReason).toBe('converged');
      expect(after.solver.build).toBe('single');
      expect(after.solver.buildNote).toMatch(/not cross-origin isolated/);
      expect(after.lift, 'the drag lifted the moving end').toBeCloseTo(translate[1], 2);
      expect(Math.abs(after.volumeRelError)).toBeLessThan(1e-6);
    });
  }, 120000);

  it.skipIf(browserSkip)('runs the threaded build from the site\'s threads/ folder on a cross-origin isolated page', async () => {
    await onPage(true, async (page) => {
      const rest = await restPositions(page);
      await page.evaluate(() => document.querySelector('subspace-deformer').drag(1, [0, 0.5, 0]));
      const after = await settled(page, rest);
      expect(after.solver).toMatchObject({ build: 'threads' });
      expect(after.solver.buildNote).toBeUndefined();
      expect(after.state, after.stopReason).toBe('converged');
      expect(after.lift).toBeCloseTo(0.5, 2);
    });
  }, 120000);
});
