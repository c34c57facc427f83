// Issue 31, item 2: a mesh without a cage as the first model is no dead end. In the app (?mesh=) the banner
// offers "Generate cage" and "Deform without a cage (spectral basis)" and each works, as does the panel's
// "generate cage for this mesh"; `ready` waits for the choice and the app dispatches 'nocage' { choice }.
// ?noCage=, the element's no-cage attribute and mount()'s noCage choose up front. The lone mesh is the built-in
// bar's mesh without its cage, served to the page as lone-bar.obj. (Before: no buttons, the panel's button did
// nothing and `ready` rejected.)
import assert from 'node:assert/strict';
import { VOLUME_TOLERANCE, volume } from './geometry.mjs';
import { appReady, appShown } from './app_probe.mjs';

const app = 'globalThis.subspaceDeformer';
const SPECTRAL = 'Deform without a cage (spectral basis)';

/** Serves the bar's mesh alone (no cage) at <page folder>/lone-bar.obj to `page`, from the default example. */
async function routeLoneBar(page) {
  await appReady(page);
  const obj = await page.evaluate(`${app}.exportObj('mesh')`);
  await page.route('**/lone-bar.obj', (route) => route.fulfill({ contentType: 'text/plain', body: obj }));
}

/** Opens `path` in `page` and records the app's 'nocage' events in globalThis.nocage once the app exists. */
async function openApp(page, url) {
  await page.goto(url);
  await page.waitForFunction(`!!${app}`);
  await page.evaluate(`globalThis.nocage = []; ${app}.addEventListener('nocage', (e) => globalThis.nocage.push(e.choice))`);
}

/** 'resolved', 'rejected' or 'pending' (after a short wait) for the page's promise expression. */
const settled = (page, promise) => page.evaluate(`Promise.race([(${promise}).then(() => 'resolved', () => 'rejected'),
  new Promise((resolve) => setTimeout(() => resolve('pending'), 500))])`);

/** Drags group 1 of `get` (the app or an element), checks the mesh followed with its volume kept. */
async function dragAndCheck(page, get) {
  const rest = await page.evaluate(`Array.from(${get}.restPositions())`);
  const indices = await page.evaluate(`Array.from(${get}.indices())`);
  const stats = await page.evaluate(`${get}.drag(1, [0, 0.6, 0])`);
  assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
  const positions = await page.evaluate(`Array.from(${get}.positions())`);
  let moved = 0;
  for (let i = 0; i < rest.length; ++i) moved = Math.max(moved, Math.abs(positions[i] - rest[i]));
  assert.ok(moved > 0.3, `the mesh moved by at most ${moved}`);
  const v0 = volume(rest, indices);
  assert.ok(Math.abs(volume(positions, indices) - v0) / v0 <= VOLUME_TOLERANCE, 'the volume is kept');
}

/** Waits for the lone mesh's offer and checks its two buttons are there. */
async function offer(page) {
  await page.waitForFunction(() => /lone-bar\.obj has no cage/.test(document.querySelector('.sd-banner')?.textContent), null, { timeout: 30000 });
  const banner = page.locator('.sd-banner');
  assert.equal(await banner.getByRole('button', { name: 'Generate cage' }).count(), 1, 'a "Generate cage" button');
  assert.equal(await banner.getAttribute('data-kind'), 'info', 'a choice to make, not styled as an error');
  assert.equal(await banner.getByRole('button', { name: SPECTRAL }).count(), 1, 'a spectral button');
  assert.equal(await settled(page, `${app}.ready`), 'pending', 'ready waits for the choice');
  return banner;
}

export default [
  {
    name: '?mesh=<a lone mesh> first: the banner\'s "Generate cage" and spectral buttons and the panel\'s generate cage each make it deformable',
    timeout: 180000,
    async run(t) {
      const page = await t.page('index.html');
      await routeLoneBar(page);
      const url = `${t.url}index.html?mesh=lone-bar.obj`;

      // The spectral basis, 20 modes.
      await openApp(page, url);
      let banner = await offer(page);
      await t.screenshot(page, 'no-cage-first-offer');
      await banner.locator('label', { hasText: 'modes' }).locator('input').fill('20');
      await banner.getByRole('button', { name: SPECTRAL }).click();
      assert.equal(await page.evaluate(`${app}.ready.then((m) => m.name)`), 'lone-bar.obj');
      assert.deepEqual(await page.evaluate(`[${app}.model.basis, ${app}.model.basisSize, globalThis.nocage]`), ['spectral', 24, ['spectral']]);
      assert.equal(await page.evaluate(`${app}.banner.text`), '');
      await dragAndCheck(page, app);

      // A generated cage of about 40 vertices.
      await openApp(page, url);
      banner = await offer(page);
      await banner.locator('label', { hasText: 'cage vertices' }).locator('input').fill('40');
      await banner.getByRole('button', { name: 'Generate cage' }).click();
      assert.equal(await page.evaluate(`${app}.ready.then((m) => m.name)`), 'lone-bar.obj');
      const generated = await page.evaluate(`[${app}.model.basis, ${app}.model.cage.positions.length / 3, globalThis.nocage]`);
      assert.equal(generated[0], 'cage');
      assert.ok(generated[1] >= 40 && generated[1] <= 48, `a cage of ${generated[1]} vertices (asked for 40)`);
      assert.deepEqual(generated[2], ['generate']);
      await dragAndCheck(page, app);
      await appShown(page);
      await t.screenshot(page, 'no-cage-first-generated');

      // The panel's "generate cage for this mesh" while the banner asks: the waiting mesh gets the cage.
      await openApp(page, url);
      await offer(page);
      await page.evaluate(`${app}.setOptions({ cageVertices: 40 })`);
      await page.locator('.lil-gui button', { hasText: 'generate cage for this mesh' }).click();
      assert.equal(await page.evaluate(`${app}.ready.then((m) => m.name)`), 'lone-bar.obj');
      assert.deepEqual(await page.evaluate(`[${app}.model.basis, globalThis.nocage]`), ['cage', ['generate']]);
      await dragAndCheck(page, app);
      assert.deepEqual(page.errors.filter((e) => !/lone-bar\.obj/.test(e)), []);
    },
  },
  {
    name: '?noCage=spectral, <subspace-deformer no-cage="spectral"> and mount({ noCage: \'generate\' }): ready resolves deformable, the event names the choice',
    timeout: 180000,
    async run(t) {
      const page = await t.page('index.html');
      await routeLoneBar(page);
      // Every banner text shown, however briefly: a choice made up front shows no "has no cage" failure first.
      await page.addInitScript(() => {
        globalThis.bannersShown = [];
        new MutationObserver(() => {
          for (const b of document.querySelectorAll('.sd-banner')) if (!b.hidden) globalThis.bannersShown.push(b.textContent);
        }).observe(document, { subtree: true, childList: true, characterData: true, attributes: true });
      });
      // The app's URL parameter: no offer, the spectral basis at once.
      await openApp(page, `${t.url}index.html?mesh=lone-bar.obj&noCage=spectral&spectralModes=20`);
      assert.equal(await page.evaluate(`${app}.ready.then((m) => m.name)`), 'lone-bar.obj');
      assert.deepEqual(await page.evaluate(`[${app}.model.basis, ${app}.banner.text, globalThis.nocage]`), ['spectral', '', ['spectral']]);
      assert.deepEqual(await page.evaluate('globalThis.bannersShown.filter((text) => /no cage/.test(text))'), [], 'no "has no cage" banner flashed');
      await dragAndCheck(page, app);

      // The element's attribute, and mount()'s option in the same page.
      const html = '<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,"></head><body>' +
        '<subspace-deformer id="e" mesh="lone-bar.obj" no-cage="spectral" spectralModes="20" style="height: 300px"></subspace-deformer>' +
        '<div id="m" style="height: 300px"></div><script>globalThis.events = [];' +
        "document.getElementById('e').addEventListener('nocage', (e) => globalThis.events.push(['element', e.detail.choice, e.detail.model.name]));</script>" +
        '<script type="module">import { mount } from "./subspace-deformer.js";' +
        "globalThis.mounted = mount(document.getElementById('m'), { mesh: 'lone-bar.obj', noCage: 'generate', settings: { cageVertices: 40 } });" +
        "globalThis.mounted.addEventListener('nocage', (e) => globalThis.events.push(['mount', e.choice, e.model.name]));</script></body></html>";
      await page.route('**/no-cage-embed.html', (route) => route.fulfill({ contentType: 'text/html', body: html }));
      await page.goto(`${t.url}no-cage-embed.html`);
      const el = "document.getElementById('e')";
      await appReady(page, `${el}.app`, { timeout: 60000 });
      await appReady(page, 'globalThis.mounted', { timeout: 60000 });
      assert.equal(await page.evaluate(`${el}.ready.then((m) => m.name)`), 'lone-bar.obj');
      assert.deepEqual(await page.evaluate('globalThis.events.sort()'),
        [['element', 'spectral', 'lone-bar.obj'], ['mount', 'generate', 'lone-bar.obj']]);
      assert.deepEqual(await page.evaluate('globalThis.bannersShown.filter((text) => /no cage/.test(text))'), [], 'no banner flashed in the embeds');
      assert.equal(await page.evaluate(`${el}.app.model.basis`), 'spectral');
      const cage = await page.evaluate('globalThis.mounted.model.cage.positions.length / 3');
      assert.ok(cage >= 40 && cage <= 48, `mount()'s generated cage has ${cage} vertices`);
      await dragAndCheck(page, el);
      await dragAndCheck(page, 'globalThis.mounted');
      assert.deepEqual(page.errors.filter((e) => !/lone-bar\.obj/.test(e)), []);
    },
  },
];
