// "Copy link to this pose" (issue 31, item 4): the panel's button puts the current scene (model, handle
// groups with their targets, solver options, the compared methods and the camera) in the page's URL as
// ?pose=... and on the clipboard; opening that link shows the same pose (same groups and targets, options,
// views, camera direction, and the same solved shape). A model opened from files, or a pose whose link would be
// too long, gets no link and the banner says why; a link cut short says so and the app still starts.
import assert from 'node:assert/strict';
import { readdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { appReady } from './app_probe.mjs';
import { decodePose } from '../../web/app/loading/pose_link.js';

const dist = process.env.SD_E2E_DIST ?? join(dirname(fileURLToPath(import.meta.url)), '..', '..', 'dist');

const app = 'globalThis.subspaceDeformer';

/** Opens the panel's Export folder and presses "copy link to this pose"; resolves with the banner's kind and text. */
async function pressCopyLink(page) {
  await page.evaluate(`${app}.setPanelOpen(true)`);
  const folder = page.locator('.lil-gui .lil-title', { hasText: 'Export' });
  if (await page.locator('.lil-gui button', { hasText: 'copy link to this pose' }).isHidden()) await folder.click();
  await page.locator('.lil-gui button', { hasText: 'copy link to this pose' }).click();
  await page.waitForFunction(() => !document.querySelector('.sd-banner').hidden);
  return page.evaluate(() => ({ kind: document.querySelector('.sd-banner').dataset.kind, text: document.querySelector('.sd-banner .sd-message').textContent }));
}

/** What a pose is: the model, the groups and targets, the options, the views, the camera direction. */
function pose(page) {
  return page.evaluate(() => {
    const a = globalThis.subspaceDeformer;
    return {
      model: a.model.name,
      handles: a.handles.toScene(),
      targets: [...a.handles.targets()],
      settings: { method: a.settings.method, jacobian: a.settings.jacobian, positionWeight: a.settings.positionWeight, volume: a.settings.volume },
      views: a.views.map((v) => v.key),
      direction: a.views[0].viewport.viewDirection().toArray(),
    };
  });
}

function assertClose(a, b, tolerance, what) {
  assert.equal(a.length, b.length, `${what}: ${a.length} against ${b.length} numbers`);
  const worst = a.reduce((m, x, i) => Math.max(m, Math.abs(x - b[i])), 0);
  assert.ok(worst <= tolerance, `${what}: differs by ${worst}`);
}

export default [
  {
    name: 'copy link: the pose (model, handles, targets, options, compared views, camera) in the URL; opening it shows the same pose',
    timeout: 120000,
    async run(t) {
      const origin = new URL(t.url).origin;
      await t.context.grantPermissions(['clipboard-read', 'clipboard-write'], { origin });
      const page = await t.page('index.html?example=sphere&compare=subspace,arap');
      await appReady(page);
      // A pose: a brushed-looking fixed group, the moving group turned and moved, other options.
      await page.evaluate(`${app}.setOptions({ jacobian: 'exact', positionWeight: 2.5 })`);
      await page.evaluate(`${app}.drag(1, [0.1, 0.45, -0.2], { axis: [0, 0, 1], angle: 0.6 })`);
      await page.evaluate(`${app}.fitView([1, -0.3, -0.5])`);
      const before = await pose(page);
      const shape = await page.evaluate(`${app}.solve().then(() => [...${app}.views[0].positions])`);

      const banner = await pressCopyLink(page);
      assert.equal(banner.kind, 'info', banner.text);
      assert.match(banner.text, /^Link copied: opening it shows this model/);
      const link = await page.evaluate(() => navigator.clipboard.readText());
      assert.equal(page.url(), link, 'the address bar shows the link');
      const url = new URL(link);
      assert.deepEqual([...url.searchParams.keys()], ['pose'], link);
      assert.ok(link.length < 8000, `${link.length} characters`);
      console.log(`     the link: ${link.length} characters`);

      const opened = await t.page(null);
      await opened.goto(link);
      await appReady(opened);
      const after = await pose(opened);
      assert.equal(after.model, before.model);
      assert.deepEqual(after.views, before.views, 'the same methods compared');
      assert.deepEqual(after.settings, before.settings, 'the same options');
      assert.deepEqual(after.handles.map((h) => h.vertices), before.handles.map((h) => h.vertices), 'the same handle groups');
      assertClose(after.targets, before.targets, 1e-12, 'the targets');
      assertClose(after.direction, before.direction, 1e-3, 'the camera direction');
      const restored = await opened.evaluate(`${app}.solve().then(() => [...${app}.views[0].positions])`);
      assertClose(restored, shape, 1e-6, 'the solved shape');
      await t.screenshot(opened, 'pose-link-opened');
      assert.deepEqual(page.errors, []);
      assert.deepEqual(opened.errors, []);
    },
  },
  {
    name: 'copy link: a model the page loaded by its URL (a lone mesh with a generated cage) is named by its path; the link opens it again',
    timeout: 120000,
    async run(t) {
      const spot = readdirSync(join(dist, 'assets')).find((f) => /^spot-.*\.obj$/.test(f));
      const page = await t.page(`index.html?mesh=assets/${spot}&noCage=generate&cageVertices=60`);
      await appReady(page, app, { timeout: 60000 });
      await page.evaluate(`${app}.drag(${app}.handles.groups.length - 1, [0, 0.1, 0.05])`);
      const before = await pose(page);
      const banner = await pressCopyLink(page);
      assert.equal(banner.kind, 'info', banner.text);
      const scene = await decodePose(new URL(page.url()).searchParams.get('pose'));
      assert.equal(scene.mesh, `assets/${spot}`, 'the mesh by its path from the page');
      assert.deepEqual(scene.generateCage, { vertices: 60 }, 'its cage generated again');
      const opened = await t.page(null);
      await opened.goto(page.url());
      await appReady(opened, app, { timeout: 60000 });
      const after = await pose(opened);
      assert.equal(after.model, before.model);
      assert.equal(await opened.evaluate(`${app}.model.cage.positions.length`), await page.evaluate(`${app}.model.cage.positions.length`), 'the same generated cage');
      assert.deepEqual(after.handles.map((h) => h.vertices), before.handles.map((h) => h.vertices));
      assertClose(after.targets, before.targets, 1e-12, 'the targets');
      assert.deepEqual(opened.errors, []);
    },
  },
  {
    name: 'copy link: a model from files or a pose too long for a link gets none and the banner says why; a cut link says so',
    timeout: 120000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      // The bar's own mesh and cage as files (exported and opened again, as if dropped).
      await page.evaluate(async () => {
        const a = globalThis.subspaceDeformer;
        const [mesh, cage] = [await a.exportObj('mesh'), await a.exportObj('restCage')];
        await a.loadFiles([new File([mesh], 'bar.obj'), new File([cage], 'bar_cage.obj')]);
      });
      let banner = await pressCopyLink(page);
      assert.equal(banner.kind, 'warning');
      assert.match(banner.text, /^No link to this pose: bar\.obj was opened from this computer, and a link cannot carry a file/);
      assert.match(banner.text, /save scene/);
      assert.ok(!page.url().includes('pose='), 'the URL is unchanged');

      // Scattered handle vertices on the fine bar (42,962 vertices): the link would be far too long.
      await page.evaluate(`${app}.loadExample('bar-fine')`);
      await page.evaluate(() => {
        const a = globalThis.subspaceDeformer;
        const n = a.model.mesh.positions.length / 3;
        let seed = 7;
        const random = () => ((seed = (seed * 16807) % 2147483647) / 2147483647);
        const scattered = Array.from({ length: n }, (_, i) => i).filter((i) => i > 2 && random() < 0.4);
        a.setHandles([scattered, [0, 1, 2]], { moving: [1] });
      });
      banner = await pressCopyLink(page);
      assert.equal(banner.kind, 'warning');
      assert.match(banner.text, /^No link to this pose: the link would be [\d,]+ characters long, more than the 8,000/);
      await t.screenshot(page, 'pose-link-too-long');

      // A link cut short: the banner says so, the app starts with its default example.
      const cut = await t.page('index.html?pose=1.q1ZKzs8rSc0rUbI');
      await appReady(cut);
      await cut.waitForFunction(() => !document.querySelector('.sd-banner').hidden);
      assert.match(await cut.locator('.sd-banner .sd-message').textContent(), /pose: this link's pose cannot be read .*cut short/);
      assert.equal(await cut.evaluate(`${app}.model.name`), 'bar');
      assert.deepEqual(page.errors, []);
    },
  },
];
