// `deform <scene.json>` as a user runs it: a child process on a generated scene in a temp folder.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { CapsuleGeometry, Scene, SphereGeometry } from 'three';
import { MAX_VOLUME_PARTS, loadSolver, makeExample, readMesh, readModel, writeObj } from 'subspace-deform';
import { exportGlb, meshOf, withHoles } from './support/three_models.js';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });
const sharedData = new URL('../../../shared/data', import.meta.url).pathname;
let dir, solver, vertexCount;

beforeAll(async () => {
  solver = await loadSolver();
  dir = mkdtempSync(join(tmpdir(), 'sd-deform-'));
  const { mesh, cage } = makeExample(solver, 'bar');
  vertexCount = mesh.positions.length / 3;
  writeFileSync(join(dir, 'bar.obj'), writeObj(solver, mesh));
  writeFileSync(join(dir, 'bar_cage.obj'), writeObj(solver, cage));
  const left = [], right = [];
  for (let i = 0; i < vertexCount; ++i) {
    if (mesh.positions[3 * i] < -2.2) left.push(i);
    if (mesh.positions[3 * i] > 2.2) right.push(i);
  }
  const scene = { mesh: 'bar.obj', cage: 'bar_cage.obj',
    handles: [{ vertices: left }, { vertices: right, translate: [0, -0.8, 0.2], rotate: { axis: [0, 0, 1], degrees: -20 } }],
    solver: { method: 'subspace', jacobian: 'fast', volume: true } };
  writeFileSync(join(dir, 'bend.json'), JSON.stringify(scene));
  writeFileSync(join(dir, 'bad.json'), JSON.stringify({ ...scene, handles: [{ vertices: [vertexCount + 5] }] }));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('deform.mjs deform', () => {
  it('prints --help and exits 0', () => {
    const r = run('deform', '--help');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/usage: .*deform <scene\.json>/);
  });

  it('solves a scene and writes the mesh, the cage and the report', () => {
    const out = join(dir, 'out.obj'), cage = join(dir, 'cage.obj'), report = join(dir, 'report.json');
    const r = run('deform', join(dir, 'bend.json'), '--out', out, '--cage-out', cage, '--report', report);
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/converged/);
    const rep = JSON.parse(readFileSync(report, 'utf8'));
    expect(rep).toMatchObject({ method: 'subspace', jacobian: 'fast', converged: true });
    expect(rep.iterationCount).toBe(rep.iterations.length);
    for (const key of ['energy', 'volume', 'step', 'ms']) expect(typeof rep.iterations[0][key]).toBe('number');
    expect(Math.abs(rep.volumeRelError)).toBeLessThanOrEqual(1e-8);
    expect(rep.handleMaxError).toBeLessThan(0.05);
    expect(rep.bindMs).toBeGreaterThan(0);
    const mesh = readMesh(solver, readFileSync(out), 'out.obj');
    expect(mesh.positions.length / 3).toBe(vertexCount);
    expect(readMesh(solver, readFileSync(cage), 'cage.obj').positions.length).toBe(28 * 3);
  });

  // Issue 31, item 4: the summary's times as people read them ("43.4 ms", "1.2 s", never "6.150e+4 ms"); ARAP's
  // header does not claim a volume it does not keep; a solve cut at --max-iterations says so, not "converged".
  it('summarises an ARAP solve stopped at its iteration limit, with readable times', () => {
    const scene = { ...JSON.parse(readFileSync(join(dir, 'bend.json'), 'utf8')), solver: { method: 'arap', volume: true } };
    writeFileSync(join(dir, 'arap.json'), JSON.stringify(scene));
    const r = run('deform', join(dir, 'arap.json'), '--max-iterations', '3');
    expect(r.status).toBe(0);
    const [header, outcome] = r.stdout.split('\n');
    expect(header).toMatch(/arap \(volume not kept\), \d+ vertices/);
    expect(header).not.toMatch(/with volume/);
    expect(outcome).toMatch(/^ {2}NOT converged \(stopped at the iteration limit\) after 3 iterations, [\d.]+ (ms|s) \(bind [\d.]+ (ms|s)\)$/);
    const full = run('deform', join(dir, 'bend.json'));
    expect(full.stdout).toMatch(/subspace\/fast .* with volume,/);
    expect(full.stdout).toMatch(/ {2}converged \(\w[^)]*\) after \d+ iterations, [\d.]+ (ms|s) \(bind [\d.]+ (ms|s)\)\n/);
    expect(r.stdout + full.stdout).not.toMatch(/e[+-]\d+ ms/);
  });

  it('deforms a glTF with UV seams into a .glb of its own layout, saying what was welded', async () => {
    // three's CapsuleGeometry: its seam and poles split, as GLTFExporter writes it.
    const glb = await exportGlb(meshOf(new CapsuleGeometry(0.4, 1.2, 6, 16)));
    writeFileSync(join(dir, 'capsule.glb'), glb);
    const model = await readModel(solver, glb, 'capsule.glb');
    const p = model.mesh.positions;
    const bottom = [], top = [];
    for (let i = 0; i < p.length / 3; ++i) {
      if (p[3 * i + 1] < -0.7) bottom.push(i);
      if (p[3 * i + 1] > 0.7) top.push(i);
    }
    writeFileSync(join(dir, 'capsule.json'), JSON.stringify({ mesh: 'capsule.glb', generateCage: { vertices: 40 },
      handles: [{ vertices: bottom }, { vertices: top, translate: [0.3, 0.2, 0] }] }));
    const out = join(dir, 'capsule-deformed.glb'), report = join(dir, 'capsule.report.json');
    const r = run('deform', join(dir, 'capsule.json'), '--out', out, '--report', report);
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    const rep = JSON.parse(readFileSync(report, 'utf8'));
    expect(rep.layout.fileVertices).toBe(p.length / 3);
    expect(rep.layout.welded).toBeGreaterThan(0);
    expect(Array.isArray(rep.warnings)).toBe(true);  // a 40-vertex generated cage may fold a little under the pull
    const back = await readModel(solver, new Uint8Array(readFileSync(out)), 'capsule-deformed.glb');
    expect(back.mesh.positions.length).toBe(p.length);
    expect(back.mesh.indices).toEqual(model.mesh.indices);
    expect(back.gltf.json.meshes[0].primitives[0].attributes).toHaveProperty('TEXCOORD_0');
    const check = run('check', join(dir, 'capsule.glb'));
    expect(check.status).toBe(0);
    expect(check.stdout).toMatch(/note \(welded\): mesh: \d+ vertices at the same point as another/);
  });

  it('warns with codes about a folded result and a deformed cage that crosses itself', () => {
    const scene = JSON.parse(readFileSync(join(dir, 'bend.json'), 'utf8'));
    // The right end turned 170 degrees and pushed back past the left end: the bar and its cage fold.
    scene.handles[1] = { vertices: scene.handles[1].vertices, translate: [-4.2, 0.5, 0], rotate: { axis: [0, 1, 0], degrees: 170 } };
    writeFileSync(join(dir, 'twist.json'), JSON.stringify(scene));
    const report = join(dir, 'twist.report.json');
    const r = run('deform', join(dir, 'twist.json'), '--report', report);
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/warning \(folded_triangles\): the deformed mesh folds over: \d+ of 10080 triangles/);
    expect(r.stdout).toMatch(/warning \(cage_self_intersecting\): the deformed cage crosses itself: \d+ pairs/);
    const rep = JSON.parse(readFileSync(report, 'utf8'));
    expect(rep.warnings.map((w) => w.code)).toEqual(['folded_triangles', 'cage_self_intersecting']);
  });

  // Two spheres (two components) and a capsule with a hole, as .glb, in one box cage: the report lists the
  // default parts' volume changes, each within 1e-6, and the note on the capped hole.
  it('keeps each component\'s volume and an open mesh\'s capped volume by default, reported per part', async () => {
    const cage = 'v -0.8 -1.3 -0.8\nv 0.8 -1.3 -0.8\nv 0.8 1.3 -0.8\nv -0.8 1.3 -0.8\nv -0.8 -1.3 0.8\nv 0.8 -1.3 0.8\nv 0.8 1.3 0.8\nv -0.8 1.3 0.8\n' +
      'f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n';
    writeFileSync(join(dir, 'box_cage.obj'), cage);
    const two = new Scene();
    const a = meshOf(new SphereGeometry(0.3, 16, 12)), b = meshOf(new SphereGeometry(0.3, 16, 12));
    a.position.set(0, -0.6, 0);
    b.position.set(0, 0.6, 0);
    two.add(a, b);
    const holed = withHoles(new CapsuleGeometry(0.4, 1.2, 6, 16), (c) => Math.abs(c[1]) < 0.25 && c[2] > 0.2);
    for (const [name, object, parts, note] of [['two.glb', two, 2, /note \(components\): mesh: the mesh has 2 separate components; each keeps its own volume/],
      ['holed.glb', meshOf(holed), 1, /note \(open\): mesh: the mesh is open: \d+ boundary edges around 1 hole/]]) {
      const glb = await exportGlb(object);
      writeFileSync(join(dir, name), glb);
      const p = (await readModel(solver, glb, name)).mesh.positions, bottom = [], top = [];
      const seen = new Set();
      for (let i = 0; i < p.length / 3; ++i) {
        const key = `${p[3 * i]},${p[3 * i + 1]},${p[3 * i + 2]}`;
        if (seen.has(key)) continue;  // one copy of each seam point: a point in two groups is refused
        seen.add(key);
        if (p[3 * i + 1] < -0.75) bottom.push(i);
        if (p[3 * i + 1] > 0.75) top.push(i);
      }
      writeFileSync(join(dir, `${name}.json`), JSON.stringify({ mesh: name, cage: 'box_cage.obj',
        handles: [{ vertices: bottom }, { vertices: top, translate: [0.15, 0.15, 0] }] }));
      const report = join(dir, `${name}.report.json`);
      const r = run('deform', join(dir, `${name}.json`), '--report', report);
      expect(r.stderr).toBe('');
      expect(r.status).toBe(0);
      const rep = JSON.parse(readFileSync(report, 'utf8'));
      expect(rep.volumePartCount, name).toBe(parts);
      expect(rep.partVolumeChange).toHaveLength(parts);
      for (const change of rep.partVolumeChange) expect(Math.abs(change), name).toBeLessThanOrEqual(1e-6);
      expect(r.stdout).toMatch(parts === 2 ? /volume of 2 parts/ : /volume/);
      expect(run('check', join(dir, name)).stdout).toMatch(note);
    }
  });

  it('warns with a code about a poor cage, as the app does (a loose box far around the bar)', () => {
    const box = [[-6, -3, -3], [6, -3, -3], [6, 3, -3], [-6, 3, -3], [-6, -3, 3], [6, -3, 3], [6, 3, 3], [-6, 3, 3]];
    const faces = [[1, 3, 2], [1, 4, 3], [5, 6, 7], [5, 7, 8], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 4, 8], [3, 8, 7], [4, 1, 5], [4, 5, 8]];
    writeFileSync(join(dir, 'loose_cage.obj'), [...box.map((v) => `v ${v.join(' ')}`), ...faces.map((f) => `f ${f.join(' ')}`)].join('\n'));
    const scene = JSON.parse(readFileSync(join(dir, 'bend.json'), 'utf8'));
    writeFileSync(join(dir, 'loose.json'), JSON.stringify({ ...scene, cage: 'loose_cage.obj' }));
    const report = join(dir, 'loose.report.json');
    const r = run('deform', join(dir, 'loose.json'), '--report', report);
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/warning \(loose_cage\): poor cage: the cage encloses [\d.e+]+ times the mesh's volume \(a loose cage\)/);
    const rep = JSON.parse(readFileSync(report, 'utf8'));
    expect(rep.warnings.map((w) => w.code)).toContain('loose_cage');
    expect(rep.warnings.every((w) => w.severity === 'warning' && typeof w.message === 'string')).toBe(true);
    // The snug procedural cage of the same bend: no warning at all.
    const snug = join(dir, 'bend.report.json');
    expect(run('deform', join(dir, 'bend.json'), '--report', snug).status).toBe(0);
    expect(JSON.parse(readFileSync(snug, 'utf8')).warnings).toEqual([]);
  });

  // scene-format.md is where a user reads the flags and their limits without running --help.
  it('is described in scene-format.md with every flag --help lists and the --parts limit it checks', () => {
    const doc = readFileSync(new URL('../../docs/scene-format.md', import.meta.url), 'utf8');
    const synopsis = doc.match(/^ {4}node scripts\/deform\.mjs deform scene\.json[\s\S]*?\n\n/m)[0];
    const flags = [...run('deform', '--help').stdout.matchAll(/^ {2}(--[\w-]+)/gm)].map((m) => m[1]);
    expect(flags).toContain('--threads');
    expect(flags.filter((flag) => !synopsis.includes(`[${flag}`))).toEqual([]);
    expect(doc).toContain(`\`--parts\` 1 to ${MAX_VOLUME_PARTS}`);
    const r = run('deform', join(dir, 'bend.json'), '--parts', String(MAX_VOLUME_PARTS + 1));
    expect(r.status).toBe(2);
    expect(r.stderr).toContain(`--parts must be an integer from 1 to ${MAX_VOLUME_PARTS}`);
  });

  it('refuses an --out it cannot write before solving', () => {
    const r = run('deform', join(dir, 'bend.json'), '--out', join(dir, 'x.fbx'));
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(/--out must name a \.obj or \.glb file/);
  });

  // --cage-out used to write OBJ text whatever the name said, so a .glb cage did not read back.
  it('writes --cage-out in the format its name gives, and refuses one it cannot write before solving', async () => {
    const cage = join(dir, 'cage_out.glb');
    const r = run('deform', join(dir, 'bend.json'), '--cage-out', cage, '--quiet');
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    const { mesh } = await readModel(solver, readFileSync(cage), 'cage_out.glb');
    expect(mesh.positions.length).toBe(28 * 3);
    const gltf = join(dir, 'cage_out.gltf');
    const refused = run('deform', join(dir, 'bend.json'), '--cage-out', gltf);
    expect(refused.status).toBe(2);
    expect(refused.stderr).toMatch(/--cage-out must name a \.obj or \.glb file \(got '.*cage_out\.gltf': \.gltf cannot be written\)/);
    expect(existsSync(gltf)).toBe(false);
  });

  it('solves with reduced integration and reports its samples, fit and the energy over every vertex', () => {
    const full = join(dir, 'full.json'), reduced = join(dir, 'reduced.json');
    expect(run('deform', join(dir, 'bend.json'), '--report', full, '--quiet').status).toBe(0);
    const r = run('deform', join(dir, 'bend.json'), '--integration', 'reduced', '--report', reduced);
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/reduced integration: \d+ rotation clusters/); // (the exact sum has no finishing)
    expect(r.stdout).toMatch(/; [1-9]\d* finishing iterations on every vertex;/);
    const a = JSON.parse(readFileSync(full, 'utf8')), b = JSON.parse(readFileSync(reduced, 'utf8'));
    expect(a).toMatchObject({ integration: 'full', weighting: 'area' });
    expect(a.reducedIntegration).toBeUndefined();
    expect(b).toMatchObject({ integration: 'reduced', converged: true });
    expect(b.reducedIntegration.samples).toBeGreaterThan(100);
    expect(b.reducedIntegration.samples).toBeLessThanOrEqual(800); // max(800, 2m) (docs/method.md section 17)
    expect(b.reducedIntegration.reliable).toBe(true);
    expect(b.warnings.map((w) => w.code)).not.toContain('reduced_integration_inaccurate');
    // The rule's iterations first, then the finishing ones on every vertex (docs/method.md section 17.3).
    const finishing = b.iterations.findIndex((it) => it.finishing);
    expect(finishing).toBeGreaterThan(0);
    expect(b.iterations.slice(0, finishing).every((it) => it.samples === b.reducedIntegration.samples)).toBe(true);
    expect(b.iterations.slice(finishing).every((it) => it.finishing && it.samples === 0)).toBe(true);
    expect(Math.abs(b.volumeRelError)).toBeLessThanOrEqual(1e-9);
    // Finished on every vertex, the solve ends at the full one's energy.
    expect(Math.abs(b.reducedIntegration.fullEnergy - a.energy)).toBeLessThan(1e-3 * a.energy);
    expect(run('deform', join(dir, 'bend.json'), '--integration', 'sampled').stderr).toMatch(/--integration must be full or reduced \(got 'sampled'\)/);
  });

  it.skipIf(!existsSync(join(sharedData, 'handbones.obj')))(
    'warns when the reduced rule misses part of the energy: the hand bones in their cage (skipped without ../shared/data)', () => {
      // A scene names models only in its own folder: links to the shared files there.
      for (const f of ['handbones.obj', 'handbones_cage.obj']) if (!existsSync(join(dir, f))) symlinkSync(join(sharedData, f), join(dir, f));
      const scene = { mesh: 'handbones.obj', cage: 'handbones_cage.obj',
        handles: [{ vertices: [0, 1, 2, 3] }, { vertices: [4000, 4001, 4002], translate: [0.01, 0, 0] }],
        solver: { integration: 'reduced', maxIterations: 2 } };
      const scenePath = join(dir, 'handbones.json'), report = join(dir, 'handbones_report.json');
      writeFileSync(scenePath, JSON.stringify(scene));
      const r = run('deform', scenePath, '--report', report);
      expect(r.status).toBe(0);
      expect(r.stdout).toMatch(/warning \(reduced_integration_inaccurate\)/);
      const b = JSON.parse(readFileSync(report, 'utf8'));
      expect(b.reducedIntegration.reliable).toBe(false);
      expect(b.reducedIntegration).toMatchObject({ rule: 'clusters', samples: 800, candidates: 5497 });
      expect(b.reducedIntegration.testError).toBeGreaterThan(0.25);
    });

  it('solves with the spectral basis (no cage needed) and keeps the volume per part', () => {
    const scene = JSON.parse(readFileSync(join(dir, 'bend.json'), 'utf8'));
    delete scene.cage;
    scene.volumeParts = { auto: 3 };
    writeFileSync(join(dir, 'spectral.json'), JSON.stringify(scene));
    const report = join(dir, 'spectral_report.json');
    const r = run('deform', join(dir, 'spectral.json'), '--basis', 'spectral', '--modes', '20', '--report', report);
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/spectral basis, 24 columns\) with the volume of 3 parts/);
    const rep = JSON.parse(readFileSync(report, 'utf8'));
    expect(rep).toMatchObject({ method: 'subspace', basis: 'spectral', basisSize: 24, volumePartCount: 3, converged: true });
    expect(rep.partVolumeChange).toHaveLength(3);
    for (const change of rep.partVolumeChange) expect(Math.abs(change)).toBeLessThanOrEqual(1e-8);
    const auto = run('deform', join(dir, 'bend.json'), '--parts', '2', '--quiet', '--report', report);
    expect(auto.status).toBe(0);
    expect(JSON.parse(readFileSync(report, 'utf8'))).toMatchObject({ basis: 'cage', volumePartCount: 2 });
  });

  // The spectral basis ignores a cage: generating one cost seconds, and one that could not be made (4 vertices
  // around the bar) failed the run with cage_failed.
  it('does not generate the scene\'s cage under the spectral basis, and says so', () => {
    const scene = JSON.parse(readFileSync(join(dir, 'bend.json'), 'utf8'));
    delete scene.cage;
    Object.assign(scene, { generateCage: { vertices: 4 }, subspace: { basis: 'spectral', modes: 10 } });
    writeFileSync(join(dir, 'spectral_generated.json'), JSON.stringify(scene));
    const report = join(dir, 'spectral_generated_report.json');
    const r = run('deform', join(dir, 'spectral_generated.json'), '--report', report);
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/warning \(generate_cage_ignored\)/);
    const rep = JSON.parse(readFileSync(report, 'utf8'));
    expect(rep).toMatchObject({ basis: 'spectral', converged: true });
    expect(rep.warnings.map((w) => w.code)).toContain('generate_cage_ignored');
    const cageOut = run('deform', join(dir, 'spectral_generated.json'), '--cage-out', join(dir, 'none.obj'));
    expect(cageOut.status).toBe(2);
    expect(cageOut.stderr).toMatch(/--cage-out: .*spectral basis/);
    // That refusal is documented (it was not), and a cage file under the spectral basis is written at rest.
    expect(run('deform', '--help').stdout).toMatch(/"generateCage" under the spectral basis makes none/);
    expect(readFileSync(new URL('../../docs/scene-format.md', import.meta.url), 'utf8')).toMatch(/`--cage-out` is bad usage, exit status 2, when there is no cage/);
    const restCage = join(dir, 'spectral_rest_cage.obj');
    const written = run('deform', join(dir, 'bend.json'), '--basis', 'spectral', '--modes', '10', '--cage-out', restCage, '--quiet');
    expect(written.status).toBe(0);
    expect(readMesh(solver, readFileSync(restCage), 'cage.obj').positions).toEqual(readMesh(solver, readFileSync(join(dir, 'bar_cage.obj')), 'cage.obj').positions);
  });

  it('refuses --basis and --modes misuse as usage errors', () => {
    expect(run('deform', join(dir, 'bend.json'), '--basis', 'spectral').stderr).toMatch(/--basis spectral needs --modes K/);
    expect(run('deform', join(dir, 'bend.json'), '--basis', 'wavelets').status).toBe(2);
    expect(run('deform', join(dir, 'bend.json'), '--modes', 'many').stderr).toMatch(/--modes must be an integer/);
    expect(run('deform', join(dir, 'bend.json'), '--basis', 'cage', '--modes', '5').stderr).toMatch(/--modes is for --basis spectral/);
  });

  it('solves a scene that names a built-in example, or a mesh with a generated cage', () => {
    const handles = JSON.parse(readFileSync(join(dir, 'bend.json'), 'utf8')).handles;
    writeFileSync(join(dir, 'example.json'), JSON.stringify({ example: 'bar', handles }));
    writeFileSync(join(dir, 'generated.json'), JSON.stringify({ mesh: 'bar.obj', generateCage: { vertices: 40 }, handles }));
    for (const [scene, cageSize] of [['example.json', [28, 28]], ['generated.json', [32, 48]]]) {
      const report = join(dir, `${scene}.report.json`), cage = join(dir, `${scene}.cage.obj`);
      const r = run('deform', join(dir, scene), '--report', report, '--cage-out', cage, '--quiet');
      expect(r.stderr, scene).toBe('');
      expect(r.status, scene).toBe(0);
      const rep = JSON.parse(readFileSync(report, 'utf8'));
      expect(rep.converged, scene).toBe(true);
      expect(Math.abs(rep.volumeRelError), scene).toBeLessThanOrEqual(1e-8);
      const cageVertices = readMesh(solver, readFileSync(cage), 'cage.obj').positions.length / 3;
      expect(cageVertices, scene).toBeGreaterThanOrEqual(cageSize[0]);
      expect(cageVertices, scene).toBeLessThanOrEqual(cageSize[1]);
    }
  });

  it('command-line flags override the scene', () => {
    const report = join(dir, 'arap.json');
    const r = run('deform', join(dir, 'bend.json'), '--method', 'arap', '--max-iterations', '5', '--report', report, '--quiet');
    expect(r.status).toBe(0);
    expect(r.stdout).toBe('');
    const rep = JSON.parse(readFileSync(report, 'utf8'));
    expect(rep.method).toBe('arap');
    expect(rep.iterationCount).toBeLessThanOrEqual(5);
  });

  it('--threads sets the solver threads; 1 and 2 threads give the same solve to the last bit', () => {
    const reports = [1, 2].map((threads) => {
      const report = join(dir, `threads${threads}.json`);
      const r = run('deform', join(dir, 'bend.json'), '--threads', String(threads), '--report', report, '--quiet');
      expect(r.status).toBe(0);
      return JSON.parse(readFileSync(report, 'utf8'));
    });
    expect(reports.map((r) => r.threads)).toEqual(process.env.SD_WASM_BUILD === 'single' ? [1, 1] : [1, 2]);
    expect(reports[1].iterations.map((it) => it.energy)).toEqual(reports[0].iterations.map((it) => it.energy));
    expect(reports[1].energy).toBe(reports[0].energy);
  });

  it.each([
    ['a bad --threads', ['bend.json', '--threads', 'many'], 2, /--threads must be a whole number from 0/],
    ['an out-of-range handle vertex', ['bad.json'], 1, /handles\[0\] uses vertex \d+, but the mesh has \d+ vertices/],
    ['a missing scene', ['nope.json'], 1, /cannot read .*nope\.json: no such file/],
    ['a bad --method', ['bend.json', '--method', 'magic'], 2, /--method must be subspace, full or arap/],
  ])('%s: clear message and exit status', (_, args, status, pattern) => {
    const r = run('deform', ...args.map((a, i) => (i === 0 ? join(dir, a) : a)));
    expect(r.status).toBe(status);
    expect(r.stdout + r.stderr).toMatch(pattern);
    expect(r.stdout + r.stderr).not.toMatch(/Aborted|RuntimeError|at .*\.js:\d+/);
  });
});
