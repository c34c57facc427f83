// What an attack on the app and its URL/embed surface found, each kept as a repro in real Chromium: a bad
// parameter or attribute is named in the banner and its default used (the page used to stay empty), compare
// lists are bounded, a scene that does not fit leaves the user's model and work alone, and the app's own
// settings and edits are checked like the solver's options.
import assert from 'node:assert/strict';
import { animationFrames, appReady } from './app_probe.mjs';

const app = 'globalThis.subspaceDeformer';

const bannerText = (page) => page.evaluate(() => {
  const banner = document.querySelector('.sd-banner');
  return banner && !banner.hidden ? banner.querySelector('.sd-message').textContent : '';
});

// What a rejected call threw, as { name, code, message } (null when it did not throw).
const failure = (page, expression) => page.evaluate(async (expression) => {
  try {
    await (0, eval)(expression);
    return null;
  } catch (error) {
    return { name: error.name, code: error.code, message: error.message };
  }
}, expression);

export default [
  {
    name: 'a bad URL parameter is named in the banner and its default used (?method=ARAP, ?example=__proto__)',
    async run(t) {
      for (const query of ['method=ARAP&example=__proto__', 'method=arap%20&example=constructor']) {
        const page = await t.page(`index.html?${query}`);
        await appReady(page);
        const got = await page.evaluate(() => {
          const a = globalThis.subspaceDeformer;
          return { model: a.model.name, method: a.views[0].method, ignored: a.ignoredOptions, views: document.querySelectorAll('canvas.sd-canvas').length };
        });
        assert.equal(got.model, 'bar', 'the default example');
        assert.equal(got.method, 'subspace', 'the default method');
        assert.equal(got.views, 1);
        assert.equal(got.ignored.length, 2, got.ignored.join('\n'));
        const banner = await bannerText(page);
        assert.match(banner, /^Ignored:\n/);
        assert.match(banner, /method must be one of 'subspace', 'full', 'arap' \(got "arap? ?"?|method must be one of/);
        assert.match(banner, /example must be a built-in example/);
        assert.deepEqual(page.errors, []);
        await t.screenshot(page, 'bad-url-parameter');
        await page.close();
      }
    },
  },
  {
    name: 'compare with 50 entries opens each method once',
    async run(t) {
      const list = Array.from({ length: 50 }, (_, i) => ['arap', 'subspace', 'full'][i % 3]).join(',');
      const page = await t.page(`index.html?compare=${list}`);
      await appReady(page);
      await page.evaluate(`${app}.solve()`);
      assert.deepEqual(await page.evaluate(`${app}.views.map((v) => v.method)`), ['arap', 'subspace', 'full']);
      const bad = await failure(page, `${app}.setCompare(['arap', 'nope'])`);
      assert.deepEqual(bad, { name: 'InputError', code: 'invalid_argument', message: 'setCompare: "nope" is no method (methods: subspace, full, arap)' });
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: '<subspace-deformer method="nope">: the banner says so, ready resolves with the default, the API works',
    async run(t) {
      const html = '<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,">' +
        '<script type="module" src="subspace-deformer.js"></script></head><body>' +
        '<subspace-deformer id="e" method="nope" compare="arap,bogus,arap" panel="none" style="height: 300px"></subspace-deformer></body></html>';
      const page = await t.page(null);
      await page.route('**/nope-embed.html', (route) => route.fulfill({ contentType: 'text/html', body: html }));
      await page.goto(`${t.url}nope-embed.html`);
      const el = "document.getElementById('e')";
      await appReady(page, `${el}.app`);
      const stats = await page.evaluate(`${el}.statsAll().map((s) => s.method)`);
      assert.deepEqual(stats, ['arap']);
      const banner = await bannerText(page);
      assert.match(banner, /method must be one of 'subspace', 'full', 'arap' \(got "nope"\)/);
      assert.match(banner, /"bogus" is no method/);
      // An element that is not in the document has no app: its API says so by name.
      const detached = await failure(page, "document.createElement('subspace-deformer').statsAll()");
      assert.equal(detached.name, 'InputError');
      assert.match(detached.message, /is not in the document/);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a scene whose handles, parts or generated cage do not fit its model leaves the current model, handles and settings as they were',
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      await page.evaluate(`${app}.drag(1, [0, 0.4, 0])`);
      const state = () => page.evaluate(() => {
        const a = globalThis.subspaceDeformer;
        return { model: a.model.name, handles: JSON.stringify(a.handles.toScene()), maxIterations: a.settings.maxIterations,
          basis: a.settings.basis, positions: Array.from(a.positions().slice(0, 6)) };
      });
      const before = await state();
      for (const scene of [
        { example: 'sphere', handles: [{ vertices: [99999] }], solver: { maxIterations: 7 } },
        { example: 'sphere', handles: [], volumeParts: { triangles: [[999999]] }, solver: { maxIterations: 7 } },
        { example: 'sphere', handles: [], subspace: { basis: 'spectral', modes: 10 }, volumeParts: { vertices: [[0], [99999]] } },
        { handles: [{ vertices: [99999] }], solver: { maxIterations: 7 } }, // no model: applies to the current one
      ]) {
        const error = await failure(page, `${app}.loadScene(${JSON.stringify(scene)})`);
        assert.equal(error?.name, 'InputError', JSON.stringify(scene));
        assert.match(error.message, /99999|999999/);
        assert.deepEqual(await state(), before, JSON.stringify(scene));
        assert.match(await bannerText(page), /99999/);
      }
      // An example with a generated cage that cannot be made (4 vertices around the bar): the cage is generated in
      // the same binding as the example, so the failure leaves the user's model (it used to be replaced first).
      const cage = await failure(page, `${app}.loadScene(${JSON.stringify({ example: 'bar', generateCage: { vertices: 4 },
        handles: [{ vertices: [0] }], solver: { maxIterations: 7 } })})`);
      assert.equal(cage?.code, 'cage_failed', JSON.stringify(cage));
      assert.deepEqual(await state(), before);
      assert.match(await bannerText(page), /no valid cage of 4 vertices/);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'compare mode: Cancel while the second view binds leaves every view on the previous model (all views or none)',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html?compare=subspace,arap');
      await appReady(page);
      await page.evaluate(`${app}.drag(1, [0, 0.4, 0])`);
      const state = () => page.evaluate(() => {
        const a = globalThis.subspaceDeformer;
        return { model: a.model.name, views: a.views.map((v) => v.session.model?.name), handles: JSON.stringify(a.handles.toScene()) };
      });
      const before = await state();
      assert.deepEqual(before.views, ['bar', 'bar']);
      // The first view has bound the sphere once the second starts binding it; Cancel then.
      const error = await page.evaluate(async () => {
        const a = globalThis.subspaceDeformer;
        const loading = a.loadExample('sphere').then(() => null, (e) => e.name);
        while (!a.views[1].session.loading) await new Promise((resolve) => setTimeout(resolve, 1));
        a.cancelLoad();
        return loading;
      });
      assert.equal(error, 'CancelledError');
      assert.deepEqual(await state(), before);
      // Both views still solve the user's model and its handles.
      const stats = await page.evaluate(`${app}.drag(1, [0, 0.3, 0]).then(() => ${app}.statsAll().map((s) => s.converged))`);
      assert.deepEqual(stats, [true, true]);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'the app\'s own settings and edits are checked: gizmoMode "fly", a NaN drag, a bad moving index',
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const fly = await failure(page, `${app}.setOptions({ gizmoMode: 'fly' })`);
      assert.deepEqual(fly, { name: 'InputError', code: 'invalid_argument', message: `setOptions: gizmoMode must be one of 'translate', 'rotate' (got "fly")` });
      const nan = await failure(page, `${app}.drag(1, [NaN, 0, 0])`);
      assert.equal(nan.name, 'InputError');
      const moving = await failure(page, `${app}.setHandles([[0, 1], [5]], { moving: [3] })`);
      assert.match(moving.message, /moving must list group indices from 0 to 1/);
      const stats = await page.evaluate(`${app}.drag(1, [0, 0.3, 0])`);
      assert.equal(stats.converged, true);
      const scene = await page.evaluate(`${app}.sceneJson()`);
      assert.ok(!JSON.stringify(scene).includes('null'), JSON.stringify(scene.handles));
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a failed first load from a URL leaves no uncaught promise rejection',
    async run(t) {
      const page = await t.page(null);
      await page.goto(`${t.url}index.html?mesh=missing.obj&cage=missing_cage.obj`);
      await page.waitForFunction(() => /no model loaded/.test(document.querySelector('.sd-stats')?.textContent));
      // The load has failed; a rejection nobody handled would be reported within the next task.
      await page.evaluate(`${app}.ready.catch(() => {})`);
      await animationFrames(page, 2);
      const unexpected = page.errors.filter((e) => !/missing(_cage)?\.obj|404|Failed to load resource/.test(e));
      assert.deepEqual(unexpected, []);
    },
  },
];
