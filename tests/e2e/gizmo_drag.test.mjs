// A gizmo drag interrupted, by real input (an attack found each): Del during a drag removed the group and left the
// gizmo "dragging" (left drags no longer orbited, and once undo brought the group back, mouse moves with no button
// dragged it); Ctrl+Z during a drag made an earlier pose unreachable and redo bring back one from the middle of the
// drag; a second finger took the handle over (the gizmo followed it while the first finger held still) and its
// lift ended the drag; and in compare mode a drag in the screen plane left ARAP's view silent about the lines it
// ignores, which the CLI's report names (handle_lines_ignored).
import assert from 'node:assert/strict';
import { appReady, project } from './app_probe.mjs';
import { Fingers, TABLET } from './touch.mjs';

const app = 'globalThis.subspaceDeformer';
const translate = (page) => page.evaluate(() => globalThis.subspaceDeformer.handles.groups[1]?.translate ?? null);
const gizmoState = (page) => page.evaluate(() => {
  const view = globalThis.subspaceDeformer.views[0];
  return { dragging: view.gizmo.dragging, orbit: view.viewport.controls.enabled };
});
const pivot = (page, view = 0) => project(page, `app.views[${view}].gizmo.pivot.position.clone()`, view);
const cameraPosition = (page) => page.evaluate(() => globalThis.subspaceDeformer.views[0].viewport.camera.position.toArray());

/** Presses the mouse on the gizmo's centre (hovered first, as a hand does) and moves it `steps` times by (dx, dy). */
async function pressAndMove(page, at, steps, dx = -8, dy = -6) {
  await page.mouse.move(at.x + 2, at.y + 2);
  await page.mouse.move(at.x, at.y);
  await page.mouse.down();
  for (let i = 1; i <= steps; ++i) await page.mouse.move(at.x + dx * i, at.y + dy * i);
  return { x: at.x + dx * steps, y: at.y + dy * steps };
}

const near = (a, b) => a.every((x, i) => Math.abs(x - b[i]) < 1e-9);

export default [
  {
    name: 'gizmo: Del during a drag ends it as a release (the camera controls back, no drag left behind)',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const at = await pressAndMove(page, await pivot(page), 5);
      const beforeDelete = await translate(page);
      assert.ok(Math.hypot(...beforeDelete) > 1e-3, 'the gizmo is dragging');
      await page.keyboard.press('Delete');
      assert.equal(await page.evaluate(`${app}.handles.groups.length`), 1, 'Del removed the moving group');
      assert.deepEqual(await gizmoState(page), { dragging: false, orbit: true }, 'the drag ended with its group');
      for (let i = 1; i <= 4; ++i) await page.mouse.move(at.x - 10 * i, at.y + 5 * i); // the button still down
      await page.mouse.up();
      const viewport = page.viewportSize();
      const camera = await cameraPosition(page);
      await page.mouse.move(0.3 * viewport.width, 0.8 * viewport.height);
      await page.mouse.down();
      await page.mouse.move(0.3 * viewport.width + 100, 0.8 * viewport.height + 40, { steps: 8 });
      await page.mouse.up();
      assert.ok(!near(await cameraPosition(page), camera), 'a left drag orbits again');
      // Undo brings the group back as it was when Del was pressed; moves without a button leave it there.
      await page.keyboard.press('Control+z');
      assert.deepEqual(await translate(page), beforeDelete, 'undo brings back the group where the drag had taken it');
      const p = await pivot(page);
      await page.mouse.move(p.x, p.y);
      await page.mouse.move(p.x + 60, p.y + 40, { steps: 6 });
      assert.deepEqual(await translate(page), beforeDelete, 'moves with no button drag nothing');
      assert.deepEqual(await gizmoState(page), { dragging: false, orbit: true });
      await page.keyboard.press('Control+z');
      assert.deepEqual(await translate(page), [0, 0, 0], 'the interrupted drag was one step');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'gizmo: Ctrl+Z and redo during a drag do nothing: the drag stays one step, no pose from its middle comes back',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      await page.evaluate(`${app}.drag(1, [0, 0.3, 0])`); // a first edit
      const first = await translate(page);
      const at = await pressAndMove(page, await pivot(page), 5);
      const middle = await translate(page);
      assert.ok(!near(middle, first), 'the gizmo is dragging');
      await page.keyboard.press('Control+z');
      await page.keyboard.press('Control+Shift+z');
      await page.evaluate(`${app}.undo()`);
      assert.deepEqual(await translate(page), middle, 'undo and redo did nothing during the drag');
      await page.mouse.move(at.x - 20, at.y - 10);
      await page.mouse.up();
      const released = await translate(page);
      assert.ok(!near(released, middle), 'the drag went on after Ctrl+Z');
      await page.keyboard.press('Control+z');
      assert.deepEqual(await translate(page), first, 'one undo takes back the whole drag, to the first edit');
      await page.keyboard.press('Control+z');
      assert.deepEqual(await translate(page), [0, 0, 0]);
      await page.keyboard.press('Control+Shift+z');
      await page.keyboard.press('Control+Shift+z');
      assert.deepEqual(await translate(page), released, 'redo brings back the released pose, never one from the middle');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'gizmo (tablet, touch): a second finger during a drag ends it where the first finger had it and pinches',
    timeout: 60000,
    async run(t) {
      const page = await t.touchPage('index.html', TABLET);
      await appReady(page);
      const fingers = await Fingers.on(page);
      const start = await pivot(page);
      const path = Array.from({ length: 5 }, (_, i) => ({ x: start.x - 6 * i, y: start.y - 10 * i }));
      // The reference: the same path with one finger.
      await fingers.drag(path);
      const alone = await translate(page);
      assert.ok(Math.hypot(...alone) > 1e-3, `one finger moved the group by ${alone}`);
      await page.evaluate(`${app}.undo()`);
      assert.deepEqual(await translate(page), [0, 0, 0]);

      // Finger 1 drags along the path and then holds still; finger 2 lands well away and moves further away.
      const distance = () => page.evaluate(() => {
        const v = globalThis.subspaceDeformer.views[0].viewport;
        return v.camera.position.distanceTo(v.controls.target);
      });
      const before = await distance();
      const end = path.at(-1);
      const second = { x: end.x + 120, y: end.y + 200 };
      await fingers.twoFinger([...path, end], [second, { x: second.x + 90, y: second.y + 150 }], { firstAlone: path.length - 1 });
      const after = await translate(page);
      assert.ok(near(after, alone), `the drag ended where finger 1 had it: ${after} (alone: ${alone})`);
      assert.deepEqual(await gizmoState(page), { dragging: false, orbit: true });
      assert.ok(await distance() < 0.9 * before, 'the two fingers pinched (zoomed in)');
      await page.evaluate(`${app}.undo()`);
      assert.deepEqual(await translate(page), [0, 0, 0], 'the interrupted drag was one step');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'gizmo: in compare mode a drag in the screen plane makes ARAP\'s view warn, as the CLI does, that it ignores lines',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html?compare=arap,subspace');
      await appReady(page);
      await pressAndMove(page, await pivot(page, 1), 6, 0, -6);
      await page.mouse.up();
      assert.ok(await page.evaluate(`${app}.handles.groups[1].line !== null`), 'the centre drag gave the group lines');
      await page.evaluate(`${app}.solve()`);
      const warnings = await page.evaluate(() => globalThis.subspaceDeformer.statsAll().map((s) => [s.method, s.warnings.map((w) => w.code)]));
      assert.deepEqual(warnings.map(([method, codes]) => [method, codes.includes('handle_lines_ignored')]), [['arap', true], ['subspace', false]],
        JSON.stringify(warnings));
      // The ARAP view's stats line shows it (redrawn a few times a second).
      await page.waitForFunction(() => /handle_lines_ignored: ARAP holds each handle vertex at its target/
        .test(globalThis.subspaceDeformer.views[0].viewport.element.innerText), null, { timeout: 5000 });
      assert.deepEqual(page.errors, []);
    },
  },
];
