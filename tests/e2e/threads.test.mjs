// Threads in the browser: the served app is cross-origin isolated and its solver runs the threaded build
// (pthread workers and all); a static host that sends no headers gets isolation from the service worker
// shim after one reload; and an embed on a course page without isolation still works, single-threaded.
import assert from 'node:assert/strict';
import { appReady, waitForIsolation } from './app_probe.mjs';

/** Records which wasm builds a page fetched (requests from its workers count too). */
function watchBuilds(page) {
  const seen = { threaded: false, single: false, pthreadWorker: false };
  page.on('request', (request) => {
    const path = new URL(request.url()).pathname;
    if (path.endsWith('/threads/subspace_deform.wasm')) seen.threaded = true;
    if (path.endsWith('/threads/subspace_deform.worker.js')) seen.pthreadWorker = true;
    if (/\/assets\/subspace_deform-[\w-]+\.wasm$/.test(path)) seen.single = true;
  });
  return seen;
}

/** Drags the moving group and checks the solver answered: converged, volume kept. */
async function dragWorks(page, get) {
  const stats = await page.evaluate(`(${get}).drag(1, [0, 0.4, 0.1])`);
  assert.ok(stats.iterations > 0, `iterations: ${stats.iterations}`);
  assert.ok(Math.abs(stats.volumeRelError) < 1e-8, `volume error ${stats.volumeRelError}`);
}

export default [
  {
    name: 'the served app is cross-origin isolated and its solver runs the threaded build',
    timeout: 40000,
    async run(t) {
      const page = await t.page(null);
      const seen = watchBuilds(page);
      await page.goto(`${t.url}index.html`);
      await appReady(page);
      assert.equal(await page.evaluate('crossOriginIsolated'), true);
      const solver = await page.evaluate('globalThis.subspaceDeformer.model.solver');
      assert.equal(solver.build, 'threads', JSON.stringify(solver));
      const cores = await page.evaluate('Math.min(16, navigator.hardwareConcurrency)');
      assert.equal(solver.threads, cores, `${solver.threads} threads on ${cores} cores`);
      assert.ok(seen.threaded && seen.pthreadWorker, `fetched: ${JSON.stringify(seen)}`);
      assert.equal(seen.single, false, 'the single-threaded build was not needed');
      await dragWorks(page, 'globalThis.subspaceDeformer');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a static host without headers: the service worker isolates the page after one reload, threads run',
    timeout: 90000,
    async run(t) {
      const url = await t.serve({ isolated: false });
      const page = await t.page(null);
      const seen = watchBuilds(page);
      await page.goto(`${url}index.html`);
      // coi-serviceworker registers itself and reloads the page once; the reloaded page is isolated.
      await waitForIsolation(page);
      await appReady(page);
      const solver = await page.evaluate('globalThis.subspaceDeformer.model.solver');
      assert.equal(solver.build, 'threads', JSON.stringify(solver));
      assert.ok(seen.threaded, `fetched: ${JSON.stringify(seen)}`);
      await dragWorks(page, 'globalThis.subspaceDeformer');
    },
  },
  {
    name: 'an embed on a course page without isolation works single-threaded',
    timeout: 40000,
    async run(t) {
      const url = await t.serve({ isolated: false });
      // The course page loads only the embed script (no service worker shim), as most course pages would.
      const html = '<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,">' +
        '<script type="module" src="subspace-deformer.js"></script></head><body>' +
        '<subspace-deformer id="e" example="bar" panel="none" style="height: 360px"></subspace-deformer></body></html>';
      const page = await t.page(null);
      const seen = watchBuilds(page);
      await page.route('**/plain-course-page.html', (route) => route.fulfill({ contentType: 'text/html', body: html }));
      await page.goto(`${url}plain-course-page.html`);
      const el = "document.getElementById('e')";
      await appReady(page, `${el}.app`);
      assert.equal(await page.evaluate('crossOriginIsolated'), false);
      const solver = await page.evaluate(`${el}.app.model.solver`);
      assert.equal(solver.build, 'single', JSON.stringify(solver));
      assert.equal(solver.threads, 1);
      assert.match(solver.buildNote, /not cross-origin isolated/);
      assert.ok(seen.single && !seen.threaded, `fetched: ${JSON.stringify(seen)}`);
      await dragWorks(page, el);
      assert.deepEqual(page.errors, []);
    },
  },
];
