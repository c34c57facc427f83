// Interaction as a new user meets it: keys right after a brush or lasso stroke and after a panel button
// (never from a text field), the two reset buttons doing what their labels say, and "fit view" framing the
// model and its handles in every view's own aspect, also in compare mode, after a resize and on the real
// models whose heads used to leave the view.
import assert from 'node:assert/strict';
import { appReady, framing, haveSharedData, project, routeSharedData } from './app_probe.mjs';

const app = 'globalThis.subspaceDeformer';
const groups = (page) => page.evaluate(() => globalThis.subspaceDeformer.handles.groups.map((g) => ({ vertices: [...g.vertices].sort((a, b) => a - b), moving: g.moving })));
const selection = (page) => page.evaluate(() => [...globalThis.subspaceDeformer.selection].sort((a, b) => a - b));

/** A stroke with a modifier held: Shift = brush, Alt = lasso (a closed loop around `at`). */
async function stroke(page, modifier, at, radius = 14) {
  await page.mouse.move(at.x + radius, at.y);
  await page.keyboard.down(modifier);
  await page.mouse.down();
  const steps = modifier === 'Alt' ? 16 : 6;
  for (let i = 1; i <= steps; ++i) {
    const a = (2 * Math.PI * i) / 16;
    if (modifier === 'Alt') await page.mouse.move(at.x + radius * Math.cos(a), at.y + radius * Math.sin(a));
    else await page.mouse.move(at.x + radius - 5 * i, at.y);
  }
  await page.mouse.up();
  await page.keyboard.up(modifier);
}

/** Every view frames its mesh and targets with the margin, and the model fills a fair part of the view. */
function assertFramed(views, what) {
  for (const v of views) {
    assert.ok(v.inFront, `${what}, ${v.method}: part of the model is behind the camera or past its far plane`);
    assert.ok(v.x <= 0.92 && v.y <= 0.92, `${what}, ${v.method}: projects to |x| ${v.x.toFixed(3)}, |y| ${v.y.toFixed(3)} (margin 0.08)`);
    assert.ok(Math.max(v.x, v.y) >= 0.5, `${what}, ${v.method}: the model fills only ${Math.max(v.x, v.y).toFixed(2)} of the view`);
  }
}

async function settle(page) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
}

export default [
  {
    name: 'keys work right after a brush or lasso stroke and after a panel button, never from a text field',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const before = (await groups(page)).length;
      // A fresh page: no click in the view first. Brush near the middle of the bar, then F.
      const middle = await project(page, 'app.views[0].viewport.controls.target.clone()');
      await stroke(page, 'Shift', middle);
      const brushed = await selection(page);
      assert.ok(brushed.length > 3, `the brush selected ${brushed.length} vertices`);
      await page.keyboard.press('f');
      let list = await groups(page);
      assert.equal(list.length, before + 1, 'F after a brush stroke made a group');
      assert.deepEqual(list.at(-1), { vertices: brushed, moving: false });
      // Alt-lasso a little to the right, then M.
      await stroke(page, 'Alt', { x: middle.x + 60, y: middle.y }, 20);
      const lassoed = await selection(page);
      assert.ok(lassoed.length > 3, `the lasso selected ${lassoed.length} vertices`);
      await page.keyboard.press('m');
      list = await groups(page);
      assert.deepEqual(list.at(-1), { vertices: lassoed, moving: true }, 'M after a lasso made a moving group');
      // A panel button takes the focus; keys still reach the app.
      await stroke(page, 'Shift', { x: middle.x - 60, y: middle.y });
      const third = await selection(page);
      await page.locator('.lil-gui button', { hasText: 'fit view (V)' }).click();
      assert.equal(await page.evaluate(() => document.activeElement?.tagName), 'BUTTON');
      await page.keyboard.press('f');
      list = await groups(page);
      assert.deepEqual(list.at(-1), { vertices: third, moving: false }, 'F after clicking a panel button');
      // Typing into a panel number field is the field's: no group, no toggle of the cage.
      await stroke(page, 'Shift', { x: middle.x - 100, y: middle.y });
      const pending = await selection(page);
      const field = page.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: /^brush radius$/ }) }).locator('input');
      await field.click();
      await page.keyboard.press('f');
      await page.keyboard.press('c');
      assert.equal((await groups(page)).length, list.length, 'F typed into a number field made no group');
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.settings.showCage), true, 'C typed into a field');
      assert.deepEqual(await selection(page), pending);
      // Focus on the page itself, pointer over the view: the keys are the app's.
      await page.evaluate(() => document.activeElement.blur());
      await page.mouse.move(middle.x, middle.y + 5);
      await page.keyboard.press('m');
      assert.deepEqual((await groups(page)).at(-1), { vertices: pending, moving: true }, 'M with the pointer over the view');
      await t.screenshot(page, 'keys-after-strokes');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: '"reset pose and handles" puts targets and mesh back at rest (undoable); "re-solve from rest" solves the same targets again',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const dragged = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.drag(1, [0, 0.6, 0.2]);
        return Array.from(app.positions());
      });
      const distance = (a, b) => a.reduce((m, x, i) => Math.max(m, Math.abs(x - b[i])), 0);
      const rest = await page.evaluate(() => Array.from(globalThis.subspaceDeformer.restPositions()));
      assert.ok(distance(dragged, rest) > 0.3, 'the drag moved the mesh');
      const button = (label) => page.locator('.lil-gui button', { hasText: label });
      await button('reset pose and handles').click();
      let now = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.solve();
        return { positions: Array.from(app.positions()), moves: app.handles.groups.map((g) => g.translate) };
      });
      assert.ok(distance(now.positions, rest) < 1e-6, `after reset the mesh is ${distance(now.positions, rest)} from rest`);
      for (const move of now.moves) assert.deepEqual(move, [0, 0, 0]);
      await page.keyboard.press('Control+z');
      now = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.solve();
        return { positions: Array.from(app.positions()), moves: app.handles.groups.map((g) => g.translate) };
      });
      assert.deepEqual(now.moves[1], [0, 0.6, 0.2], 'Ctrl+Z brought the displacement back');
      assert.ok(distance(now.positions, dragged) < 1e-4, `undo: ${distance(now.positions, dragged)} from the dragged pose`);
      // Re-solve from rest: the first result drawn is the rest pose, the solve ends where it was.
      await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        app.firstFrame = new Promise((resolve) => {
          const once = () => {
            app.removeEventListener('frame', once);
            resolve(Array.from(app.positions()));
          };
          app.addEventListener('frame', once);
        });
      });
      await button('re-solve from rest (same targets)').click();
      const first = await page.evaluate('globalThis.subspaceDeformer.firstFrame');
      assert.ok(distance(first, rest) < 1e-9, 're-solve starts from the rest pose');
      const again = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        const stats = await app.solve();
        return { positions: Array.from(app.positions()), stats };
      });
      assert.equal(again.stats.state, 'converged');
      assert.ok(distance(again.positions, dragged) < 1e-4, `re-solved pose ${distance(again.positions, dragged)} from the first solve`);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'fit view frames the model and its handles in every view: compare mode, after a pull, after a resize',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html?compare=1');
      await appReady(page);
      assertFramed(await framing(page), 'compare mode at load');
      // A large pull takes the moving end out of the frame; V frames it again.
      await page.evaluate(`${app}.drag(1, [3, 1.5, 0])`);
      const pulled = await framing(page);
      assert.ok(pulled.some((v) => v.x > 0.95 || v.y > 0.95), 'the pull left the frame (else this test proves nothing)');
      const middle = await project(page, 'app.views[1].viewport.controls.target.clone()', 1);
      await page.mouse.move(middle.x, middle.y);
      await page.keyboard.press('v');
      await settle(page);
      assertFramed(await framing(page), 'after V');
      // The window narrows: the views are framed again for their new aspect.
      await page.setViewportSize({ width: 900, height: 760 });
      await page.waitForFunction(() => globalThis.subspaceDeformer.views[0].viewport.camera.aspect < 0.5);
      await settle(page);
      assertFramed(await framing(page), 'after a resize');
      // Leaving compare mode: one wide view, framed again.
      await page.evaluate(`${app}.setCompare(false)`);
      await settle(page);
      assertFramed(await framing(page), 'single view after compare');
      await t.screenshot(page, 'fit-view');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'the shared armadillo and boy load framed, heads inside the view (skipped without ../shared/data)',
    timeout: 120000,
    async run(t) {
      if (!haveSharedData('armadillo.obj', 'armadillo_cage.obj', 'boy.obj', 'boy_cage.obj')) {
        console.log('     skipped: ../shared/data is absent (test meshes live beside the project, not in it)');
        return;
      }
      const page = await t.page(null);
      await routeSharedData(page);
      await page.goto(`${t.url}index.html?compare=1&mesh=shared-data/armadillo.obj&cage=shared-data/armadillo_cage.obj`);
      await appReady(page);
      assertFramed(await framing(page), 'armadillo, compare mode');
      await t.screenshot(page, 'fit-armadillo-compare');
      await page.evaluate(`${app}.setCompare(false)`);
      await page.evaluate(`${app}.loadUrls('shared-data/boy.obj', 'shared-data/boy_cage.obj')`);
      await settle(page);
      assertFramed(await framing(page), 'boy');
      await t.screenshot(page, 'fit-boy');
      assert.deepEqual(page.errors, []);
    },
  },
];
