// The app in real Chromium: loads cleanly, handles + drag deform the mesh with the volume kept, compare mode,
// bad input reported in the page with the previous model kept, several embeds per page, URL parameters.
import assert from 'node:assert/strict';
import { VOLUME_TOLERANCE, volume } from './geometry.mjs';
import { appReady, appShown, dragUp, project as screenPoint } from './app_probe.mjs';

/** Counts pixels of the app's screenshot that differ from the background, per view third. */
async function nonBackgroundFractions(page, views) {
  return page.evaluate(async (views) => {
    const url = globalThis.subspaceDeformer.screenshot();
    const img = new Image();
    img.src = url;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width;
    c.height = img.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const data = ctx.getImageData(0, 0, c.width, c.height).data;
    const counts = new Array(views).fill(0);
    const bg = [0xee, 0xf1, 0xf5];
    for (let y = 0; y < c.height; y += 2) {
      for (let x = 0; x < c.width; x += 2) {
        const i = 4 * (y * c.width + x);
        if (Math.abs(data[i] - bg[0]) + Math.abs(data[i + 1] - bg[1]) + Math.abs(data[i + 2] - bg[2]) > 30) {
          counts[Math.min(views - 1, Math.floor((x * views) / c.width))]++;
        }
      }
    }
    return counts.map((n) => n / ((c.width * c.height) / 4 / views));
  }, views);
}

export default [
  {
    name: 'the page loads the default example with no console errors',
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const info = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        return { name: app.model.name, vertices: app.stats.vertexCount, groups: app.handles.groups.map((g) => g.moving),
          canvases: document.querySelectorAll('canvas.sd-canvas').length, examples: app.exampleNames };
      });
      assert.ok(info.vertices > 100, `default example has ${info.vertices} vertices`);
      assert.equal(info.canvases, 1);
      assert.deepEqual(info.groups, [false, true], 'default handles: one fixed end, one moving end');
      assert.ok(info.examples.length >= 2, `example menu: ${info.examples}`);
      await appShown(page);
      await t.screenshot(page, 'app-default');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'handles picked with the mouse (click, brush, key M) and dragged with the gizmo',
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      // Screen position of a world point (an expression over `app`).
      const project = (expr) => screenPoint(page, expr);
      // The vertex nearest the camera in the middle of the model.
      const mid = await project(`(() => {
        const P = app.model.mesh.positions, eye = app.views[0].viewport.camera.position;
        const c = app.views[0].viewport.controls.target;
        let best = 0, bestD = Infinity;
        for (let i = 0; i < P.length / 3; ++i) {
          const d = (P[3*i]-c.x)**2 + (P[3*i+1]-c.y)**2 + 0.3 * ((P[3*i]-eye.x)**2 + (P[3*i+1]-eye.y)**2 + (P[3*i+2]-eye.z)**2);
          if (d < bestD) { bestD = d; best = i; }
        }
        return eye.clone().fromArray(P, 3 * best);
      })()`);
      await page.mouse.click(mid.x, mid.y);
      const selection = () => page.evaluate(() => globalThis.subspaceDeformer.selection.size);
      assert.equal(await selection(), 1, 'a click selects one vertex');
      await page.keyboard.down('Shift');
      await page.mouse.move(mid.x - 15, mid.y);
      await page.mouse.down();
      for (let i = 0; i <= 6; ++i) await page.mouse.move(mid.x - 15 + 5 * i, mid.y);
      await page.mouse.up();
      await page.keyboard.up('Shift');
      const brushed = await selection();
      assert.ok(brushed > 3, `the brush selected ${brushed} vertices`);
      await page.keyboard.press('m');
      const groups = await page.evaluate(() => globalThis.subspaceDeformer.handles.groups.map((g) => [g.vertices.length, g.moving]));
      assert.deepEqual(groups.at(-1), [brushed, true], 'M made the selection a moving group');
      // Drag the gizmo's centre (free translation) upwards.
      await dragUp(page, await project('app.views[0].gizmo.pivot.position.clone()'));
      const translate = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        return app.handles.groups[app.handles.active].translate;
      });
      assert.ok(Math.hypot(...translate) > 1e-3, `the gizmo moved the group by ${translate}`);
      // A drag in the screen plane holds the group only across the camera's lines (its depth is the solver's).
      const seen = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        return { line: app.handles.groups[app.handles.active].line, eye: app.views[0].viewport.camera.position.toArray(),
          saved: app.handles.toScene()[app.handles.active] };
      });
      assert.deepEqual(seen.line, { from: seen.eye }, 'the centre drag gave the group the camera\'s lines');
      assert.deepEqual(seen.saved.from, seen.eye, 'the scene keeps the lines as "from"');
      const stats = await page.evaluate(() => globalThis.subspaceDeformer.solve());
      assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
      assert.ok(Math.abs(stats.volumeRelError) <= VOLUME_TOLERANCE, `volume error ${stats.volumeRelError}`);
      await page.keyboard.press('Control+z');
      const undone = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        return app.handles.groups[app.handles.active].translate;
      });
      assert.deepEqual(undone, [0, 0, 0], 'Ctrl+Z undid the gizmo drag');
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.handles.lines().some(Boolean)), false, 'and its lines');
      await t.screenshot(page, 'app-mouse');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'several embeds on one page; handles + drag through the element API deform the mesh and keep the volume',
    timeout: 45000,
    async run(t) {
      const page = await t.page('embed-example.html');
      const el = "document.getElementById('bar')";
      await appReady(page, el);
      const rest = await page.evaluate(`Array.from(${el}.restPositions())`);
      const indices = await page.evaluate(`Array.from(${el}.indices())`);
      // Handles chosen here: the 5% ends of the bar along x.
      let lo = Infinity;
      let hi = -Infinity;
      for (let v = 0; v < rest.length; v += 3) {
        lo = Math.min(lo, rest[v]);
        hi = Math.max(hi, rest[v]);
      }
      const left = [];
      const right = [];
      for (let v = 0; v < rest.length / 3; ++v) {
        if (rest[3 * v] < lo + 0.05 * (hi - lo)) left.push(v);
        if (rest[3 * v] > hi - 0.05 * (hi - lo)) right.push(v);
      }
      await page.evaluate(([l, r]) => document.getElementById('bar').setHandles([l, r], { moving: [1] }), [left, right]);
      const lift = 0.25 * (hi - lo);
      const stats = await page.evaluate((lift) => document.getElementById('bar').drag(1, [0, lift, 0]), lift);
      assert.equal(stats.state, 'converged', `solver state ${stats.state}: ${stats.stopReason}`);
      const positions = await page.evaluate(`Array.from(${el}.positions())`);
      let moved = 0;
      for (let i = 0; i < positions.length; ++i) moved = Math.max(moved, Math.abs(positions[i] - rest[i]));
      assert.ok(moved > 0.5 * lift, `the mesh moved by at most ${moved}, expected about ${lift}`);
      // The moving end reached its target (soft constraint: within 10% of the lift).
      let err = 0;
      for (const v of right) err = Math.max(err, Math.abs(positions[3 * v + 1] - rest[3 * v + 1] - lift));
      assert.ok(err < 0.1 * lift, `moving handle misses its target by ${err}`);
      const v0 = volume(rest, indices);
      const v1 = volume(positions, indices);
      assert.ok(Math.abs(v1 - v0) / Math.abs(v0) <= VOLUME_TOLERANCE, `volume changed by ${(v1 - v0) / v0} (tolerance ${VOLUME_TOLERANCE})`);
      assert.ok(Math.abs(stats.volumeRelError) <= VOLUME_TOLERANCE, `solver reports volume error ${stats.volumeRelError}`);
      await t.screenshot(page, 'embed-dragged');
      // The same page holds two more instances (a compare view and a scripted one): all loaded and working.
      await page.waitForFunction(() => /converged: true/.test(document.getElementById('scripted-result').textContent), null, { timeout: 25000 });
      const views = await page.evaluate(async () => {
        const els = [...document.querySelectorAll('subspace-deformer')];
        await Promise.all(els.map((e) => e.ready));
        return els.map((e) => e.statsAll().length);
      });
      assert.deepEqual(views, [1, 3, 1]);
      await page.evaluate(() => document.getElementById('compare').scrollIntoView());
      await t.screenshot(page, 'embed-page');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'compare mode renders ARAP | subspace | full with the same handles',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html?compare=arap,subspace,full');
      await appReady(page);
      const stats = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.drag(1, [0, 0.5, 0]);
        return app.statsAll();
      });
      assert.deepEqual(stats.map((s) => s.method), ['arap', 'subspace', 'full']);
      for (const s of stats) assert.ok(['converged', 'stopped'].includes(s.state), `${s.method}: ${s.state} ${s.stopReason}`);
      for (const s of stats) assert.ok(s.iterations > 0, `${s.method} iterated`);
      const fractions = await nonBackgroundFractions(page, 3);
      for (const [i, f] of fractions.entries()) assert.ok(f > 0.02, `view ${i} shows almost nothing (${(100 * f).toFixed(1)}% drawn)`);
      await t.screenshot(page, 'compare');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'a bad file shows an error in the page and keeps the previous model',
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const before = await page.evaluate(() => ({ name: globalThis.subspaceDeformer.model.name, n: globalThis.subspaceDeformer.stats.vertexCount }));
      const input = page.locator('.sd-app input[type=file]');
      // Garbage bytes as an OBJ, with a cage that parses: the reader's error must reach the page.
      const cage = 'v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n' +
        'f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n';
      await input.setInputFiles([
        { name: 'broken.obj', mimeType: 'text/plain', buffer: Buffer.from('v 0 0 0\nv 1 0 zz\nf 1 2 99999\n'.repeat(50)) },
        { name: 'cage.obj', mimeType: 'text/plain', buffer: Buffer.from(cage) },
      ]);
      const banner = page.locator('.sd-banner');
      await banner.waitFor({ state: 'visible' });
      const text = await banner.innerText();
      assert.match(text, /broken\.obj/, `the error names the file: ${text}`);
      assert.match(text, /previous model is kept/);
      await t.screenshot(page, 'bad-file');
      // A mesh with no cage: a clear message.
      await input.setInputFiles([{ name: 'lonely.obj', mimeType: 'text/plain', buffer: Buffer.from(cage) }]);
      await page.waitForFunction(() => /lonely\.obj has no cage/.test(document.querySelector('.sd-banner').textContent));
      const after = await page.evaluate(() => ({ name: globalThis.subspaceDeformer.model.name, n: globalThis.subspaceDeformer.stats.vertexCount }));
      assert.deepEqual(after, before, 'the previous model is still loaded');
      // ... and it still deforms.
      const stats = await page.evaluate(() => globalThis.subspaceDeformer.drag(1, [0, 0.3, 0]));
      assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
      const errors = page.errors.filter((e) => !/broken\.obj|lonely\.obj/.test(e));
      assert.deepEqual(errors, []);
    },
  },
  {
    name: 'URL parameters choose the example or a scene',
    async run(t) {
      const page = await t.page('index.html?example=sphere');
      await appReady(page);
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.model.name), 'sphere');
      const scene = { example: 'bar', handles: [{ vertices: [0, 1, 2] }, { vertices: [10, 11], translate: [0, 0.2, 0] }],
        solver: { method: 'subspace', jacobian: 'fast', volume: true, maxIterations: 50 } };
      await page.route('**/scenes/test-scene.json', (route) => route.fulfill({ contentType: 'application/json', body: JSON.stringify(scene) }));
      await page.goto(`${t.url}index.html?scene=scenes/test-scene.json`);
      await appReady(page);
      const got = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        return { name: app.model.name, scene: app.sceneJson() };
      });
      assert.equal(got.name, 'bar');
      assert.deepEqual(got.scene.handles, scene.handles);
      assert.equal(got.scene.solver.maxIterations, 50);
      assert.deepEqual(page.errors, []);
    },
  },
];
