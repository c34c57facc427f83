// What the app tells the user: the convergence plot (one series per method and per model), warm times per
// iteration, the rest cage dimmed where the method does not move it, solve() waiting for new compare views,
// panel rows that are not cut, the model's name and size, compact saved scenes, a first load that fails,
// the progress of a long full-space solve, the wasm build and threads (and the threads control), an embed
// mounted into an unsized element, and the poor-cage warning with its "Generate cage".
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { appReady, haveSharedData, installReplyGate, overlaps, rect, routeSharedData } from './app_probe.mjs';

const app = 'globalThis.subspaceDeformer';

/**
 * The cut names and values of the panel: rows whose text is wider than its box, and choices whose text wraps out
 * of sight (lil-gui breaks a choice's text anywhere in a box one line high: "harmonic (harmon").
 */
function cutPanelText(page) {
  return page.evaluate(() => {
    const cut = [];
    for (const row of document.querySelectorAll('.lil-controller')) {
      const parts = [row.querySelector('.lil-name'), row.querySelector('.lil-display'), row.querySelector('input:not([type=checkbox])')];
      for (const el of parts) if (el && el.offsetParent && el.scrollWidth > el.clientWidth + 1) cut.push(el.textContent || el.value);
      const choice = row.querySelector('.lil-option .lil-display');
      if (choice?.offsetParent && choice.scrollHeight > choice.clientHeight + 1) cut.push(choice.textContent);
    }
    return cut;
  });
}

export default [
  {
    // lil-gui's touch styles have larger fonts: a tablet showed Armijo c1 0.0001 as "0.000" and cut two choices.
    name: 'no panel row is cut on a touch tablet either, every folder open',
    timeout: 45000,
    async run(t) {
      const page = await t.touchPage('index.html', { width: 820, height: 1180 });
      await appReady(page);
      await page.evaluate(`${app}.setPanelOpen(true)`);
      await page.evaluate(() => document.querySelectorAll('.lil-title[aria-expanded=false]').forEach((title) => title.click()));
      assert.deepEqual(await cutPanelText(page), [], 'panel text cut');
      const c1 = page.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: /^Armijo c1$/ }) }).locator('input');
      assert.equal(await c1.inputValue(), '0.0001');
      await t.screenshot(page, 'tablet-panel');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'the plot starts a fresh series per method and per model; times per iteration leave out the cold first one',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const plot = () => page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        const view = app.views[0];
        return { shown: view.viewport.plot.shown, series: view.session.record.series.map((s) => [s.method, s.points.length]),
          stats: app.stats, points: view.session.history.map((p) => p.ms),
          iterations: view.session.history.map((p) => p.iteration),
          firstPositive: view.session.history.find((p) => p.merit > 0)?.iteration };
      });
      await page.evaluate(`${app}.drag(1, [0, 0.5, 0.2])`);
      await page.waitForFunction(() => globalThis.subspaceDeformer.views[0].viewport.plot.shown?.points > 1);
      const subspace = await plot();
      assert.match(subspace.shown.label, /^Subspace/);
      // The series is numbered from 1; the log plot starts at its first positive merit (an iteration that
      // found the rest pose already solved has a merit of 0 up to rounding, e.g. -1.8e-25, and is not drawn).
      assert.equal(subspace.iterations[0], 1);
      assert.ok(subspace.firstPositive <= 2, `first positive merit at iteration ${subspace.firstPositive}`);
      assert.equal(subspace.shown.first, subspace.firstPositive);
      // Warm time: the median of the iterations after the first (which carries the one-off set-up).
      const warm = subspace.points.slice(1).sort((a, b) => a - b);
      const median = warm.length % 2 ? warm[warm.length >> 1] : 0.5 * (warm[warm.length / 2 - 1] + warm[warm.length / 2]);
      assert.ok(Math.abs(subspace.stats.msPerIteration - median) < 1e-9, `${subspace.stats.msPerIteration} vs median ${median}`);
      assert.equal(subspace.stats.firstIterationMs, subspace.points[0]);
      // Another method: its own series, numbered from 1, its own label; the subspace one is kept apart.
      await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        app.setOptions({ method: 'arap' });
        await app.drag(1, [0, 0.5, 0.3]);
      });
      await page.waitForFunction(() => {
        const app = globalThis.subspaceDeformer;
        const shown = app.views[0].viewport.plot.shown;
        return shown?.label === 'ARAP' && shown.last === app.stats.iterations; // the plot is redrawn 5 times a second
      });
      const arap = await plot();
      assert.deepEqual(arap.series.map((s) => s[0]), ['subspace', 'arap']);
      assert.equal(arap.iterations[0], 1);
      assert.equal(arap.shown.first, arap.firstPositive);
      assert.equal(arap.shown.last, arap.stats.iterations);
      assert.equal(arap.series[1][1], arap.stats.iterations, 'the ARAP series holds only ARAP iterations');
      // Another model: one fresh series.
      await page.evaluate(`${app}.loadExample('sphere')`);
      assert.equal((await plot()).series.length, 1);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'compare mode: solve() waits for new views, rest cages dimmed, nothing overlaps, model and panel readable',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      // Toggle compare and solve at once: solve() resolves only when every new view has bound and settled.
      const after = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.drag(1, [0, 0.5, 0.2]);
        app.setCompare(true);
        await app.solve();
        const rest = app.restPositions();
        return app.views.map((v, i) => ({ method: v.method, state: v.session.state, moved: app.positions(i).some((x, k) => Math.abs(x - rest[k]) > 0.1),
          opacity: v.viewport.cageView.lineMaterial.opacity, note: v.cageNote.textContent,
          cageAtRest: app.cagePositions(i).every((x, k) => x === app.model.cage.positions[k]) }));
      });
      assert.deepEqual(after.map((v) => v.method), ['arap', 'subspace', 'full']);
      for (const v of after) {
        assert.equal(v.state, 'converged', `${v.method} settled before solve() returned`);
        assert.ok(v.moved, `${v.method} shows the drag`);
      }
      const [arap, subspace, full] = after;
      for (const v of [arap, full]) {
        assert.ok(v.cageAtRest && v.opacity < subspace.opacity, `${v.method}: the rest cage, dimmed (${v.opacity} vs ${subspace.opacity})`);
        assert.match(v.note, /rest cage/);
      }
      assert.equal(subspace.cageAtRest, false, 'the subspace cage moved');
      assert.equal(subspace.note, '');
      // The status bar (model, fps) overlaps no stats line and no plot; the model's name and size are in it.
      await page.waitForFunction(() => document.querySelectorAll('.sd-plot').length === 3);
      const status = await rect(page, '.sd-status');
      const boxes = await page.evaluate(() => [...document.querySelectorAll('.sd-plot, .sd-stats')].map((e) => {
        const r = e.getBoundingClientRect();
        return { left: r.left, top: r.top, right: r.right, bottom: r.bottom };
      }));
      for (const box of boxes) assert.ok(!overlaps(status, box), `status bar ${JSON.stringify(status)} over ${JSON.stringify(box)}`);
      assert.equal(await page.textContent('.sd-model'), 'bar: 5,042 vertices, 10,080 triangles, cage 28 vertices');
      assert.match(await page.textContent('.sd-fps'), /^\d+ fps/);
      assert.deepEqual(await cutPanelText(page), [], 'panel text cut');
      // A saved scene writes each vertex list on one line.
      await page.locator('.lil-gui .lil-title', { hasText: 'Export' }).click(); // the folder starts closed
      const [download] = await Promise.all([page.waitForEvent('download'),
        page.locator('.lil-gui button', { hasText: 'save scene (JSON)' }).click()]);
      const text = readFileSync(await download.path(), 'utf8');
      const scene = JSON.parse(text);
      assert.ok(text.split('\n').length < 40, `${text.split('\n').length} lines for ${scene.handles.length} groups`);
      assert.ok(text.includes(`"vertices": [${scene.handles[0].vertices.join(', ')}]`));
      await t.screenshot(page, 'compare-stats');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a first load that fails says no model is loaded, in the banner and in the view',
    async run(t) {
      const page = await t.page(null);
      page.errors.length = 0;
      await page.goto(`${t.url}index.html?mesh=missing.obj&cage=missing_cage.obj`);
      await page.waitForFunction(() => !!globalThis.subspaceDeformer);
      await page.evaluate(`${app}.ready`).catch(() => {});
      const banner = await page.textContent('.sd-banner .sd-message');
      assert.match(banner, /missing\.obj/);
      assert.match(banner, /No model is loaded\./);
      assert.doesNotMatch(banner, /previous model/);
      await page.waitForFunction(() => /no model loaded/.test(document.querySelector('.sd-stats')?.textContent));
      assert.doesNotMatch(await page.textContent('.sd-stats'), /loading/);
      page.errors.length = 0; // the 404s of the missing files are the point of this test
    },
  },
  {
    name: 'a long full-space solve shows its progress and, when done, its iterations and time',
    timeout: 90000,
    async run(t) {
      const page = await t.page(null);
      await installReplyGate(page);
      await page.goto(`${t.url}index.html?method=full`);
      await appReady(page);
      // One iteration per request, and the solver's replies held after the first of this solve: the solve
      // stays in progress (as a long one on a slow machine) for as long as the test holds them.
      await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.solve();
        app.setOptions({ iterationsPerFrame: 1 });
        const onFrame = () => {
          if (app.stats.progress?.iteration < 1) return;
          globalThis.replyGate.hold();
          app.removeEventListener('frame', onFrame);
        };
        app.addEventListener('frame', onFrame);
        app.drag(1, [0, 2, 0.5]);
      });
      const line = () => page.textContent('.sd-stats');
      // The line shows the progress of a solve that has run for a while (the app's threshold; it is redrawn a
      // few times a second).
      await page.waitForFunction(() => /iteration [1-9]\d* of at most 100 .* so far .* at most .* left/.test(document.querySelector('.sd-stats').textContent),
        null, { timeout: 30000 });
      const during = await line();
      const progress = await page.evaluate(`${app}.stats.progress`);
      assert.equal(progress.maxIterations, 100);
      assert.ok(progress.iteration >= 1 && progress.msLeftAtMost > 0, JSON.stringify(progress));
      await t.screenshot(page, 'long-solve-progress');
      await page.evaluate(() => globalThis.replyGate.release());
      const stats = await page.evaluate(`${app}.solve()`);
      assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
      await page.waitForFunction(() => /\d+ iterations in \d/.test(document.querySelector('.sd-stats').textContent));
      assert.match(await line(), /converged/);
      assert.match(during, /s\/iteration|first iteration/);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'each view says which wasm build runs with how many threads; the threads control shares the cores',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const cores = await page.evaluate('Math.min(16, navigator.hardwareConcurrency)');
      const statsText = () => page.evaluate(() => [...document.querySelectorAll('.sd-stats')].map((e) => e.textContent));
      await page.waitForFunction((n) => document.querySelector('.sd-stats').textContent.includes(`wasm: threaded build, ${n} thread`), cores);
      const threadsRow = page.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: /^threads$/ }) }).locator('select');
      // The default first, then the counts (integer labels once put 'auto' last).
      const labels = await threadsRow.evaluate((select) => [...select.options].map((o) => o.textContent));
      assert.deepEqual(labels.slice(0, 2), ['auto (every core)', '1 thread']);
      await threadsRow.selectOption({ label: '1 thread' });
      assert.equal(await page.evaluate(`${app}.settings.threads`), 1);
      await page.waitForFunction(() => document.querySelector('.sd-stats').textContent.includes('wasm: threaded build, 1 thread'));
      // Compare mode: the page's cores are split between the views' workers.
      await threadsRow.selectOption({ label: 'auto (every core)' });
      await page.evaluate(`${app}.setCompare(true)`);
      const share = Math.max(1, Math.floor(cores / 3));
      await page.waitForFunction((share) => {
        const lines = [...document.querySelectorAll('.sd-stats')].map((e) => e.textContent);
        return lines.length === 3 && lines.every((l) => l.includes(`threaded build, ${share} thread`));
      }, share);
      assert.equal((await statsText()).length, 3);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'without isolation: single-threaded said and why, threads control disabled; an unsized mount gets a sensible size',
    timeout: 45000,
    async run(t) {
      const url = await t.serve({ isolated: false });
      const html = '<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,"></head><body style="margin:0">' +
        '<div id="unsized" style="width: 800px"></div><subspace-deformer id="e" example="bar" panel="open" style="height: 520px"></subspace-deformer>' +
        '<script type="module">import { mount } from "./subspace-deformer.js"; globalThis.mounted = mount(document.getElementById("unsized"), { panel: false });</script>' +
        '</body></html>';
      const page = await t.page(null);
      await page.route('**/plain-page.html', (route) => route.fulfill({ contentType: 'text/html', body: html }));
      await page.goto(`${url}plain-page.html`);
      await appReady(page, 'globalThis.mounted');
      await appReady(page, "document.getElementById('e').app");
      const size = await page.evaluate(() => {
        const r = globalThis.mounted.element.getBoundingClientRect();
        return { width: r.width, height: r.height };
      });
      assert.equal(size.width, 800);
      assert.ok(Math.abs(size.height - 500) <= 2, `unsized mount: ${size.width} x ${size.height} (16:10 expected)`);
      const view = await page.evaluate(() => globalThis.mounted.views[0].element.getBoundingClientRect().height);
      assert.ok(view > 400, `its view is ${view} px tall`);
      await page.waitForFunction(() => /single-threaded build \(page not cross-origin isolated\)/.test(document.querySelector('#e .sd-stats')?.textContent));
      const row = page.locator('#e .lil-controller', { has: page.locator('.lil-name', { hasText: /^threads$/ }) });
      assert.match(await row.locator('.lil-display').textContent(), /1 \(single-threaded build\)/);
      assert.equal(await row.evaluate((el) => el.classList.contains('lil-disabled')), true);
      assert.match(await row.getAttribute('title'), /not cross-origin isolated/);
      await t.screenshot(page, 'unsized-mount');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a poor cage gets a warning with "Generate cage", which replaces it by a good one',
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      // The bar in its own cage blown up 5 times about the bar's centre: a loose cage.
      await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        const obj = (p, f) => [...Array.from({ length: p.length / 3 }, (_, i) => `v ${p[3 * i]} ${p[3 * i + 1]} ${p[3 * i + 2]}`),
          ...Array.from({ length: f.length / 3 }, (_, i) => `f ${f[3 * i] + 1} ${f[3 * i + 1] + 1} ${f[3 * i + 2] + 1}`)].join('\n');
        const cage = app.model.cage.positions.map((x) => 5 * x);
        const files = [new File([obj(app.restPositions(), app.indices())], 'bar.obj'), new File([obj(cage, app.model.cage.indices)], 'loose_cage.obj')];
        await app.loadFiles(files);
      });
      const banner = page.locator('.sd-banner');
      assert.equal(await banner.getAttribute('data-kind'), 'warning');
      assert.match(await banner.textContent(), /The cage of bar\.obj looks poor:[\s\S]*times the mesh's volume/);
      const quality = await page.evaluate(`${app}.model.cageQuality`);
      assert.ok(quality.poor && quality.volumeRatio > 20, JSON.stringify(quality));
      // The spectral basis does not use the cage: no quality, no warning, no rest cage drawn or noted in ARAP's
      // view, the status bar names the modes; back to the cage basis, the warning is back.
      await page.evaluate(`${app}.setOptions({ method: 'arap' })`);
      await page.evaluate(`${app}.setBasis('spectral', 12)`);
      assert.equal(await page.evaluate(`${app}.model.cageQuality`), null);
      assert.ok(await banner.isHidden(), 'no warning about a cage the spectral basis does not use');
      assert.equal(await page.textContent('.sd-cage-note'), '');
      assert.equal(await page.evaluate(`${app}.views[0].viewport.cageView.shown`), false);
      await page.waitForFunction(() => /spectral basis, 12 modes$/.test(document.querySelector('.sd-model').textContent));
      await page.evaluate(`${app}.setBasis('cage')`);
      assert.match(await banner.textContent(), /The cage of bar\.obj looks poor/);
      assert.match(await page.textContent('.sd-cage-note'), /rest cage \(dimmed\): ARAP does not move it/);
      await page.evaluate(`${app}.setOptions({ method: 'subspace' })`);
      await banner.locator('input').fill('60');
      await banner.locator('button', { hasText: 'Generate cage' }).click();
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.generatedCage, null, { timeout: 60000 });
      const generated = await page.evaluate(`${app}.model`);
      assert.equal(generated.cageQuality.poor, false, JSON.stringify(generated.cageQuality));
      assert.ok(generated.cage.positions.length / 3 >= 40, `${generated.cage.positions.length / 3} cage vertices`);
      assert.ok(await banner.isHidden(), 'the warning is gone with the poor cage');
      if (haveSharedData('cow.obj', 'cow_cage.obj')) {
        await routeSharedData(page);
        await page.evaluate(`${app}.loadUrls('shared-data/cow.obj', 'shared-data/cow_cage.obj')`);
        assert.match(await banner.textContent(), /cow\.obj looks poor:[\s\S]*motions of the cage barely move the mesh/);
        await t.screenshot(page, 'poor-cage-cow');
        // Without the cage regularisation (docs/method.md 6.1) pulling the cow's head by 5% of the diagonal grew its
        // cage's diagonal from 42 to 543: a loose cage's free motions; it must stay within 1.5x its rest diagonal.
        const { rest, deformed } = await page.evaluate(async () => {
          const app = globalThis.subspaceDeformer;
          const p = app.restPositions(), n = p.length / 3;
          const diagonal = (q) => {
            const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
            for (let i = 0; i < q.length; i += 3) for (let a = 0; a < 3; ++a) { lo[a] = Math.min(lo[a], q[i + a]); hi[a] = Math.max(hi[a], q[i + a]); }
            return Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
          };
          const by = (axis) => [...Array(n).keys()].sort((a, b) => p[3 * a + axis] - p[3 * b + axis]);
          const fixed = by(1).slice(0, Math.ceil(n / 20)), isFixed = new Set(fixed);
          const head = by(0).reverse().filter((v) => !isFixed.has(v)).slice(0, Math.ceil(n / 20));
          const restCage = diagonal(app.model.cage.positions);
          await app.setHandles([fixed, head], { moving: [1] });
          await app.drag(1, [0, 0.05 * diagonal(p), 0]);
          return { rest: restCage, deformed: diagonal(app.cagePositions()) };
        });
        assert.ok(deformed <= 1.5 * rest, `the cow's cage grew from diagonal ${rest} to ${deformed}`);
      } else {
        console.log('     (the cow part skipped: ../shared/data is absent)');
      }
      assert.deepEqual(page.errors, []);
    },
  },
];
