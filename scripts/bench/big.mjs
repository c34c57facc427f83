#!/usr/bin/env node
// The app on large meshes (docs/benchmarks.md, "Large meshes"): geodesic spheres of about 250k and 1M vertices in
// the 42-vertex icosphere cage of the built-in sphere, loaded from OBJ files as a user would (parse, check, bind,
// the reduced integration's fit), then dragged: the bottom cap fixed, the top cap swung sideways.
//   time to the first deformable frame: from the load call until the first solver result of a drag is drawn;
//   updates per second while dragging, ms per iteration, the integration used (the app samples while dragging
//   models of 20k+ vertices) and the time to settle after release (the drag ends as the gizmo's does on release):
//   until converged, and until the shape drawn stops moving to the eye (stillToTheEye);
//   peak memory: the largest resident size of Chromium's processes (all of them, sampled every 200 ms).
// With --models, the real models of ../shared/data in their own cages instead (handbones, boy, ...: the drag of
// scripts/bench/models.mjs, its moving end swung sideways by up to 8% of the diagonal); --sizes '' drops the spheres.
// Usage: node scripts/bench/big.mjs [--sizes 250000,1000000] [--models handbones,boy] [--seconds 6] [--no-build]
import { execFileSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadSolver, makeExample, readMesh, writeObj } from 'subspace-deform';
import { availableModels, dragHandles } from './models.mjs';
import { serveStatic } from '../../tests/e2e/static_server.mjs';
import { launchBrowser } from '../../tests/e2e/browser.mjs';
import { optionReader, siteToMeasure } from '../lib/browser_bench.mjs';
import { frequencyFor, geodesicSphereObj } from './geodesic_sphere.mjs';

const args = process.argv.slice(2);
const opt = optionReader(args);
const sizes = opt('sizes', '250000,1000000').split(',').filter(Boolean).map(Number);
const realModels = opt('models', '').split(',').filter(Boolean);
const seconds = Number(opt('seconds', 6));
const dist = siteToMeasure(args);

// The models, written into the served folder (a build output, not part of the project).
const data = join(dist, 'bench-data');
mkdirSync(data, { recursive: true });
const solver = await loadSolver();
writeFileSync(join(data, 'cage.obj'), writeObj(solver, makeExample(solver, 'sphere').cage));
const models = sizes.map((size) => {
  const sphere = geodesicSphereObj(frequencyFor(size));
  const file = `sphere-${sphere.vertices}.obj`;
  writeFileSync(join(data, file), sphere.obj);
  // Handles from the vertex positions: the caps below y = -0.85 (fixed) and above y = 0.85 (moving).
  const fixed = [], moving = [];
  sphere.obj.split('\n').filter((l) => l.startsWith('v ')).forEach((line, i) => {
    const y = Number(line.split(' ')[2]);
    if (y < -0.85) fixed.push(i);
    if (y > 0.85) moving.push(i);
  });
  return { file, cage: 'cage.obj', vertices: sphere.vertices, triangles: sphere.triangles, fixed, moving, swing: [0.4, 0, 0] };
});
// The real models: copied beside the spheres (a build output, never committed), with the drag's handles.
const sharedData = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..', '..', 'shared', 'data');
for (const name of availableModels(sharedData, realModels)) {
  for (const file of [`${name}.obj`, `${name}_cage.obj`]) copyFileSync(join(sharedData, file), join(data, file));
  const mesh = readMesh(solver, readFileSync(join(sharedData, `${name}.obj`)), `${name}.obj`);
  const [fixed, moved] = dragHandles(mesh);
  models.push({ file: `${name}.obj`, cage: `${name}_cage.obj`, vertices: mesh.positions.length / 3,
    triangles: mesh.indices.length / 3, fixed: fixed.vertices, moving: moved.vertices, swing: moved.translate });
}
if (realModels.length && !existsSync(sharedData)) console.log(`bench/big: ${sharedData} is absent: no real models`);

// Resident memory of every Chromium process, in MB.
function chromiumRssMb() {
  try {
    const out = execFileSync('ps', ['-C', 'chromium', '-o', 'rss='], { encoding: 'utf8' });
    return out.split('\n').filter(Boolean).reduce((sum, kb) => sum + Number(kb), 0) / 1024;
  } catch {
    return NaN;
  }
}

/**
 * When the shape stopped moving to the eye: the time of the first result drawn from which every later one lies
 * within EYE_FRACTION of the rest mesh's bounding-box diagonal from the settled shape (a tenth of a pixel on a model
 * 1000 pixels across). `drawn`: [{ at, positions }] in order, from the release, positions of the vertices
 * eyeSample(n) picks; `settledAt` when no drawn result qualifies. Runs in the page (passed as source).
 */
function stillToTheEye(drawn, final, rest, settledAt) {
  const EYE_FRACTION = 1e-4;
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < rest.length; ++i) {
    lo[i % 3] = Math.min(lo[i % 3], rest[i]);
    hi[i % 3] = Math.max(hi[i % 3], rest[i]);
  }
  const limit = EYE_FRACTION * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const kept = eyeSample(final); // the same vertices as each drawn result's
  const far = (p) => {
    for (let i = 0; i < p.length; i += 3) {
      if (Math.hypot(p[i] - kept[i], p[i + 1] - kept[i + 1], p[i + 2] - kept[i + 2]) > limit) return true;
    }
    return false;
  };
  let last = -1; // the last drawn result still visibly away from the settled shape
  drawn.forEach((d, k) => { if (far(d.positions)) last = k; });
  return last + 1 < drawn.length ? drawn[last + 1].at : settledAt;
}

/**
 * The positions (xyz interleaved) of at most 50,000 vertices evenly spaced in index order: a copy of every result
 * drawn while a 1M-vertex model settles would hold 24 MB each. Runs in the page (passed as source).
 */
function eyeSample(positions) {
  const n = positions.length / 3, stride = Math.ceil(n / 50000);
  const out = new Float64Array(3 * Math.ceil(n / stride));
  for (let v = 0, k = 0; v < n; v += stride, k += 3) out.set(positions.subarray(3 * v, 3 * v + 3), k);
  return out;
}

const server = await serveStatic(dist);
const browser = await launchBrowser({ viewport: { width: 1280, height: 800 } });
try {
  console.log(`${seconds} s drags; the app's defaults (fast Jacobian, iterations per request auto, drag integration auto)`);
  console.log('vertices  triangles  load+bind ms  to first deformable frame ms  updates/s  ms/iteration  samples  settle ms  to eye ms  peak RSS MB  W MB (float32)');
  for (const model of models) {
    const page = await browser.context.newPage();
    page.on('pageerror', (e) => console.error('page error:', e.message));
    await page.goto(`${server.url}index.html?example=bar`);
    await page.waitForFunction('!!globalThis.subspaceDeformer');
    await page.evaluate('globalThis.subspaceDeformer.ready');
    let peak = chromiumRssMb();
    const sampler = setInterval(() => { peak = Math.max(peak, chromiumRssMb()); }, 200);
    const r = await page.evaluate(async ({ model, seconds, helpers }) => {
      const app = globalThis.subspaceDeformer;
      const { stillToTheEye, eyeSample } = new Function(`${helpers}; return { stillToTheEye, eyeSample };`)();
      const t0 = performance.now();
      await app.loadScene({ mesh: `bench-data/${model.file}`, cage: `bench-data/${model.cage}`,
        handles: [{ vertices: model.fixed }, { vertices: model.moving, translate: [0, 0, 0] }] });
      const loaded = performance.now();
      const session = app.views[0].session;
      const moving = app.handles.groups.findIndex((g) => g.moving);
      // The drag: the first result drawn is the first deformable frame.
      let updates = 0;
      let first = 0;
      const samples = [];
      const onFrame = () => {
        if (!first) first = performance.now();
        updates++;
        samples.push(app.stats.samples);
      };
      app.addEventListener('frame', onFrame);
      // Main-thread JS of the app per update: applying a solver result (uploads, proxy) and its frame callback.
      let mainMs = 0;
      const onResult = session.onFrame;
      session.onFrame = (...a) => {
        const t = performance.now();
        onResult(...a);
        mainMs += performance.now() - t;
      };
      const iterations0 = session.totalIterations;
      const dragStart = performance.now();
      await new Promise((resolve) => {
        const tick = (now) => {
          if (now - dragStart >= 1000 * seconds) return resolve();
          const s = Math.sin((Math.PI * (now - dragStart)) / 2000);
          app.handles.setTransform(moving, model.swing.map((v) => v * s));
          requestAnimationFrame(tick);
        };
        requestAnimationFrame(tick);
      });
      app.handles.endTransform(); // the pointer's release, as the gizmo's: the solvers settle from here
      const dragged = performance.now();
      const firstDrag = updates && first ? first : dragged;
      const countedFrom = firstDrag;
      app.removeEventListener('frame', onFrame);
      session.onFrame = onResult;
      const iterations = session.totalIterations - iterations0;
      const drag = session.history.filter((h) => h.ms > 0 && h.iteration > iterations0); // the drag's, not the load's
      const ms = drag.map((h) => h.ms).sort((a, b) => a - b);
      const reducedShare = drag.filter((h) => h.samples > 0).length / Math.max(1, drag.length);
      // Each result drawn while it settles, to find when the shape stopped moving to the eye.
      const drawn = [{ at: dragged, positions: eyeSample(app.positions()) }];
      const onSettleFrame = () => drawn.push({ at: performance.now(), positions: eyeSample(app.positions()) });
      app.addEventListener('frame', onSettleFrame);
      const stats = await app.solve();
      const settledAt = performance.now();
      app.removeEventListener('frame', onSettleFrame);
      return {
        loadMs: loaded - t0, firstFrameMs: firstDrag - t0,
        updatesPerSecond: updates / ((dragged - countedFrom) / 1000 || 1),
        msPerIteration: ms.length ? ms[Math.floor(ms.length / 2)] : NaN,
        reducedShare, iterationsPerUpdate: iterations / Math.max(1, updates), mainMsPerUpdate: mainMs / Math.max(1, updates),
        samples: Math.max(0, ...samples), settleMs: settledAt - dragged, state: stats.state, settledSamples: stats.samples,
        eyeMs: stillToTheEye(drawn, app.positions(), app.restPositions(), settledAt) - dragged,
        float32: app.model.float32, wBytes: stats.vertexCount * app.model.basisSize * (app.model.float32 ? 4 : 8),
      };
    }, { model, seconds, helpers: `${stillToTheEye}\n${eyeSample}` });
    clearInterval(sampler);
    peak = Math.max(peak, chromiumRssMb());
    console.log(`${String(model.vertices).padStart(8)} ${String(model.triangles).padStart(10)} ${r.loadMs.toFixed(0).padStart(13)} ` +
      `${r.firstFrameMs.toFixed(0).padStart(29)} ${r.updatesPerSecond.toFixed(1).padStart(10)} ${r.msPerIteration.toFixed(1).padStart(13)} ` +
      `${String(r.samples).padStart(8)} ${r.settleMs.toFixed(0).padStart(10)} ${r.eyeMs.toFixed(0).padStart(9)} ${peak.toFixed(0).padStart(12)} ` +
      `${(r.wBytes / 1e6).toFixed(0).padStart(6)} (${r.float32})  settled ${r.state} (samples ${r.settledSamples}); ` +
      `${(100 * r.reducedShare).toFixed(0)}% of the drag's iterations reduced; ${r.iterationsPerUpdate.toFixed(1)} iterations and ${r.mainMsPerUpdate.toFixed(1)} ms of main-thread JS per update`);
    await page.close();
  }
} finally {
  await browser.close();
  await server.close();
}
