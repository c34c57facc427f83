// Cage coordinates in the app (docs/method.md sections 2, 18, 19; docs/app.md): the coordinates control binds
// the model again with handles kept and it still deforms; the influence view colours the mesh by a clicked cage
// vertex's weight, negative weights in blue with the scale in a legend; "compare coordinates" shows mean value
// and harmonic coordinates side by side on one scale; a saved scene carries the coordinates.
import assert from 'node:assert/strict';
import { appReady, appShown } from './app_probe.mjs';
import { VOLUME_TOLERANCE } from './geometry.mjs';

const app = 'globalThis.subspaceDeformer';

// Where cage vertex j of view `view` is drawn, in page coordinates (the camera's projection, computed here).
function cageVertexOnScreen(page, view, j) {
  return page.evaluate(([view, j]) => {
    const v = globalThis.subspaceDeformer.views[view].viewport;
    const p = v.cageView.geometry.attributes.position.array;
    v.camera.updateMatrixWorld();
    const apply = (m, x) => [0, 1, 2, 3].map((r) => m[r] * x[0] + m[4 + r] * x[1] + m[8 + r] * x[2] + m[12 + r] * x[3]);
    const eye = apply(v.camera.matrixWorldInverse.elements, [p[3 * j], p[3 * j + 1], p[3 * j + 2], 1]);
    const clip = apply(v.camera.projectionMatrix.elements, eye);
    const rect = v.canvas.getBoundingClientRect();
    return { x: rect.left + ((clip[0] / clip[3] + 1) / 2) * rect.width, y: rect.top + ((1 - clip[1] / clip[3]) / 2) * rect.height };
  }, [view, j]);
}

// Vertices coloured as negative (blue: more blue than red) in view `view`.
function blueVertices(page, view) {
  return page.evaluate((view) => {
    const color = globalThis.subspaceDeformer.views[view].viewport.meshView.geometry.attributes.color;
    if (!color) return -1;
    let blue = 0;
    for (let i = 0; i < color.count; ++i) if (color.getZ(i) > color.getX(i) + 0.05) ++blue;
    return blue;
  }, view);
}

// The C's inner cage vertex whose mean value weights are the most negative (tests/js/coordinates.test.js
// measured it: -0.008 on 40% of the mesh).
const VERTEX = 51;

export default [
  {
    name: 'cage coordinates: the control rebinds and deforms; the influence of a clicked cage vertex, mean value beside harmonic',
    timeout: 120000,
    async run(t) {
      // ?coordinates= chooses the first binding's coordinates.
      const page = await t.page('index.html?example=c-bar&coordinates=harmonic');
      await appReady(page);
      assert.equal(await page.evaluate(`${app}.model.coordinates.coordinates`), 'harmonic');
      const groupsBefore = await page.evaluate(`${app}.handles.groups.length`);
      // The panel's "cage coordinates" control binds the model again with positive mean value coordinates.
      const row = page.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: /^cage coordinates$/ }) });
      await row.locator('select').selectOption({ label: 'positive mean value (pmvc)' });
      await page.waitForFunction(`${app}.model?.coordinates?.coordinates === 'pmvc'`, null, { timeout: 60000 });
      assert.equal(await page.evaluate(`${app}.handles.groups.length`), groupsBefore, 'the handles stay');
      assert.ok(await page.evaluate(`${app}.model.coordinates.minWeight >= 0`), 'positive mean value weights are >= 0');
      await page.waitForFunction(() => document.querySelector('.sd-model').textContent.includes('pmvc coordinates'));
      assert.equal(await page.evaluate(`${app}.settings.coordinates`), 'pmvc', 'the settings take what was bound');
      // A bad type is refused before anything binds: the model and the settings stay.
      const refused = await page.evaluate(`${app}.setCoordinates('nope').then(() => 'bound', (e) => [e.name, e.message])`);
      assert.deepEqual(refused[0], 'InputError');
      assert.match(refused[1], /^setOptions: /);
      assert.equal(await page.evaluate(`${app}.settings.coordinates + ' ' + ${app}.model.coordinates.coordinates`), 'pmvc pmvc');
      // A binding chosen in the panel and cancelled before it ends: the control shows again what is in effect.
      await row.locator('select').selectOption({ label: 'harmonic (harmonic)' });
      await page.evaluate(`${app}.cancelLoad()`);
      await page.waitForFunction((label) => [...document.querySelectorAll('.lil-controller')]
        .find((c) => c.querySelector('.lil-name')?.textContent === 'cage coordinates')
        ?.querySelector('select option:checked')?.textContent === label, 'positive mean value (pmvc)', { timeout: 15000 });
      assert.equal(await page.evaluate(`${app}.settings.coordinates + ' ' + ${app}.model.coordinates.coordinates`), 'pmvc pmvc');
      const stats = await page.evaluate(`${app}.drag(1, [0.3, 0.3, 0])`);
      assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
      assert.ok(Math.abs(stats.volumeRelError) <= VOLUME_TOLERANCE, `volume error ${stats.volumeRelError}`);
      // A saved scene names the coordinates.
      const scene = await page.evaluate(`${app}.sceneJson()`);
      assert.deepEqual(scene.subspace, { basis: 'cage', coordinates: 'pmvc', pmvcResolution: 32 });

      // Back to mean value coordinates, then "compare coordinates" with harmonic ones beside them.
      await page.evaluate(`${app}.setCoordinates('mvc')`);
      await page.evaluate(`${app}.setOptions({ compareCoordinates: 'harmonic' })`);
      await page.evaluate(`${app}.setCompare('coordinates')`);
      const views = await page.evaluate(`${app}.views.map((v) => [v.key, v.session.model?.coordinates?.coordinates])`);
      assert.deepEqual(views, [['subspace:mvc', 'mvc'], ['subspace:harmonic', 'harmonic']]);
      const labels = await page.locator('.sd-label').allTextContents();
      assert.deepEqual(labels, ['Subspace (mean value coordinates)', 'Subspace (harmonic coordinates)']);
      await page.evaluate(`${app}.solve()`);

      // I turns picking on; a click next to cage vertex VERTEX in the left view shows its influence in both.
      await page.locator('.sd-canvas').first().click({ position: { x: 5, y: 5 } });
      await page.keyboard.press('i');
      assert.equal(await page.evaluate(`${app}.influence.picking`), true);
      const at = await cageVertexOnScreen(page, 0, VERTEX);
      await page.mouse.click(at.x + 3, at.y - 2);
      await page.waitForFunction(`${app}.influence.column === ${VERTEX}`, null, { timeout: 15000 });
      assert.equal(await page.evaluate(`${app}.selection.size`), 0, 'picking selects no handle vertices');
      const legends = await page.locator('.sd-influence').evaluateAll((els) => els.map((e) => ({ hidden: e.hidden, text: e.textContent })));
      assert.equal(legends.length, 2);
      assert.ok(legends.every((l) => !l.hidden), 'both views show a legend');
      assert.match(legends[0].text, new RegExp(`cage vertex ${VERTEX} \u00b7 mean value coordinates`));
      assert.match(legends[0].text, /vertices \([\d.]+%\) negative, down to \u2212/);
      assert.match(legends[1].text, /harmonic coordinates/);
      assert.match(legends[1].text, /no negative weight/);
      const scale = await page.evaluate(`${app}.influence.scale`);
      assert.ok(scale.min < 0 && scale.max > 0, `one shared scale with negatives: ${JSON.stringify(scale)}`);
      const blue = [await blueVertices(page, 0), await blueVertices(page, 1)];
      assert.ok(blue[0] > 100, `mean value coordinates: ${blue[0]} vertices drawn negative`);
      assert.equal(blue[1], 0, 'harmonic coordinates: none drawn negative');
      await appShown(page);
      await t.screenshot(page, 'influence-mvc-harmonic');

      // Hidden again: the plain colour; picking off gives the handle selection back.
      await page.evaluate(`${app}.influence.hide()`);
      assert.equal(await blueVertices(page, 0), -1, 'no vertex colours once hidden');
      await page.keyboard.press('i');
      assert.equal(await page.evaluate(`${app}.views[0].picker.enabled`), true);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    // A tester ticked "compare coordinates" with a harmonic grid of 256 (refused: too much work) and got a second
    // view with no mesh, the box ticked, while solve() resolved "converged".
    name: 'compare coordinates refused by the worker: back to one view, the box unticked, the banner says why',
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html?example=bar');
      await appReady(page);
      await page.evaluate(`${app}.setOptions({ harmonicResolution: 256, compareCoordinates: 'harmonic' })`);
      const row = page.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: /^compare coordinates$/ }) });
      await row.locator('input').click();
      await page.waitForFunction(`${app}.banner.text?.startsWith('Compare views not shown: harmonic coordinates')`, null, { timeout: 60000 });
      assert.deepEqual(await page.evaluate(`${app}.views.map((v) => v.key)`), ['subspace']);
      assert.equal(await row.locator('input').isChecked(), false, 'the box unticks');
      assert.equal(await page.evaluate(`${app}.views.every((v) => !!v.session.model)`), true, 'no view without a model');
      const refused = await page.evaluate(`${app}.setCompare('coordinates').then(() => 'shown', (e) => e.message)`);
      assert.match(refused, /^harmonic coordinates: factoring the grid/, 'setCompare rejects with the reason');
      assert.deepEqual(await page.evaluate(`${app}.views.map((v) => v.key)`), ['subspace']);
      const stats = await page.evaluate(`${app}.drag(1, [0, 0.3, 0])`);
      assert.equal(stats.state, 'converged');
      assert.equal(stats.vertexCount, 5042);
      assert.deepEqual(page.errors, []);
    },
  },
];
