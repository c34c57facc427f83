// The app's edits in the browser: painted volume parts in the one undo timeline (Ctrl+Z after a brush stroke takes
// back the stroke, not an earlier handle edit), a saved scene's painted parts drawn and edited after it is loaded,
// redo ended by a new edit of another kind, a stroke under way when another model is bound, influence picking with
// the bone tool (one tap, one tool), and painted parts under an influence column.
import assert from 'node:assert/strict';
import { appReady, project } from './app_probe.mjs';

const app = 'globalThis.subspaceDeformer';
const painted = (page) => page.evaluate(`${app}.parts.painter.vertexPart.filter((p) => p >= 0).length`);
const movingTarget = (page) => page.evaluate(`Array.from(${app}.handles.targets()).slice(-3)`);

/** A brush stroke (Shift-drag) across the bar from x = a to x = b (world units, through the middle). */
async function brushStroke(page, a, b, { release = true } = {}) {
  const from = await project(page, `app.views[0].viewport.controls.target.clone().set(${a}, 0, 0)`);
  const to = await project(page, `app.views[0].viewport.controls.target.clone().set(${b}, 0, 0)`);
  await page.keyboard.down('Shift');
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let i = 1; i <= 8; ++i) await page.mouse.move(from.x + ((to.x - from.x) * i) / 8, from.y + ((to.y - from.y) * i) / 8);
  if (release) await page.mouse.up();
  await page.keyboard.up('Shift');
}

export default [
  {
    name: 'edits: Ctrl+Z takes back a paint stroke; a saved scene\'s painted parts are drawn and a stroke adds to them',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      await page.evaluate(`${app}.drag(1, [0, 0.5, 0])`);
      const dragged = await movingTarget(page);
      const centre = await project(page, 'app.views[0].viewport.controls.target.clone()');
      await page.mouse.move(centre.x, centre.y);
      await page.keyboard.press('p');
      await brushStroke(page, -1.8, -0.6);
      const first = await painted(page);
      assert.ok(first > 10, `the stroke painted ${first} vertices`);
      await page.evaluate(`${app}.parts.setCurrent(3)`);
      await brushStroke(page, 0.6, 1.8);
      const both = await painted(page);
      assert.ok(both > first, 'the second stroke painted more');
      await page.keyboard.press('Control+z');
      assert.equal(await painted(page), first, 'Ctrl+Z takes back the last stroke');
      assert.deepEqual(await movingTarget(page), dragged, 'and leaves the handle edit before it');
      await page.keyboard.press('Control+Shift+z');
      assert.equal(await painted(page), both, 'redo paints it again');
      assert.equal(await page.evaluate(`${app}.parts.apply()`), 3, 'two painted parts and the rest');
      const scene = await page.evaluate(`${app}.sceneJson()`);
      const saved = scene.volumeParts.vertices.map((list) => list.length);
      assert.deepEqual(saved.reduce((a, b) => a + b), both);

      await page.reload();
      await appReady(page);
      await page.evaluate((s) => globalThis.subspaceDeformer.loadScene(s), scene);
      assert.equal(await page.evaluate(`${app}.parts.count`), 3);
      assert.equal(await painted(page), both, 'the scene\'s parts are painted');
      assert.ok(await page.evaluate(`!!${app}.views[0].viewport.meshView.geometry.attributes.color`), 'and drawn as colours');
      // Four vertices more, kept: the scene's parts stay, with a fourth part.
      await page.evaluate(`${app}.parts.setCurrent(5)`);
      const free = await page.evaluate(`Array.from(${app}.parts.painter.vertexPart.keys()).filter((v) => ${app}.parts.painter.vertexPart[v] < 0).slice(0, 4)`);
      await page.evaluate((v) => globalThis.subspaceDeformer.parts.paint(v, 'add'), free);
      assert.equal(await page.evaluate(`${app}.parts.unkeptPaint`), true);
      assert.equal(await page.evaluate(`${app}.parts.apply()`), 4);
      const again = await page.evaluate(`${app}.sceneJson().volumeParts.vertices.map((list) => list.length)`);
      assert.deepEqual(again, [...saved, 4]);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'edits: a new handle edit ends the redo of an undone bone, and a skeleton edit that of a handle edit',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      await page.evaluate(`${app}.skeleton.addJoint([-1, 0, 0]).then(() => ${app}.skeleton.addJoint([1, 0, 0]))`);
      await page.evaluate(`${app}.undo()`);
      assert.equal(await page.evaluate(`${app}.skeleton.bones`), 0);
      await page.evaluate(`${app}.drag(1, [0, 0.3, 0])`);
      assert.equal(await page.locator('.sd-tool[data-action="redo"]').isDisabled(), true, 'nothing to redo');
      await page.evaluate(`${app}.redo()`);
      assert.equal(await page.evaluate(`${app}.skeleton.bones`), 0, 'the bone stays undone');
      // The other way: a handle edit undone, then a bone.
      const before = await movingTarget(page);
      await page.evaluate(`${app}.drag(1, [0, -0.5, 0])`);
      await page.evaluate(`${app}.undo()`);
      await page.evaluate(`${app}.skeleton.addJoint([1, 0, 0])`);
      await page.evaluate(`${app}.redo()`);
      assert.deepEqual(await movingTarget(page), before, 'the undone drag stays undone');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'edits: a stroke under way ends with its model; one tap serves one tool; the legend says paint is hidden',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const centre = await project(page, 'app.views[0].viewport.controls.target.clone()');
      await page.mouse.move(centre.x, centre.y);
      await page.keyboard.press('p');
      await brushStroke(page, -1.5, -0.5, { release: false }); // the button still down
      assert.ok(await painted(page) > 0);
      await page.evaluate(`${app}.loadExample('sphere')`);
      for (let i = 1; i <= 8; ++i) await page.mouse.move(centre.x + 5 * i, centre.y + 3 * i);
      await page.mouse.up();
      assert.equal(await painted(page), 0, 'the stroke did not go on painting the new model');
      // Influence picking and the bone tool both on: a tap on the mesh places no joint.
      await page.keyboard.press('p');
      await page.evaluate(`${app}.setOptions({ tool: 'bone' })`);
      await page.evaluate(`${app}.influence.setPicking(true)`);
      await page.mouse.click(centre.x, centre.y);
      await page.waitForTimeout(200);
      assert.equal(await page.evaluate(`${app}.skeleton.joints`), 0, 'the tap was the influence picking\'s');
      await page.evaluate(`${app}.influence.setPicking(false)`);
      await page.mouse.click(centre.x, centre.y);
      await page.waitForFunction(`${app}.skeleton.joints === 1`, null, { timeout: 5000 });
      // Painted parts under an influence column: the legend says they are hidden.
      await page.evaluate(`${app}.parts.auto(3)`);
      await page.evaluate(`${app}.influence.show(0)`);
      assert.match(await page.locator('.sd-influence').first().textContent(), /painted volume parts are hidden/);
      await page.evaluate(`${app}.parts.clear()`);
      assert.doesNotMatch(await page.locator('.sd-influence').first().textContent(), /painted volume parts are hidden/);
      assert.deepEqual(page.errors, []);
    },
  },
];
