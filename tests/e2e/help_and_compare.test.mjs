// Two small things a user hit (issue 31, item 4): the help card is modal (a press beside it closes it instead of
// dragging the model underneath) and closes with Escape; a page opened with ?compare=coordinates ticks "compare
// coordinates", not "compare methods".
import assert from 'node:assert/strict';
import { appReady } from './app_probe.mjs';

const app = 'globalThis.subspaceDeformer';
const shown = (page) => page.evaluate(() => !document.querySelector('.sd-help-card').hidden);
const camera = (page) => page.evaluate(() => globalThis.subspaceDeformer.views[0].viewport.camera.position.toArray());

export default [
  {
    name: 'the help card is modal and closes with Escape',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      await page.evaluate(`${app}.layout.helpCard.toggle()`);
      assert.equal(await shown(page), true);
      await page.keyboard.press('Escape');
      assert.equal(await shown(page), false, 'Escape closed the card');
      // Open again; a drag beside the card closes it and does not turn the camera underneath.
      await page.evaluate(`${app}.layout.helpCard.toggle()`);
      const before = await camera(page);
      const box = await page.locator('canvas').first().boundingBox();
      await page.mouse.move(box.x + 10, box.y + box.height / 2);
      await page.mouse.down();
      await page.mouse.move(box.x + 80, box.y + box.height / 2 + 20, { steps: 5 });
      await page.mouse.up();
      assert.equal(await shown(page), false, 'a press beside the card closed it');
      assert.deepEqual(await camera(page), before, 'the drag did not reach the view underneath');
      // While the card is up, keys are the card's: C does not hide the cage.
      await page.evaluate(`${app}.layout.helpCard.toggle()`);
      const cage = await page.evaluate(`${app}.settings.showCage`);
      await page.keyboard.press('c');
      assert.equal(await page.evaluate(`${app}.settings.showCage`), cage, 'C under the card changed nothing');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: '?compare=coordinates ticks "compare coordinates", not "compare methods"',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html?compare=coordinates');
      await appReady(page);
      const box = (name) => page.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: new RegExp(`^${name}$`) }) })
        .locator('input[type=checkbox]');
      await page.evaluate(`${app}.setPanelOpen(true)`);
      assert.equal(await box('compare coordinates').isChecked(), true, '"compare coordinates" is ticked');
      const methods = box('compare methods');
      if (await methods.count()) assert.equal(await methods.isChecked(), false, '"compare methods" is not');
      assert.deepEqual(page.errors, []);
    },
  },
];
