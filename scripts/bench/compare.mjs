#!/usr/bin/env node
// Does the slowest method starve the others in compare mode? Headless Chromium (Debian's, software WebGL),
// one example: each method alone in a single view, then the three side by side (compare mode), each time a
// scripted drag (the moving group swings up and down, its target updated every animation frame, as a gizmo
// drag does) and then the release. Per view: solver iterations and updates (results drawn) per second
// during the drag, the median and 95th-percentile gap between its updates (how stale the view gets), the
// median ms per iteration, and the time from release to settled. Page: animation frames per second and the
// app's own main-thread ms per frame (its frame callback plus applying results). Iterations after the
// release: how far each view had to go once the handles stopped.
// Usage: node scripts/bench/compare.mjs [--example bar-fine] [--seconds 4] [--methods arap,subspace,full]
//        [--threads auto|N] [--idle METHOD] [--no-build]
// --idle METHOD: in compare mode that view is drawn but does not solve (its requests stop), which separates
// what its solver costs the others from what drawing one more view costs.
// SD_E2E_DIST=folder measures another build (e.g. the code before a change, built into its own folder).
import { serveStatic } from '../../tests/e2e/static_server.mjs';
import { launchBrowser } from '../../tests/e2e/browser.mjs';
import { extentAlong } from '../../tests/e2e/geometry.mjs';
import { optionReader, siteToMeasure } from '../lib/browser_bench.mjs';

const args = process.argv.slice(2);
const opt = optionReader(args);
const example = opt('example', 'bar-fine');
const seconds = Number(opt('seconds', 4));
const methods = opt('methods', 'arap,subspace,full').split(',');
const threads = opt('threads', 'auto');
const idle = opt('idle', '');
const dist = siteToMeasure(args);

/** In the page: a drag of `seconds`, then the release; per view what it got. */
async function measure({ seconds, amplitude, idle }) {
  const app = globalThis.subspaceDeformer;
  await app.resetHandles();
  await app.solve();
  for (const view of app.views) if (view.method === idle && app.views.length > 1) view.session.pump = () => {};
  const group = app.handles.groups.findIndex((g) => g.moving);
  const views = app.views.map((view) => {
    const record = { method: view.method, updates: [], it0: view.session.totalIterations, view };
    view.addEventListener('frame', () => record.updates.push(performance.now()));
    return record;
  });
  let mainMs = 0;
  const loop = app.loop;
  app.loop = (now) => {
    const t = performance.now();
    const redraws = loop(now);
    mainMs += performance.now() - t;
    return redraws;
  };
  const t0 = performance.now();
  let frames = 0;
  await new Promise((resolve) => {
    const tick = (now) => {
      const t = now - t0;
      if (t >= 1000 * seconds) return resolve();
      frames++;
      app.handles.setTransform(group, [0, amplitude * Math.sin((Math.PI * t) / 1000), 0]);
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
  const elapsed = (performance.now() - t0) / 1000;
  app.loop = loop;
  const release = performance.now();
  const atRelease = views.map((r) => r.view.session.totalIterations);
  const settled = await Promise.all(views.map(async (r) => {
    if (r.method === idle && views.length > 1) return NaN;
    await r.view.session.settled();
    return performance.now() - release;
  }));
  const quantile = (values, q) => {
    if (!values.length) return NaN;
    const sorted = [...values].sort((a, b) => a - b);
    return sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
  };
  return {
    fps: frames / elapsed,
    mainMsPerFrame: mainMs / Math.max(1, frames),
    views: views.map((r, i) => {
      const during = r.updates.filter((t) => t - t0 <= 1000 * seconds);
      const gaps = during.slice(1).map((t, k) => t - during[k]);
      const points = r.view.session.history;
      const iterations = points.filter((p) => p.iteration > r.it0);
      return {
        method: r.method,
        updatesPerSecond: during.length / elapsed,
        gapMedian: quantile(gaps, 0.5),
        gap95: quantile(gaps, 0.95),
        msPerIteration: quantile(iterations.map((p) => p.ms), 0.5),
        iterationsPerSecond: (r.view.session.totalIterations - r.it0) / (elapsed + settled[i] / 1000),
        settleMs: settled[i],
        releaseIterations: r.view.session.totalIterations - atRelease[i],
        state: r.view.session.state,
      };
    }),
  };
}

const server = await serveStatic(dist, { isolated: true });
const browser = await launchBrowser({ viewport: { width: 1280, height: 800 } });
const line = (label, r) => {
  for (const v of r.views) {
    console.log(`${label.padEnd(9)} ${v.method.padEnd(9)} ${v.updatesPerSecond.toFixed(1).padStart(9)} ${v.gapMedian.toFixed(0).padStart(10)} ` +
      `${v.gap95.toFixed(0).padStart(8)} ${v.msPerIteration.toFixed(1).padStart(13)} ${v.settleMs.toFixed(0).padStart(11)} ` +
      `(${v.releaseIterations}) ${v.state}` +
      `   (page ${r.fps.toFixed(1)} fps, app ${r.mainMsPerFrame.toFixed(1)} ms/frame)`);
  }
};
try {
  console.log(`${example}, ${seconds} s drag, threads ${threads}, cores ${await (async () => {
    const page = await browser.context.newPage();
    const n = await page.evaluate(() => navigator.hardwareConcurrency);
    await page.close();
    return n;
  })()}`);
  console.log('mode      method    updates/s  gap median  gap 95%  ms/iteration  release->settled ms (iterations)');
  const runs = [...methods.map((m) => ({ label: 'alone', query: `method=${m}` })), { label: 'compare', query: `compare=${methods.join(',')}` }];
  for (const run of runs) {
    const page = await browser.context.newPage();
    page.on('pageerror', (e) => console.error('page error:', e.message));
    await page.goto(`${server.url}index.html?example=${example}&${run.query}`);
    await page.waitForFunction('!!globalThis.subspaceDeformer');
    await page.evaluate('globalThis.subspaceDeformer.ready');
    if (threads !== 'auto') await page.evaluate((n) => globalThis.subspaceDeformer.setOptions({ threads: n }), Number(threads));
    const [lo, hi] = extentAlong(await page.evaluate(() => Array.from(globalThis.subspaceDeformer.restPositions())));
    line(run.label, await page.evaluate(measure, { seconds, amplitude: 0.3 * (hi - lo), idle }));
    await page.close();
  }
} finally {
  await browser.close();
  await server.close();
}
