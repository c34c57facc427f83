// The control panel follows the app's state and drives the app through its intents (the public API) only: what a
// script changes shows in the panel (options, compare mode, handle groups, volume parts, influence picking, the
// skeleton, stats), what the panel does shows in the app, and disposing the app takes the panel with it.
import assert from 'node:assert/strict';
import { animationFrames, appReady } from './app_probe.mjs';

/** What a named panel row shows: a checkbox's state, a select's or a text field's value. */
function panelValue(page, name) {
  return page.evaluate((name) => {
    const row = [...document.querySelectorAll('.lil-controller')].find((c) => c.querySelector('.lil-name')?.textContent === name);
    if (!row) return undefined;
    const checkbox = row.querySelector('input[type=checkbox]');
    if (checkbox) return checkbox.checked;
    const select = row.querySelector('select');
    if (select) return select.options[select.selectedIndex]?.textContent;
    return row.querySelector('input')?.value;
  }, name);
}

function row(page, name) {
  return page.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: new RegExp(`^${name}$`) }) });
}

export default [
  {
    name: 'the panel follows scripted changes through events and drives the app through its API',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      // Script -> panel: options, handle groups, compare mode.
      await page.evaluate(() => globalThis.subspaceDeformer.setOptions({ wireframe: true, jacobian: 'exact', maxIterations: 42 }));
      assert.equal(await panelValue(page, 'wireframe'), true);
      assert.equal(await panelValue(page, 'Jacobian'), 'exact');
      assert.equal(await panelValue(page, 'max iterations'), '42');
      await page.evaluate(() => globalThis.subspaceDeformer.setHandles([[0, 1], [2], [3, 4]], { moving: [2] }));
      assert.equal(await panelValue(page, 'groups'), '2 fixed, 1 moving');
      assert.equal(await panelValue(page, 'selected'), '0 vertices');
      // Script -> panel: the volume parts' painting, the influence's picking and the skeleton (the state's parts).
      await page.evaluate(() => { const app = globalThis.subspaceDeformer; app.parts.setPainting(true); app.parts.setCurrent(3); app.influence.setPicking(true); });
      assert.deepEqual([await panelValue(page, 'paint parts (P)'), await panelValue(page, 'painted part'), await panelValue(page, 'click a cage vertex (I)')], [true, '3', true]);
      await page.evaluate(() => { const app = globalThis.subspaceDeformer; app.parts.setPainting(false); app.influence.setPicking(false); });
      assert.deepEqual([await panelValue(page, 'paint parts (P)'), await panelValue(page, 'click a cage vertex (I)')], [false, false]);
      await page.evaluate(() => globalThis.subspaceDeformer.skeleton.setEnabled(false));
      assert.equal(await panelValue(page, 'use bones'), false);
      await page.evaluate(() => globalThis.subspaceDeformer.skeleton.setEnabled(true));
      // Panel -> app: buttons and controls call the public API.
      await page.locator('.lil-gui button', { hasText: 'clear groups' }).click();
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.handles.groups.length), 0);
      assert.equal(await panelValue(page, 'groups'), '0 fixed, 0 moving');
      await page.locator('.lil-gui button', { hasText: 'undo (Ctrl+Z)' }).click();
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.handles.groups.length), 3, 'undo brought the groups back');
      await row(page, 'flat shading').locator('input').check();
      await row(page, 'method').locator('select').selectOption('arap');
      const after = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        return { flat: app.settings.flatShading, method: app.settings.method, view: app.views[0].method };
      });
      assert.deepEqual(after, { flat: true, method: 'arap', view: 'arap' });
      // The stats folder follows the solve.
      const stats = await page.evaluate(() => globalThis.subspaceDeformer.drag(2, [0, 0.3, 0]));
      assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
      await page.waitForFunction(() => {
        const rows = [...document.querySelectorAll('.lil-controller')];
        const status = rows.find((c) => c.querySelector('.lil-name')?.textContent === 'status');
        return status?.querySelector('input')?.value === 'converged';
      }, null, { timeout: 5000 });
      // Compare mode set by a script ticks the panel's box; the box switches it off again.
      await page.evaluate(() => globalThis.subspaceDeformer.setCompare(['arap', 'subspace']));
      assert.equal(await panelValue(page, 'compare methods'), true);
      await row(page, 'compare methods').locator('input').uncheck();
      await page.waitForFunction(() => globalThis.subspaceDeformer.views.length === 1);
      await t.screenshot(page, 'panel-events');
      // The app takes its panel along when disposed.
      const left = await page.evaluate(() => {
        globalThis.subspaceDeformer.dispose();
        return { panels: document.querySelectorAll('.lil-gui').length, apps: document.querySelectorAll('.sd-app').length };
      });
      assert.deepEqual(left, { panels: 0, apps: 0 });
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a model from a file is named in the example menu (it no longer goes blank); a closed panel leaves the compare views\' labels free',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const obj = await page.evaluate(() => globalThis.subspaceDeformer.exportObj('mesh'));
      const cage = await page.evaluate(() => globalThis.subspaceDeformer.exportObj('restCage'));
      const [chooser] = await Promise.all([page.waitForEvent('filechooser'), page.evaluate(() => globalThis.subspaceDeformer.openFilePicker())]);
      await chooser.setFiles([{ name: 'mine.obj', mimeType: 'text/plain', buffer: Buffer.from(obj) },
        { name: 'mine_cage.obj', mimeType: 'text/plain', buffer: Buffer.from(cage) }]);
      // The panel follows the app's 'load' event, which comes with the model.
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.name === 'mine.obj', null, { timeout: 30000 });
      assert.equal(await panelValue(page, 'example'), 'mine.obj (file)');
      // Choosing an example from the menu still loads it.
      await row(page, 'example').locator('select').selectOption('sphere');
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.name === 'sphere', null, { timeout: 30000 });
      assert.equal(await panelValue(page, 'example'), 'sphere');
      // Compare mode on a narrow window with the panel closed: no panel header over any label.
      await page.setViewportSize({ width: 900, height: 700 });
      await page.evaluate(() => globalThis.subspaceDeformer.setCompare(true));
      await page.evaluate(() => globalThis.subspaceDeformer.setPanelOpen(false));
      await page.waitForFunction(() => document.querySelectorAll('.sd-label').length === 3);
      await animationFrames(page, 2); // the views are laid out for the closed panel
      const covered = await page.evaluate(() => {
        const panel = document.querySelector('.lil-gui.lil-root');
        const p = panel && panel.offsetParent ? panel.getBoundingClientRect() : null;
        return [...document.querySelectorAll('.sd-label')].map((label) => {
          const r = label.getBoundingClientRect();
          return { text: label.textContent, covered: !!p && r.left < p.right && p.left < r.right && r.top < p.bottom && p.top < r.bottom };
        });
      });
      assert.equal(covered.length, 3);
      for (const label of covered) assert.equal(label.covered, false, `the panel covers "${label.text}"`);
      await t.screenshot(page, 'compare-panel-closed');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'the example and lesson menus show what the app holds after a load cancelled or replaced, and the blank lesson entry is no choice',
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const app = 'globalThis.subspaceDeformer';
      const menu = (name) => page.evaluate((name) => [...document.querySelectorAll('.lil-controller')]
        .find((c) => c.querySelector('.lil-name')?.textContent === name)?.querySelector('select')?.value, name);
      const menuShows = (name, value) => page.waitForFunction(([name, value]) => [...document.querySelectorAll('.lil-controller')]
        .find((c) => c.querySelector('.lil-name')?.textContent === name)?.querySelector('select')?.value === value, [name, value], { timeout: 10000 })
        .catch(async () => assert.fail(`the ${name} menu shows ${await menu(name)}, not ${value}`));
      // A tester chose an example, then Cancel: the menu said the example, the app held the bar.
      await row(page, 'example').locator('select').selectOption('spot');
      await page.locator('.sd-progress button').click();
      await menuShows('example', 'bar');
      assert.equal(await page.evaluate(`${app}.model.name`), 'bar');
      // A lesson replaced at once by an example: the lesson menu said the lesson (and choosing it again did nothing).
      await row(page, 'lesson').locator('select').selectOption('volume');
      await row(page, 'example').locator('select').selectOption('sphere');
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.name === 'sphere', null, { timeout: 30000 });
      await menuShows('lesson', '');
      assert.equal(await page.evaluate(`${app}.lesson`), null);
      assert.equal(await panelValue(page, 'compare methods'), false);
      await row(page, 'lesson').locator('select').selectOption('volume');
      await page.waitForFunction(() => globalThis.subspaceDeformer.lesson?.id === 'volume', null, { timeout: 60000 });
      // The blank entry is no action: the menu goes back to the lesson, which stays.
      await row(page, 'lesson').locator('select').selectOption('');
      await menuShows('lesson', 'volume');
      assert.equal(await page.evaluate(`${app}.lesson.id`), 'volume');
      assert.deepEqual(page.errors, []);
    },
  },
];
