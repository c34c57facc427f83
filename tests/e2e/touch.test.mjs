// The app on a phone and a tablet, by touch only (touch emulation: hasTouch, isMobile, a coarse pointer): the
// layout gives the view the screen and the panel opens over it; with the tool strip a student clears the
// groups, brushes a fixed group, lassos a moving one and drags its gizmo with a finger (the solve converges
// with the volume kept), undoes it; a second finger turns a brush stroke into a pinch (the stroke's selection
// is undone, the camera zooms); press-and-hold brushes; the help has a touch version. Screenshots of each
// device go to test-results/.
import assert from 'node:assert/strict';
import { appReady, framing, overlaps, project, rect } from './app_probe.mjs';
import { Fingers, PHONE, TABLET, tapButton } from './touch.mjs';
import { VOLUME_TOLERANCE } from './geometry.mjs';

const app = 'globalThis.subspaceDeformer';
const selected = (page) => page.evaluate(() => globalThis.subspaceDeformer.selection.size);
const groups = (page) => page.evaluate(() => globalThis.subspaceDeformer.handles.groups.map((g) => ({ size: g.vertices.length, moving: g.moving })));
const tool = (page, id) => ({ tap: () => tapButton(page.locator(`.sd-tool[data-action="${id}"]`)) });

/** Screen points of the bar's ends: the rest centroids of its lowest and highest 6% along x. */
function barEnds(page) {
  return project(page, `(() => {
    const P = app.model.mesh.positions; let lo = Infinity, hi = -Infinity;
    for (let i = 0; i < P.length; i += 3) { lo = Math.min(lo, P[i]); hi = Math.max(hi, P[i]); }
    const v = app.views[0].viewport.controls.target.clone();
    return v.set(lo + 0.04 * (hi - lo), 0, 0);
  })()`).then(async (left) => ({ left, right: await project(page, `(() => {
    const P = app.model.mesh.positions; let lo = Infinity, hi = -Infinity;
    for (let i = 0; i < P.length; i += 3) { lo = Math.min(lo, P[i]); hi = Math.max(hi, P[i]); }
    return app.views[0].viewport.controls.target.clone().set(hi - 0.04 * (hi - lo), 0, 0);
  })()`) }));
}

/** Every vertex and handle target of every view projects inside it (with the fit's margin). */
function assertFramed(views, what) {
  for (const v of views) assert.ok(v.inFront && v.x <= 0.95 && v.y <= 0.95, `${what}: ${v.method} projects to |x| ${v.x.toFixed(2)}, |y| ${v.y.toFixed(2)}`);
}

/** A closed loop of `n` points around `at`. */
function loop(at, radius, n = 16) {
  return Array.from({ length: n + 1 }, (_, i) => ({ x: at.x + radius * Math.cos((2 * Math.PI * i) / n), y: at.y + radius * Math.sin((2 * Math.PI * i) / n) }));
}

async function cameraDistance(page) {
  return page.evaluate(() => {
    const v = globalThis.subspaceDeformer.views[0].viewport;
    return v.camera.position.distanceTo(v.controls.target);
  });
}

/** The whole student task by touch on one device. */
async function studentTask(t, viewport, name) {
  const page = await t.touchPage('index.html', viewport);
  await appReady(page);
  const fingers = await Fingers.on(page);
  // The view takes the screen: the panel starts closed, and no panel header covers it.
  assert.equal(await page.evaluate(`${app}.panelOpen`), false, 'the panel starts closed on a small screen');
  const view = await rect(page, '.sd-view');
  assert.ok(view.right - view.left >= viewport.width - 80, `the view is ${view.right - view.left} px wide of ${viewport.width}`);
  assert.equal(await rect(page, '.lil-gui.lil-root'), null, 'no panel header over the view');
  await t.screenshot(page, `touch-${name}-start`);

  // The panel, by touch: on a phone a bottom sheet with the view above it, on a tablet beside the view; either
  // way the view keeps the model in sight (framed again for its new size). "clear groups", then closed again.
  await tool(page, 'panel').tap();
  const panel = await rect(page, '.lil-gui.lil-root');
  const smaller = await rect(page, '.sd-view');
  assert.ok(panel && !overlaps(panel, smaller), 'the open panel leaves the view free');
  assertFramed(await framing(page), 'with the panel open');
  await t.screenshot(page, `touch-${name}-panel`);
  await tapButton(page.locator('.lil-gui button', { hasText: 'clear groups' }));
  await tool(page, 'panel').tap();
  assert.deepEqual(await groups(page), []);

  // Brush a fixed group at the left end.
  const ends = await barEnds(page);
  await tool(page, 'brush').tap();
  await fingers.drag([{ x: ends.left.x, y: ends.left.y - 6 }, { x: ends.left.x + 4, y: ends.left.y }, { x: ends.left.x + 8, y: ends.left.y + 6 }]);
  const brushed = await selected(page);
  assert.ok(brushed > 5, `the brush selected ${brushed} vertices`);
  await tool(page, 'fixed').tap();
  assert.deepEqual(await groups(page), [{ size: brushed, moving: false }], 'the fixed button made a fixed group');

  // Lasso the right end, then a moving group: its gizmo appears there.
  await tool(page, 'lasso').tap();
  await fingers.drag(loop(ends.right, Math.max(18, 0.06 * viewport.width)));
  const lassoed = await selected(page);
  assert.ok(lassoed > 5, `the lasso selected ${lassoed} vertices`);
  await tool(page, 'moving').tap();
  assert.deepEqual((await groups(page)).at(-1), { size: lassoed, moving: true });

  // Drag the gizmo's centre (free translation) up with a finger; the mesh follows with the volume kept.
  const pivot = await project(page, 'app.views[0].gizmo.pivot.position.clone()');
  await fingers.drag(Array.from({ length: 9 }, (_, i) => ({ x: pivot.x, y: pivot.y - 8 * i })));
  const translate = await page.evaluate(() => globalThis.subspaceDeformer.handles.groups[1].translate);
  assert.ok(Math.hypot(...translate) > 1e-3, `the finger moved the group by ${translate}`);
  assert.equal(await selected(page), 0, 'dragging the gizmo selected nothing');
  const stats = await page.evaluate(`${app}.solve()`);
  assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
  assert.ok(Math.abs(stats.volumeRelError) <= VOLUME_TOLERANCE, `volume error ${stats.volumeRelError}`);
  await t.screenshot(page, `touch-${name}-dragged`);

  // Undo by touch: the drag is gone.
  await tool(page, 'undo').tap();
  assert.deepEqual(await page.evaluate(() => globalThis.subspaceDeformer.handles.groups[1].translate), [0, 0, 0]);
  return { page, fingers, ends };
}

export default [
  {
    name: 'phone (390 x 844, touch): fixed and moving groups made by touch only, the gizmo dragged by a finger',
    timeout: 60000,
    async run(t) {
      const { page, fingers, ends } = await studentTask(t, PHONE, 'phone');
      // A second finger during a brush stroke: no selection is left, and the pinch zooms.
      await tool(page, 'brush').tap();
      const before = await cameraDistance(page);
      // A third of the way from the fixed end: away from the gizmo (whose handles would take the finger).
      const mid = { x: (2 * ends.left.x + ends.right.x) / 3, y: (2 * ends.left.y + ends.right.y) / 3 };
      await fingers.twoFinger([mid, { x: mid.x + 3, y: mid.y }, { x: mid.x - 60, y: mid.y - 90 }],
        [{ x: mid.x + 10, y: mid.y + 40 }, { x: mid.x + 70, y: mid.y + 130 }], { firstAlone: 1 });
      assert.equal(await selected(page), 0, 'the cancelled stroke left no selection');
      const after = await cameraDistance(page);
      assert.ok(after < 0.9 * before, `the pinch zoomed in: camera distance ${before.toFixed(3)} -> ${after.toFixed(3)}`);
      // Press and hold, then drag, in the pick tool: a brush stroke.
      await tool(page, 'pick').tap();
      await page.evaluate(`${app}.fitView()`);
      const { left } = await barEnds(page);
      await fingers.drag([left, { x: left.x + 5, y: left.y }, { x: left.x + 10, y: left.y }],
        { holdUntil: `${app}.views[0].picker.stroke?.longPress` });
      assert.ok(await selected(page) > 3, 'press-and-hold then drag brushed');
      // A tap with the pick tool toggles one vertex (an erase tap removes it again); off the groups, since a
      // tap on a group's vertex with nothing selected makes that group active instead.
      await page.evaluate(`${app}.clearSelection()`);
      const free = await barEnds(page).then(({ left, right }) => ({ x: (2 * left.x + right.x) / 3, y: (2 * left.y + right.y) / 3 }));
      await fingers.tap(free);
      assert.equal(await selected(page), 1, 'a tap picked one vertex');
      await tool(page, 'erase').tap();
      await fingers.tap(free);
      assert.equal(await selected(page), 0, 'an erase tap removed it');
      // The help: a card with the touch version first.
      await tool(page, 'help').tap();
      const help = await page.locator('.sd-help-card h3').first().textContent();
      assert.equal(help, 'Touch and pen');
      await t.screenshot(page, 'touch-phone-help');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'tablet (820 x 1180, touch): the same by touch only; the panel opens over the view',
    timeout: 60000,
    async run(t) {
      const { page } = await studentTask(t, TABLET, 'tablet');
      // The gizmo's rotate mode from the strip; a drag on the rotation ring turns the group.
      await tool(page, 'gizmo').tap();
      assert.equal(await page.evaluate(`${app}.settings.gizmoMode`), 'rotate');
      assert.deepEqual(page.errors, []);
    },
  },
];
