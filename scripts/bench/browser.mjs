#!/usr/bin/env node
// Speed of the browser app in headless Chromium (Debian's, software WebGL): for each built-in example the
// bind time; then per example (default: all) and method (default: subspace):
//   idle fps: a static scene redrawn every animation frame (the renderer's floor: no solver, no uploads; a
//   software renderer treats redraws on consecutive frames as motion: half resolution, and the coarse motion
//   proxy for meshes of more than 30k triangles, web/app/view/motion_proxy.js);
//   a scripted drag (the moving group swings up and down, its target updated every animation frame, as a
//   gizmo drag does) for a few seconds: page fps (rAF rate), redraws/s, main-thread JS per frame (the app's
//   animation-frame callback + applying solver results, i.e. what the app itself costs the page), ms per
//   iteration (median), solver iterations and updates per second, the share of drag frames that drew the
//   motion proxy; then the time to converge after release.
// Usage: node scripts/bench/browser.mjs [--seconds 4] [--examples bar,sphere] [--methods subspace,arap,full]
//        [--jacobian fast|exact] [--no-build]
// Note: headless Chromium renders with SwiftShader (CPU) on the same cores as the solver, so fps here is a
// floor, not what a GPU gives. SD_E2E_DIST=folder measures another build (e.g. an older one).
import { serveStatic } from '../../tests/e2e/static_server.mjs';
import { launchBrowser } from '../../tests/e2e/browser.mjs';
import { extentAlong } from '../../tests/e2e/geometry.mjs';
import { optionReader, siteToMeasure } from '../lib/browser_bench.mjs';

const args = process.argv.slice(2);
const opt = optionReader(args);
const seconds = Number(opt('seconds', 4));
const methods = opt('methods', 'subspace').split(',');
const jacobian = opt('jacobian', 'fast');
const dist = siteToMeasure(args);

const server = await serveStatic(dist);
const browser = await launchBrowser({ viewport: { width: 1280, height: 800 } });
try {
  const page = await browser.context.newPage();
  page.on('pageerror', (e) => console.error('page error:', e.message));
  await page.goto(`${server.url}index.html?method=subspace`);
  await page.waitForFunction('!!globalThis.subspaceDeformer');
  await page.evaluate('globalThis.subspaceDeformer.ready');

  const examples = await page.evaluate(async () => {
    const app = globalThis.subspaceDeformer;
    const out = [];
    for (const name of app.exampleNames) {
      const t = performance.now();
      await app.loadExample(name);
      out.push({ name, vertices: app.stats.vertexCount, cageVertices: app.model.cage.positions.length / 3,
        bindMs: app.model.bindMs, loadMs: performance.now() - t });
    }
    return out;
  });
  console.log('example      vertices  cage  bind ms  load ms (worker start + example + check + bind)');
  for (const e of examples) {
    console.log(`${e.name.padEnd(12)} ${String(e.vertices).padStart(8)} ${String(e.cageVertices).padStart(5)} ${e.bindMs.toFixed(0).padStart(8)} ${e.loadMs.toFixed(0).padStart(8)}`);
  }
  const chosen = opt('examples', examples.map((e) => e.name).join(',')).split(',');

  console.log(`\nper example: idle redraws, then a ${seconds} s drag per method (jacobian ${jacobian}, iterations per request: auto)`);
  console.log('example   method     idle fps  drag fps  redraws/s  main ms/frame  ms/iteration  iterations/s  updates/s  proxy  release->settled ms (iterations)');
  for (const name of chosen) {
    await page.evaluate((name) => globalThis.subspaceDeformer.loadExample(name), name);
    for (const method of methods) {
      const [lo, hi] = extentAlong(await page.evaluate(() => Array.from(globalThis.subspaceDeformer.restPositions())));
      const amplitude = 0.3 * (hi - lo);
      const r = await page.evaluate(async ({ method, seconds, jacobian, amplitude }) => {
        const app = globalThis.subspaceDeformer;
        app.setOptions({ method, jacobian });
        await app.resetHandles(); // targets and mesh back at rest
        await app.solve();
        const session = app.views[0].session;
        const viewport = app.views[0].viewport;
        const frameLoop = (ms, each) => new Promise((resolve) => {
          let frames = 0;
          const t0 = performance.now();
          const tick = (now) => {
            if (now - t0 >= ms) return resolve(frames / ((now - t0) / 1000));
            frames++;
            each(now - t0);
            requestAnimationFrame(tick);
          };
          requestAnimationFrame(tick);
        });
        // Static scene, redrawn every frame.
        const idleFps = await frameLoop(2000, () => viewport.invalidate());
        // Main-thread JS of the app: its animation-frame callback and the handling of solver results.
        let mainMs = 0;
        const loop = app.loop;
        app.loop = (now) => {
          const t = performance.now();
          const redraws = loop(now);
          mainMs += performance.now() - t;
          return redraws;
        };
        const onFrame = session.onFrame;
        session.onFrame = (...a) => {
          const t = performance.now();
          onFrame(...a);
          mainMs += performance.now() - t;
        };
        let renders = 0;
        const render = viewport.render;
        viewport.render = function () {
          renders++;
          return render.call(this);
        };
        const group = app.handles.groups.findIndex((g) => g.moving);
        let updates = 0;
        const count = () => updates++;
        app.addEventListener('frame', count);
        const it0 = session.totalIterations;
        const t0 = performance.now();
        let frames = 0;
        let proxyFrames = 0;
        const fps = await frameLoop(1000 * seconds, (t) => {
          frames++;
          if (viewport.meshView.drawingProxy) proxyFrames++;
          app.handles.setTransform(group, [0, amplitude * Math.sin((Math.PI * t) / 1000), 0]);
        });
        const elapsed = (performance.now() - t0) / 1000;
        app.loop = loop;
        session.onFrame = onFrame;
        viewport.render = render;
        app.removeEventListener('frame', count);
        const iterations = session.totalIterations - it0;
        const ms = session.history.filter((h) => h.iteration > it0).map((h) => h.ms).filter((x) => x > 0).sort((a, b) => a - b);
        const t1 = performance.now();
        const it1 = session.totalIterations;
        const stats = await app.solve();
        return { idleFps, fps, renderFps: renders / elapsed, mainMsPerFrame: mainMs / Math.max(1, frames),
          msPerIteration: ms.length ? ms[Math.floor(ms.length / 2)] : NaN, iterationsPerSecond: iterations / elapsed,
          updatesPerSecond: updates / elapsed, proxyShare: proxyFrames / Math.max(1, frames), releaseMs: performance.now() - t1, releaseIterations: session.totalIterations - it1,
          state: stats.state, stopReason: stats.stopReason, volumeRelError: stats.volumeRelError };
      }, { method, seconds, jacobian, amplitude });
      console.log(`${name.padEnd(9)} ${method.padEnd(9)} ${r.idleFps.toFixed(1).padStart(9)} ${r.fps.toFixed(1).padStart(9)} ${r.renderFps.toFixed(1).padStart(10)} ` +
        `${r.mainMsPerFrame.toFixed(1).padStart(14)} ${r.msPerIteration.toFixed(2).padStart(13)} ${r.iterationsPerSecond.toFixed(1).padStart(13)} ` +
        `${r.updatesPerSecond.toFixed(1).padStart(10)} ${`${(100 * r.proxyShare).toFixed(0)}%`.padStart(6)}  ${r.releaseMs.toFixed(0)} (${r.releaseIterations}) ${r.state}` +
        `${r.state === 'stopped' ? ` (${r.stopReason})` : ''}, volume error ${r.volumeRelError.toExponential(1)}`);
    }
  }
} finally {
  await browser.close();
  await server.close();
}
