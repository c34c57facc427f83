// The spectral basis and the volume parts in the app (docs/method.md sections 15-16): the basis control
// rebinds the model and it still deforms with the volume kept; a lone mesh deforms at once without a cage
// from the banner's offer; automatic and painted parts keep every part's volume, shown as colours, and a
// saved scene carries the basis and the parts.
import assert from 'node:assert/strict';
import { VOLUME_TOLERANCE } from './geometry.mjs';
import { ellipsoidObj } from './geometry.mjs';
import { appReady, appShown } from './app_probe.mjs';

const app = 'globalThis.subspaceDeformer';

export default [
  {
    name: 'the basis control binds the spectral basis; auto and painted parts keep each part\'s volume',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      // The panel's "subspace basis" control binds the model again with the spectral basis, handles kept.
      const groupsBefore = await page.evaluate(`${app}.handles.groups.length`);
      const row = page.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: /^subspace basis$/ }) });
      await row.locator('select').selectOption('spectral');
      await page.waitForFunction(`${app}.model?.basis === 'spectral'`, null, { timeout: 30000 });
      const bound = await page.evaluate(`({ size: ${app}.model.basisSize, groups: ${app}.handles.groups.length, modes: ${app}.settings.spectralModes })`);
      assert.equal(bound.size, bound.modes + 4, 'the spectral basis has modes + 4 columns');
      assert.equal(bound.groups, groupsBefore, 'the handles stay');
      let stats = await page.evaluate(`${app}.drag(1, [0, -0.8, 0.2])`);
      assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
      assert.equal(stats.basis, 'spectral');
      assert.ok(Math.abs(stats.volumeRelError) <= VOLUME_TOLERANCE, `volume error ${stats.volumeRelError}`);
      // The plot and the label name the spectral basis, not the cage.
      await page.waitForFunction(`${app}.views[0].viewport.plot.shown?.label === 'Subspace (spectral, ${bound.modes} modes)'`, null, { timeout: 5000 });
      assert.match(await page.locator('.sd-model').textContent(), new RegExp(`spectral basis, ${bound.modes} modes`));
      // Automatic parts: the solver keeps each part's volume; the mesh shows them as colours.
      const count = await page.evaluate(`${app}.parts.auto(3)`);
      assert.equal(count, 3);
      stats = await page.evaluate(`${app}.solve()`);
      assert.equal(stats.partVolumeChange.length, 3);
      for (const change of stats.partVolumeChange) assert.ok(Math.abs(change) <= VOLUME_TOLERANCE, `part change ${change}`);
      assert.ok(await page.evaluate(`!!${app}.views[0].viewport.meshView.geometry.attributes.color`), 'parts are coloured');
      await appShown(page);
      await t.screenshot(page, 'parts-auto');
      // Painting: P turns painting on, a brush stroke paints part 1 (not the handle selection).
      await page.evaluate(`${app}.parts.clear()`);
      await page.locator('.sd-canvas').first().click({ position: { x: 5, y: 5 } });
      await page.keyboard.press('p');
      assert.equal(await page.evaluate(`${app}.parts.painting`), true);
      await page.evaluate(`${app}.parts.setCurrent(1)`);
      const box = await page.locator('.sd-canvas').first().boundingBox();
      const x = box.x + box.width / 2, y = box.y + box.height / 2;
      await page.keyboard.down('Shift');
      await page.mouse.move(x - 40, y);
      await page.mouse.down();
      for (let i = 0; i <= 8; ++i) await page.mouse.move(x - 40 + 10 * i, y);
      await page.mouse.up();
      await page.keyboard.up('Shift');
      const painted = await page.evaluate(`${app}.parts.painter.vertexPart.filter((p) => p === 1).length`);
      assert.ok(painted > 3, `the brush painted ${painted} vertices`);
      assert.equal(await page.evaluate(`${app}.selection.size`), 0, 'painting selects no handle vertices');
      assert.equal(await page.evaluate(`${app}.parts.apply()`), 2, 'the painted part and the rest');
      stats = await page.evaluate(`${app}.solve()`);
      for (const change of stats.partVolumeChange) assert.ok(Math.abs(change) <= VOLUME_TOLERANCE, `part change ${change}`);
      const scene = await page.evaluate(`${app}.sceneJson()`);
      assert.deepEqual(scene.subspace, { basis: 'spectral', modes: bound.modes });
      assert.equal(scene.volumeParts.vertices.length, 1, 'the saved scene lists the painted part');
      await page.keyboard.press('p');
      assert.equal(await page.evaluate(`${app}.parts.painting`), false);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a lone mesh deforms at once with the spectral basis, offered beside "Generate cage"',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      // The current example's mesh alone, as a picked file.
      const obj = await page.evaluate(async () => globalThis.subspaceDeformer.exportObj('mesh'));
      const [chooser] = await Promise.all([page.waitForEvent('filechooser'), page.evaluate(() => globalThis.subspaceDeformer.openFilePicker())]);
      await chooser.setFiles([{ name: 'lone.obj', mimeType: 'text/plain', buffer: Buffer.from(obj) }]);
      await page.waitForFunction(() => /lone\.obj has no cage/.test(document.querySelector('.sd-banner').textContent));
      const banner = page.locator('.sd-banner');
      assert.equal(await banner.getByRole('button', { name: 'Generate cage' }).count(), 1);
      await banner.locator('input[type=number]').nth(1).fill('20');
      await banner.getByRole('button', { name: 'Deform without a cage (spectral basis)' }).click();
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.name === 'lone.obj', null, { timeout: 30000 });
      const info = await page.evaluate(`({ basis: ${app}.model.basis, size: ${app}.model.basisSize, cage: ${app}.model.cage.positions.length })`);
      assert.deepEqual(info, { basis: 'spectral', size: 24, cage: 0 });
      const stats = await page.evaluate(`${app}.drag(1, [0, 0.8, 0])`);
      assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
      assert.ok(Math.abs(stats.volumeRelError) <= VOLUME_TOLERANCE);
      // Back to the cage basis: a lone mesh has none, so that fails in the banner and nothing changes.
      const back = await page.evaluate(`${app}.setBasis('cage').then(() => 'bound', (e) => e.code)`);
      assert.equal(back, 'no_cage');
      assert.deepEqual(await page.evaluate(`[${app}.settings.basis, ${app}.model.basis]`), ['spectral', 'spectral']);
      await appShown(page);
      await t.screenshot(page, 'spectral-lone-mesh');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'the spectral basis over its memory budget: the banner retries with fewer modes, and the setting drops so a new load does not repeat the refusal',
    timeout: 120000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      // A closed ellipsoid of 94,802 vertices: 300 modes need about 1.15 GB (eigenvectors, Lanczos basis, B),
      // over the 1 GiB budget; the refusal comes before any computation.
      const obj = ellipsoidObj(400, 238);
      const [chooser] = await Promise.all([page.waitForEvent('filechooser'), page.evaluate(() => globalThis.subspaceDeformer.openFilePicker())]);
      await chooser.setFiles([{ name: 'big.obj', mimeType: 'text/plain', buffer: Buffer.from(obj) }]);
      await page.waitForFunction(() => /big\.obj has no cage/.test(document.querySelector('.sd-banner').textContent), null, { timeout: 60000 });
      const banner = page.locator('.sd-banner');
      await banner.locator('label', { hasText: 'modes' }).locator('input').fill('300');
      await banner.getByRole('button', { name: 'Deform without a cage (spectral basis)' }).click();
      await page.waitForFunction(() => /use fewer modes/.test(document.querySelector('.sd-banner').textContent), null, { timeout: 60000 });
      assert.equal(await page.evaluate(`${app}.model.name`), 'bar', 'the previous model is kept');
      assert.equal(await page.evaluate(`${app}.settings.spectralModes`), 150, 'the setting dropped to the offer');
      const field = banner.locator('label', { hasText: 'modes' }).locator('input');
      assert.equal(await field.inputValue(), '150');
      await t.screenshot(page, 'spectral-over-budget');
      // Retry with few modes (quick): the mesh deforms in its spectral basis.
      await field.fill('4');
      await banner.getByRole('button', { name: 'Retry with fewer modes' }).click();
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.name === 'big.obj', null, { timeout: 90000 });
      const model = await page.evaluate(`({ basis: ${app}.model.basis, size: ${app}.model.basisSize, modes: ${app}.settings.spectralModes })`);
      assert.deepEqual(model, { basis: 'spectral', size: 8, modes: 4 });
      assert.deepEqual(page.errors.filter((e) => !/big\.obj/.test(e)), []);
    },
  },
];
