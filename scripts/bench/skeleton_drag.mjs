#!/usr/bin/env node
// The app's drag rate with and without bones (docs/experiments/skeleton.md, "Drag rate in the app"): each built-in
// example is loaded in Chromium with its default handles and dragged as a user would (its moving group swung
// along z by up to 15% of the model's height (its y extent) every animation frame), once without a skeleton and once with two bones
// along its longest axis (joints at the centroids of the vertices near 20%, 50% and 80% of that axis), alternating
// twice. Per drag: solver results drawn per second, the solver's median ms per iteration, and the page's drawing
// rate. What the user sees is the first number; the second says what the bones cost the solver.
// Usage: node scripts/bench/skeleton_drag.mjs [--examples bar,sphere,...] [--seconds 4] [--no-build]
import { EXAMPLE_NAMES } from '../../web/lib/example_names.js';
import { serveStatic } from '../../tests/e2e/static_server.mjs';
import { launchBrowser } from '../../tests/e2e/browser.mjs';
import { optionReader, siteToMeasure } from '../lib/browser_bench.mjs';

const args = process.argv.slice(2);
const opt = optionReader(args);
const examples = opt('examples', EXAMPLE_NAMES.join(',')).split(',').filter(Boolean);
const seconds = Number(opt('seconds', 4));
const dist = siteToMeasure(args);

/**
 * Two bones along the longest axis of `rest` (xyz interleaved): joints at the centroids of the vertices within 5%
 * of 20%, 50% and 80% of that axis. Runs in the page (passed as source).
 */
function spine(rest) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < rest.length; ++i) {
    lo[i % 3] = Math.min(lo[i % 3], rest[i]);
    hi[i % 3] = Math.max(hi[i % 3], rest[i]);
  }
  const axis = [0, 1, 2].reduce((a, b) => (hi[b] - lo[b] > hi[a] - lo[a] ? b : a));
  const joints = [0.2, 0.5, 0.8].map((f) => {
    const sum = [0, 0, 0];
    let count = 0;
    for (let i = 0; i < rest.length; i += 3) {
      if (Math.abs((rest[i + axis] - lo[axis]) / (hi[axis] - lo[axis]) - f) > 0.05) continue;
      for (let k = 0; k < 3; ++k) sum[k] += rest[i + k];
      count++;
    }
    return sum.map((s) => s / count);
  });
  return { joints, bones: [[0, 1], [1, 2]] };
}

/** One drag of `seconds` of the moving group, in the page: updates/s, median ms per iteration, drawing rate. */
async function drag(page) {
  return page.evaluate(async (seconds) => {
    const app = globalThis.subspaceDeformer;
    await app.solve();
    const session = app.views[0].session;
    const moving = app.handles.groups.findIndex((g) => g.moving);
    const rest = app.restPositions();
    let lo = Infinity, hi = -Infinity;
    for (let i = 1; i < rest.length; i += 3) { lo = Math.min(lo, rest[i]); hi = Math.max(hi, rest[i]); }
    const swing = 0.15 * (hi - lo);
    let updates = 0;
    const onFrame = () => updates++;
    app.addEventListener('frame', onFrame);
    const iterations0 = session.totalIterations;
    const start = performance.now();
    let drawn = 0;
    await new Promise((resolve) => {
      const tick = (now) => {
        if (now - start >= 1000 * seconds) return resolve();
        drawn++;
        const s = Math.sin((Math.PI * (now - start)) / (1000 * seconds));
        app.handles.setTransform(moving, [0, 0, swing * s]);
        requestAnimationFrame(tick);
      };
      requestAnimationFrame(tick);
    });
    const elapsed = (performance.now() - start) / 1000;
    app.handles.endTransform();
    app.removeEventListener('frame', onFrame);
    const ms = session.history.filter((h) => h.ms > 0 && h.iteration > iterations0).map((h) => h.ms).sort((a, b) => a - b);
    await app.solve();
    app.resetHandles();
    await app.solve();
    return { updatesPerSecond: updates / elapsed, msPerIteration: ms[Math.floor(ms.length / 2)] ?? NaN, drawingFps: drawn / elapsed };
  }, seconds);
}

const server = await serveStatic(dist);
const browser = await launchBrowser({ viewport: { width: 1280, height: 800 } });
const pad = (v, n, digits = 1) => (typeof v === 'number' ? v.toFixed(digits) : String(v)).padStart(n);
try {
  console.log(`${seconds} s drags of each example's moving group, without and with two bones, alternating twice`);
  console.log('example    vertices  bones  updates/s  ms/iteration  drawing fps');
  for (const example of examples) {
    const page = await browser.context.newPage();
    page.on('pageerror', (e) => console.error('page error:', e.message));
    await page.goto(`${server.url}index.html?example=${example}`);
    await page.waitForFunction('!!globalThis.subspaceDeformer');
    await page.evaluate('globalThis.subspaceDeformer.ready');
    const vertices = await page.evaluate(() => globalThis.subspaceDeformer.restPositions().length / 3);
    const skeleton = await page.evaluate((source) => new Function(`return (${source})`)()(globalThis.subspaceDeformer.restPositions()), spine.toString());
    for (const round of [0, 1]) {
      for (const bones of round === 0 ? [false, true] : [true, false]) {
        const refused = await page.evaluate((spec) => globalThis.subspaceDeformer.skeleton.use(spec).then(() => null, (e) => e.message),
          bones ? skeleton : null);
        if (refused) {
          console.log(`${example.padEnd(10)} ${pad(vertices, 8, 0)}  the spine was refused: ${refused}`);
          continue;
        }
        const r = await drag(page);
        console.log(`${example.padEnd(10)} ${pad(vertices, 8, 0)}  ${bones ? '  yes' : '   no'}  ${pad(r.updatesPerSecond, 9)}  ` +
          `${pad(r.msPerIteration, 12)}  ${pad(r.drawingFps, 11)}`);
      }
    }
    await page.close();
  }
} finally {
  await browser.close();
  await server.close();
}
