// Generated cages in the app: the built-in bunny example gets its cage in the worker on load
// (URL parameter and embed attribute), and a lone mesh picked with the file chooser gets one from the
// "Generate cage" banner action; both then deform with the volume kept.
import assert from 'node:assert/strict';
import { VOLUME_TOLERANCE, ellipsoidObj, volume } from './geometry.mjs';
import { animationFrames, appReady, appShown, installReplyGate } from './app_probe.mjs';

const BUNNY_CAGE = 120; // the bunny example's target cage size (web/lib/examples.js)

function maxDifference(a, b) {
  let d = 0;
  for (let i = 0; i < a.length; ++i) d = Math.max(d, Math.abs(a[i] - b[i]));
  return d;
}


/** Drags the moving group of the app/element `get` by `lift` and checks the mesh moved with the volume kept. */
async function dragAndCheck(page, get, translation) {
  const rest = await page.evaluate(`Array.from(${get}.restPositions())`);
  const indices = await page.evaluate(`Array.from(${get}.indices())`);
  const stats = await page.evaluate(`${get}.drag(1, ${JSON.stringify(translation)})`);
  assert.equal(stats.state, 'converged', `solver state ${stats.state}: ${stats.stopReason}`);
  const positions = await page.evaluate(`Array.from(${get}.positions())`);
  const lift = Math.hypot(...translation);
  const moved = maxDifference(positions, rest);
  assert.ok(moved > 0.5 * lift, `the mesh moved by at most ${moved}, expected about ${lift}`);
  const v0 = volume(rest, indices);
  const v1 = volume(positions, indices);
  assert.ok(Math.abs(v1 - v0) / Math.abs(v0) <= VOLUME_TOLERANCE, `volume changed by ${(v1 - v0) / v0} (tolerance ${VOLUME_TOLERANCE})`);
  assert.ok(Math.abs(stats.volumeRelError) <= VOLUME_TOLERANCE, `solver reports volume error ${stats.volumeRelError}`);
  return stats;
}

export default [
  {
    name: '?example=bunny generates its cage in the worker and is ready to drag',
    timeout: 40000,
    async run(t) {
      const page = await t.page(null);
      // The worker generates the cage (its progress says so), and the main thread stays responsive meanwhile:
      // animation frames keep coming while the load is outstanding (its reply held here, as a slow worker's).
      await installReplyGate(page, { holdAtPhase: 'generating the cage' });
      await page.goto(`${t.url}index.html?example=bunny`);
      await page.waitForFunction(() => globalThis.replyGate?.holding);
      await animationFrames(page, 5);
      const loading = await page.evaluate(() => {
        const name = globalThis.subspaceDeformer.model?.name ?? null;
        globalThis.replyGate.release();
        return name;
      });
      assert.notEqual(loading, 'bunny', 'the frames came while the bunny was loading');
      await appReady(page);
      const info = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        return { name: app.model.name, vertices: app.stats.vertexCount, cageVertices: app.model.cage.positions.length / 3,
          generated: app.model.generatedCage, groups: app.handles.groups.map((g) => g.moving), examples: app.exampleNames };
      });
      assert.equal(info.name, 'bunny');
      assert.equal(info.vertices, 1839, 'the npm bunny has 1839 vertices');
      assert.ok(info.examples.includes('bunny'), `example menu: ${info.examples}`);
      assert.ok(info.generated, 'the model reports its generated cage');
      assert.ok(info.cageVertices >= BUNNY_CAGE && info.cageVertices <= 1.2 * BUNNY_CAGE, `cage has ${info.cageVertices} vertices`);
      assert.ok(info.generated.volumeRatio > 1, `cage/mesh volume ratio ${info.generated.volumeRatio}`);
      assert.deepEqual(info.groups, [false, true], 'default handles: feet fixed, ears moving');
      // The moving group is the top (ears): its vertices are all in the upper part along y.
      const heights = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        const P = app.model.mesh.positions;
        let lo = Infinity;
        let hi = -Infinity;
        for (let i = 1; i < P.length; i += 3) {
          lo = Math.min(lo, P[i]);
          hi = Math.max(hi, P[i]);
        }
        const t = (v) => (P[3 * v + 1] - lo) / (hi - lo);
        const [fixed, moving] = app.handles.groups;
        return { fixedMax: Math.max(...fixed.vertices.map(t)), movingMin: Math.min(...moving.vertices.map(t)) };
      });
      assert.ok(heights.fixedMax < 0.1 && heights.movingMin > 0.8, `handles at heights ${JSON.stringify(heights)}`);
      await dragAndCheck(page, 'globalThis.subspaceDeformer', [1.5, 1.2, 0]);
      // The generated cage exports at rest (OBJ) with the cage's vertex count.
      const obj = await page.evaluate(() => globalThis.subspaceDeformer.exportObj('restCage'));
      assert.equal(obj.split('\n').filter((l) => l.startsWith('v ')).length, info.cageVertices);
      await appShown(page);
      await t.screenshot(page, 'bunny');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: '<subspace-deformer example="bunny">: the element loads the bunny and deforms it through its API',
    timeout: 40000,
    async run(t) {
      // A course page with one element, served next to the built embed script.
      const html = '<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,">' +
        '<script type="module" src="subspace-deformer.js"></script></head><body>' +
        '<subspace-deformer id="b" example="bunny" panel="none" style="height: 480px"></subspace-deformer></body></html>';
      const page = await t.page(null);
      await page.route('**/bunny-embed.html', (route) => route.fulfill({ contentType: 'text/html', body: html }));
      await page.goto(`${t.url}bunny-embed.html`);
      const el = "document.getElementById('b')";
      await appReady(page, `${el}.app`);
      assert.equal(await page.evaluate(`${el}.app.model.name`), 'bunny');
      await dragAndCheck(page, el, [0, 1.5, 0]);
      await appShown(page, `${el}.app`);
      await t.screenshot(page, 'bunny-embed');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a lone mesh from the file chooser gets a cage from "Generate cage" and becomes draggable',
    timeout: 40000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const choose = async (name, text) => {
        const [chooser] = await Promise.all([
          page.waitForEvent('filechooser'),
          page.evaluate(() => globalThis.subspaceDeformer.openFilePicker()),
        ]);
        await chooser.setFiles([{ name, mimeType: 'text/plain', buffer: Buffer.from(text) }]);
      };
      const banner = page.locator('.sd-banner');
      // A mesh with a fin on one edge (a non-manifold edge no pairing splits) cannot get a cage: the checker's
      // findings, no offer. (An open mesh can: its cage encloses the surface with its holes capped.)
      await choose('fin.obj', `${ellipsoidObj()}v 0 1 0.6\nf 1 2 ${2 + 9 * 20 + 1}\n`);
      await page.waitForFunction(() => /fin\.obj has no cage, and it cannot get/.test(document.querySelector('.sd-banner').textContent));
      assert.match(await banner.innerText(), /non-manifold edge/);
      assert.equal(await banner.getByRole('button', { name: 'Generate cage' }).count(), 0, 'no Generate cage offer for a broken mesh');
      await choose('ellipsoid.obj', ellipsoidObj());
      await page.waitForFunction(() => /ellipsoid\.obj has no cage/.test(document.querySelector('.sd-banner').textContent));
      const field = banner.locator('input[type=number]').first(); // the cage size (the second is the spectral basis' modes)
      assert.equal(Number(await field.inputValue()), 120, 'the size field starts at the default cage size');
      // A large cage takes a while: the progress bar appears, and Cancel keeps the previous model and offers again.
      await field.fill('1000');
      await banner.getByRole('button', { name: 'Generate cage' }).click();
      const progress = page.locator('.sd-progress');
      await progress.waitFor({ state: 'visible' });
      // The bar shows after 250 ms; the worker names the phase once it has started (and checked the mesh).
      await page.waitForFunction(() => /generating a 1000-vertex cage/.test(document.querySelector('.sd-progress').innerText), null, { timeout: 10000 });
      await t.screenshot(page, 'generate-cage-progress');
      await progress.getByRole('button', { name: 'Cancel' }).click();
      await page.waitForFunction(() => /cancelled/.test(document.querySelector('.sd-banner').textContent));
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.model.name), 'bar', 'the previous model is kept');
      await field.fill('40');
      await t.screenshot(page, 'generate-cage-offer');
      await banner.getByRole('button', { name: 'Generate cage' }).click();
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.name === 'ellipsoid.obj', null, { timeout: 30000 });
      const info = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        return { vertices: app.stats.vertexCount, cageVertices: app.model.cage.positions.length / 3, generated: app.model.generatedCage,
          groups: app.handles.groups.map((g) => [g.vertices.length, g.moving]), banner: app.banner.text, scene: app.sceneJson() };
      });
      assert.equal(info.vertices, 182);
      assert.ok(info.cageVertices >= 40 && info.cageVertices <= 48, `cage has ${info.cageVertices} vertices (asked for 40)`);
      assert.equal(info.banner, '', 'the banner is gone');
      assert.deepEqual(info.groups.map((g) => g[1]), [false, true], 'default handles on the new mesh');
      assert.deepEqual(info.scene.generateCage, { vertices: 40 }, 'a saved scene regenerates the cage');
      await dragAndCheck(page, 'globalThis.subspaceDeformer', [0, 0.8, 0]);
      // The generated cage at rest, and the deformed cage, export as OBJ with the same vertex count.
      const [rest, deformed] = await page.evaluate(async () => [
        await globalThis.subspaceDeformer.exportObj('restCage'), await globalThis.subspaceDeformer.exportObj('cage')]);
      const count = (s) => s.split('\n').filter((l) => l.startsWith('v ')).length;
      assert.equal(count(rest), info.cageVertices);
      assert.equal(count(deformed), info.cageVertices);
      assert.notEqual(rest, deformed);
      await appShown(page);
      await t.screenshot(page, 'generate-cage-dragged');
      // "generate cage for this mesh" (panel button) on the loaded model: a new cage, the same handles and drag, still solving well.
      const before = await page.evaluate(() => globalThis.subspaceDeformer.handles.toScene());
      await page.evaluate(() => globalThis.subspaceDeformer.setOptions({ cageVertices: 60 }));
      await page.locator('.lil-gui button', { hasText: 'generate cage for this mesh' }).click();
      // The 40-48-vertex cage is replaced once the new one is bound.
      await page.waitForFunction(() => globalThis.subspaceDeformer.model.cage.positions.length / 3 >= 60, null, { timeout: 20000 });
      const again = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        const stats = await app.solve();
        return { cageVertices: app.model.cage.positions.length / 3, handles: app.handles.toScene(), stats };
      });
      assert.ok(again.cageVertices >= 60 && again.cageVertices <= 72, `regenerated cage has ${again.cageVertices} vertices (asked for 60)`);
      assert.deepEqual(again.handles, before, 'the handle groups and their displacement are kept');
      assert.equal(again.stats.state, 'converged', `${again.stats.state}: ${again.stats.stopReason}`);
      assert.ok(Math.abs(again.stats.volumeRelError) <= VOLUME_TOLERANCE, `volume error ${again.stats.volumeRelError}`);
      assert.deepEqual(page.errors.filter((e) => !/ellipsoid\.obj|open\.obj/.test(e)), []);
    },
  },
];
