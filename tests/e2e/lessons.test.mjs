// The built-in lessons in the app and the embed: ?lesson= and lesson="..." load the scene, the views it
// compares, its camera and its caption; the solves reproduce the caption (ARAP loses volume where the subspace
// keeps it; every part keeps its volume); the panel's lesson menu switches lessons; a mistyped name falls back
// to the default example and says why; Spot, the built-in example, is seen from the front.
import assert from 'node:assert/strict';
import { appReady, embedPage } from './app_probe.mjs';

const app = 'globalThis.subspaceDeformer';

/** The direction the first view's camera looks along, normalized. */
function viewDirection(page, get = app) {
  return page.evaluate((get) => {
    const a = new Function(`return ${get}`)();
    return a.views[0].viewport.viewDirection().toArray();
  }, get);
}

function unit(v) {
  const n = Math.hypot(...v);
  return v.map((x) => x / n);
}

export default [
  {
    // Its caption says to press step: it used to say "pause, then step" while both solves ran to convergence, and
    // restart un-paused them.
    name: '?lesson=subspace-vs-full starts paused at rest, as its caption says; step runs one iteration in each view; restart is paused again',
    timeout: 120000,
    async run(t) {
      const page = await t.page('index.html?lesson=subspace-vs-full');
      await appReady(page);
      await page.waitForFunction(() => globalThis.subspaceDeformer.lesson?.id === 'subspace-vs-full', null, { timeout: 90000 });
      const at = () => page.evaluate(`${app}.statsAll().map((s) => s.state + ' ' + s.iterations)`);
      assert.match(await page.locator('.sd-lesson').textContent(), /starts paused at rest: press step \(N\)/);
      assert.equal(await page.evaluate(`${app}.stepping.paused`), true);
      assert.deepEqual(await at(), ['paused 0', 'paused 0']);
      await page.locator('[data-action=next]').click();
      await page.waitForFunction(() => globalThis.subspaceDeformer.statsAll().every((s) => s.iterations === 1), null, { timeout: 60000 });
      await page.locator('.sd-lesson-restart').click();
      await page.waitForFunction(() => globalThis.subspaceDeformer.statsAll().every((s) => s.iterations === 0), null, { timeout: 60000 });
      await page.waitForFunction(() => globalThis.subspaceDeformer.lesson?.id === 'subspace-vs-full', null, { timeout: 60000 });
      assert.equal(await page.evaluate(`${app}.stepping.paused`), true, 'restart: paused again');
      assert.deepEqual(await at(), ['paused 0', 'paused 0']);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: '?lesson=arap-vs-subspace: ARAP | subspace with the caption; ARAP loses more than a quarter of the volume, the subspace keeps it',
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html?lesson=arap-vs-subspace');
      await appReady(page);
      const lesson = await page.evaluate(`${app}.lesson`);
      assert.equal(lesson.id, 'arap-vs-subspace');
      assert.deepEqual(await page.evaluate(`${app}.views.map((v) => v.method)`), ['arap', 'subspace']);
      assert.match(await page.locator('.sd-lesson-title').textContent(), /ARAP against the subspace on a large rotation/);
      assert.match(await page.locator('.sd-lesson-caption').textContent(), /more than a quarter of its volume/);
      const [arap, subspace] = await page.evaluate(`${app}.solve().then(() => ${app}.statsAll())`);
      assert.equal(subspace.state, 'converged');
      assert.ok(Math.abs(subspace.volumeRelError) < 1e-6, `subspace volume ${subspace.volumeRelError}`);
      assert.ok(arap.volumeRelError < -0.25, `ARAP volume ${arap.volumeRelError}`);
      await t.screenshot(page, 'lesson-arap-vs-subspace');
      // The title folds the caption away; the panel's menu loads another lesson (one view, parts coloured).
      await page.locator('.sd-lesson-title').click();
      assert.equal(await page.locator('.sd-lesson-caption').isVisible(), false);
      await page.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: /^lesson$/ }) }).locator('select').selectOption('volume-parts');
      await page.waitForFunction(() => globalThis.subspaceDeformer.lesson?.id === 'volume-parts', null, { timeout: 60000 });
      const stats = await page.evaluate(`${app}.solve()`);
      assert.equal(await page.evaluate(`${app}.views.length`), 1);
      assert.equal(stats.partVolumeChange.length, 6);
      assert.ok(Math.max(...stats.partVolumeChange.map(Math.abs)) < 1e-6, `part changes ${stats.partVolumeChange}`);
      assert.match(await page.locator('.sd-lesson-caption').textContent(), /6 coloured parts/);
      // The camera looks at Spot's side, as the lesson says.
      const seen = await viewDirection(page);
      const wanted = unit([-1, -0.35, 0.25]);
      assert.ok(seen.reduce((s, x, i) => s + x * wanted[i], 0) > 0.999, `view direction ${seen}`);
      await t.screenshot(page, 'lesson-volume-parts');
      // Another model ends the lesson: no caption any more.
      await page.evaluate(`${app}.loadExample('sphere')`);
      assert.equal(await page.evaluate(`${app}.lesson`), null);
      assert.equal(await page.locator('.sd-lesson').isVisible(), false);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: '<subspace-deformer lesson="volume">: Spot from its side, ARAP gains volume, the subspace keeps it; restart loads it again',
    timeout: 90000,
    async run(t) {
      const { page, el } = await embedPage(t, 'lesson="volume"', { name: 'lesson-page.html', height: 480 });
      assert.equal(await page.evaluate(`${el}.lesson.id`), 'volume');
      assert.equal(await page.evaluate(`${el}.app.model.name`), 'spot');
      const [arap, subspace] = await page.evaluate(`${el}.solve().then(() => ${el}.statsAll())`);
      assert.ok(arap.volumeRelError > 0.03, `ARAP volume ${arap.volumeRelError}`);
      assert.ok(Math.abs(subspace.volumeRelError) < 1e-6, `subspace volume ${subspace.volumeRelError}`);
      await t.screenshot(page, 'lesson-embed-volume');
      // Moving the handle away, then restart: the lesson's own handles come back.
      const before = await page.evaluate(`${el}.app.handles.groups[1].translate`);
      await page.evaluate(`${el}.drag(1, [0, 0, 0])`);
      await page.locator('.sd-lesson-restart').click();
      await page.waitForFunction((el) => new Function(`return ${el}`)().app.handles.groups[1]?.translate[1] > 0, el, { timeout: 60000 });
      assert.deepEqual(await page.evaluate(`${el}.app.handles.groups[1].translate`), before);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a mistyped lesson name: the default example and a banner naming the lessons; Spot loads seen from the front',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html?lesson=nope');
      await appReady(page);
      assert.equal(await page.evaluate(`${app}.model.name`), 'bar');
      const banner = await page.evaluate(`${app}.banner.text`);
      assert.match(banner, /lesson must be a built-in lesson: subspace-vs-full, arap-vs-subspace, volume, spectral, volume-parts/);
      assert.match(banner, /"nope"/);
      await page.evaluate(`${app}.loadExample('spot')`);
      // Spot faces -z: the camera looks along +z (from in front of it), not along -z (at its back).
      const seen = await viewDirection(page);
      assert.ok(seen[2] > 0.5, `Spot is seen along ${seen.map((x) => x.toFixed(2))}`);
      await t.screenshot(page, 'spot-front');
      assert.deepEqual(page.errors.filter((e) => !/nope/.test(e)), []);
    },
  },
  {
    name: 'the open panel leaves the lesson bar free: restart is reachable and the caption is not under the panel (desktop, tablet, phone in landscape)',
    timeout: 90000,
    async run(t) {
      // A tester found restart under the open panel at 1280x800, and the caption running under it.
      const page = await t.page('index.html?lesson=volume');
      await appReady(page);
      for (const [width, height] of [[1280, 800], [820, 1180], [844, 390]]) {
        await page.setViewportSize({ width, height });
        await page.evaluate(`${app}.setPanelOpen(true)`);
        await page.waitForFunction(() => document.querySelector('.lil-gui.lil-root')?.getBoundingClientRect().width > 0);
        const seen = await page.evaluate(() => {
          const restart = document.querySelector('.sd-lesson-restart').getBoundingClientRect();
          const top = document.elementFromPoint(restart.x + restart.width / 2, restart.y + restart.height / 2);
          return { restart: !!top?.closest('.sd-lesson-restart'), captionRight: document.querySelector('.sd-lesson-caption').getBoundingClientRect().right,
            panelLeft: document.querySelector('.lil-gui.lil-root').getBoundingClientRect().left };
        });
        assert.ok(seen.restart, `${width}x${height}: restart is covered`);
        assert.ok(seen.captionRight <= seen.panelLeft + 0.5, `${width}x${height}: the caption ends at ${seen.captionRight}, the panel starts at ${seen.panelLeft}`);
        await t.screenshot(page, `lesson-bar-panel-${width}x${height}`);
      }
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a scene saved in compare mode names the panel\'s method and the methods compared; loading it shows them again',
    timeout: 90000,
    async run(t) {
      // A tester saved the volume lesson (ARAP | subspace, method subspace): the scene said method arap with ARAP's
      // cap, and loading it showed ARAP alone.
      const page = await t.page('index.html?lesson=volume');
      await appReady(page);
      const scene = await page.evaluate(`${app}.sceneJson()`);
      assert.equal(scene.solver.method, 'subspace');
      assert.equal(scene.solver.maxIterations, 100);
      assert.deepEqual(scene.view, { compare: ['arap', 'subspace'] });
      const again = await t.page('index.html');
      await appReady(again);
      await again.evaluate((scene) => globalThis.subspaceDeformer.loadScene(scene), scene);
      await again.evaluate(`${app}.solve()`);
      assert.deepEqual(await again.evaluate(`${app}.views.map((v) => v.method)`), ['arap', 'subspace']);
      assert.equal(await again.evaluate(`${app}.settings.method`), 'subspace');
      assert.deepEqual(await again.evaluate(`${app}.sceneJson()`), scene);
      assert.deepEqual([...page.errors, ...again.errors], []);
    },
  },
  {
    name: 'restart and the next lesson start from the app\'s solver settings, not the ones changed before; a lesson replaced at once changes nothing',
    timeout: 90000,
    async run(t) {
      // A tester unticked "volume constraint" as the volume lesson says, then restart: still unticked, and so in the next
      // lesson; a lesson chosen, then an example 50 ms later: the example came up in the lesson's compare views.
      const page = await t.page('index.html?lesson=volume');
      await appReady(page);
      // A lesson starts a fresh undo history: undo went to Spot's default groups, never on screen.
      const undoable = () => page.evaluate(() => !document.querySelector('[data-action=undo]').disabled);
      assert.equal(await undoable(), false, 'nothing to undo after a lesson loads');
      await page.evaluate(`${app}.setOptions({ volume: false, maxIterations: 200, wireframe: true })`);
      await page.locator('.sd-lesson-restart').click();
      await page.waitForFunction(() => globalThis.subspaceDeformer.settings.volume === true, null, { timeout: 60000 });
      await page.waitForFunction(() => globalThis.subspaceDeformer.lesson?.id === 'volume', null, { timeout: 60000 });
      assert.deepEqual(await page.evaluate(`[${app}.settings.maxIterations, ${app}.settings.wireframe]`), [100, true]); // display stays
      assert.equal(await undoable(), false, 'nothing to undo after a restart');
      await page.evaluate(`${app}.loadExample('bar')`);
      assert.equal(await page.evaluate(`${app}.lesson`), null);
      await page.evaluate(`${app}.setCompare(false)`);
      const views = await page.evaluate(async () => {
        const a = globalThis.subspaceDeformer;
        const lesson = a.loadLesson('volume').catch((error) => error.name);
        await new Promise((r) => setTimeout(r, 50));
        await a.loadExample('sphere');
        return { lesson: await lesson, model: a.model.name, views: a.views.map((v) => v.key), compare: a.compare };
      });
      assert.deepEqual(views, { lesson: 'CancelledError', model: 'sphere', views: ['subspace'], compare: false });
      assert.deepEqual(page.errors, []);
    },
  },
];
