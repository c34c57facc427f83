// Rendering is decoupled from the solver (the page draws at its own frame rate however slow the solve: here
// frames keep coming, each redrawn, while a solver reply is outstanding), the worker's
// normals are right, ARAP converges after a large pull instead of hitting its cap, and scenes go through the
// shared parser (solver/scene.js) with its messages, and large meshes draw their coarse motion proxy while a
// software renderer is in motion.
import assert from 'node:assert/strict';
import { extentAlong } from './geometry.mjs';
import { appReady, installReplyGate } from './app_probe.mjs';

export default [
  {
    name: 'animation frames keep coming, each redrawn, during a drag while a solver request is outstanding',
    timeout: 45000,
    async run(t) {
      const page = await t.page(null);
      await installReplyGate(page);
      await page.goto(`${t.url}index.html`);
      await appReady(page);
      const r = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        const gate = globalThis.replyGate;
        await app.solve();
        const group = app.handles.groups.findIndex((g) => g.moving);
        const viewport = app.views[0].viewport;
        let renders = 0;
        const render = viewport.render;
        viewport.render = function () { renders++; return render.call(this); };
        // The solver's replies are held (as a solver far slower than a frame would be) while the handle moves
        // every frame: the page must go on drawing without them.
        gate.hold();
        let frames = 0;
        let heldFrames = 0;
        let rendersAtFirstHeld = 0;
        await new Promise((resolve) => {
          const tick = () => {
            if (gate.held > 0 && heldFrames++ === 0) rendersAtFirstHeld = renders;
            if (heldFrames > 10 || frames >= 300) return resolve();
            frames++;
            app.handles.setTransform(group, [0, 0.8 * Math.sin(0.1 * frames), 0]);
            requestAnimationFrame(tick);
          };
          requestAnimationFrame(tick);
        });
        const held = gate.held;
        const heldRenders = renders - rendersAtFirstHeld;
        viewport.render = render;
        gate.release();
        const stats = await app.solve();
        return { held, heldRenders, state: stats.state, stopReason: stats.stopReason };
      });
      assert.ok(r.held >= 1, `${r.held} solver replies held`);
      // The page does not wait for the solver: the ten frames after its reply was due were each redrawn (the
      // handle moved every frame).
      assert.ok(r.heldRenders >= 9, `${r.heldRenders} redraws in 10 frames while the solver's reply was outstanding`);
      assert.equal(r.state, 'converged', `${r.state}: ${r.stopReason}`);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'normals computed in the worker are unit length and match three.js computeVertexNormals',
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const r = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.drag(1, [0, 0.6, 0.2], { axis: [0, 0, 1], angle: 0.5 });
        const geometry = app.views[0].viewport.meshView.geometry;
        const normals = geometry.attributes.normal.array;
        const reference = geometry.clone();
        reference.computeVertexNormals();
        const expected = reference.attributes.normal.array;
        let worstLength = 0;
        let worstDot = 1;
        for (let i = 0; i < normals.length; i += 3) {
          const length = Math.hypot(normals[i], normals[i + 1], normals[i + 2]);
          worstLength = Math.max(worstLength, Math.abs(length - 1));
          worstDot = Math.min(worstDot, normals[i] * expected[i] + normals[i + 1] * expected[i + 1] + normals[i + 2] * expected[i + 2]);
        }
        // The normals belong to the positions drawn (the worker sent both for the same iterate).
        const drawn = geometry.attributes.position.array;
        const solver = app.positions();
        let worstPosition = 0;
        for (let i = 0; i < drawn.length; ++i) worstPosition = Math.max(worstPosition, Math.abs(drawn[i] - solver[i]));
        return { count: normals.length / 3, worstLength, worstDot, worstPosition };
      });
      assert.ok(r.count > 100);
      assert.ok(r.worstLength < 1e-5, `a normal's length is off by ${r.worstLength}`);
      assert.ok(r.worstDot > 1 - 1e-5, `a normal deviates from three.js's: cos = ${r.worstDot}`);
      assert.ok(r.worstPosition < 1e-5, `drawn positions differ from the solver's by ${r.worstPosition}`);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'ARAP converges after a large pull (its own iteration cap), scenes go through the shared parser',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const [lo, hi] = extentAlong(await page.evaluate(() => Array.from(globalThis.subspaceDeformer.restPositions())));
      // Plain local-global (arapAcceleration 0) needs more than the Gauss-Newton cap of 100 here; the default
      // Anderson acceleration far fewer. Both must converge under ARAP's own cap.
      const pull = (arapAcceleration) => page.evaluate(async ({ lift, arapAcceleration }) => {
        const app = globalThis.subspaceDeformer;
        app.setOptions({ method: 'arap', arapAcceleration });
        await app.resolveFromRest();
        return app.drag(1, [0, lift, 0]);
      }, { lift: 0.3 * (hi - lo), arapAcceleration });
      const plain = await pull(0);
      assert.equal(plain.state, 'converged', `plain ARAP: ${plain.state} ${plain.stopReason} after ${plain.iterations} iterations`);
      assert.ok(plain.iterations > 100, `plain ARAP needed ${plain.iterations} iterations (more than the Gauss-Newton cap of 100)`);
      const stats = await pull(5);
      assert.equal(stats.state, 'converged', `ARAP: ${stats.state} ${stats.stopReason} after ${stats.iterations} iterations`);
      assert.ok(stats.iterations < plain.iterations / 2, `accelerated ARAP: ${stats.iterations} iterations, plain ${plain.iterations}`);
      // A saved ARAP scene keeps ARAP's cap and loads back (the app's settings from the scene's "solver").
      const scene = await page.evaluate(() => globalThis.subspaceDeformer.sceneJson());
      assert.equal(scene.solver.method, 'arap');
      assert.equal(scene.solver.maxIterations, 1000);
      // Scene errors are the parser's (the CLI's) messages, and the model stays.
      const bad = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        const error = await app.loadScene({ example: 'bar', handles: [], solver: { method: 'magic' } }).catch((e) => e);
        return { error: error.message, type: error.name, code: error.code, banner: document.querySelector('.sd-banner').textContent, model: app.model.name };
      });
      assert.match(bad.error, /solver\.method must be one of 'subspace', 'full', 'arap'/);
      assert.deepEqual([bad.type, bad.code], ['InputError', 'invalid_argument'], 'scripts get the typed error of the library');
      assert.match(bad.banner, /previous model is kept/);
      assert.equal(bad.model, 'bar');
      // A scene with handles only applies to the model on screen, with degrees and a rotation center.
      const applied = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.loadScene({ handles: [{ vertices: [0] }, { vertices: [5, 6], rotate: { axis: [0, 0, 1], degrees: 30, center: [0, 0, 0] } }],
          solver: { method: 'subspace', maxIterations: 40, arapEnergyTolerance: 1e-6 } });
        return { model: app.model.name, scene: app.sceneJson(), settings: { ...app.settings } };
      });
      assert.equal(applied.model, 'bar');
      assert.equal(applied.scene.handles.length, 2);
      assert.ok(Math.abs(applied.scene.handles[1].rotate.angle - Math.PI / 6) < 1e-9, `angle ${applied.scene.handles[1].rotate.angle}`);
      assert.equal(applied.settings.maxIterations, 40);
      assert.equal(applied.settings.arapMaxIterations, 1000);
      assert.equal(applied.scene.solver.arapEnergyTolerance, 1e-6);
      const errors = page.errors.filter((e) => !/solver\.method/.test(e));
      assert.deepEqual(errors, []);
    },
  },
  {
    name: 'a large mesh draws its coarse proxy while dragging on software WebGL, and the full mesh once still',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html?example=bar-fine');
      await appReady(page);
      const drag = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        const meshView = app.views[0].viewport.meshView;
        const group = app.handles.groups.findIndex((g) => g.moving);
        // The handle moves every frame until five frames have drawn the proxy (the first changes start the
        // motion; a frame far behind the previous change, on a loaded machine, counts as still) or 300 have not.
        let frames = 0;
        let proxyFrames = 0;
        await new Promise((resolve) => {
          const tick = () => {
            if (meshView.drawingProxy) proxyFrames++;
            if (proxyFrames >= 5 || frames >= 300) return resolve();
            frames++;
            app.handles.setTransform(group, [0, 0.5 * Math.sin(0.2 * frames), 0]);
            requestAnimationFrame(tick);
          };
          requestAnimationFrame(tick);
        });
        await app.solve();
        return { frames, proxyFrames };
      });
      // Still again: the view draws the full mesh at full resolution once it has settled.
      await page.waitForFunction(() => !globalThis.subspaceDeformer.views[0].viewport.inMotion, null, { polling: 'raf' });
      const r = await page.evaluate(() => {
        const viewport = globalThis.subspaceDeformer.views[0].viewport;
        const meshView = viewport.meshView;
        return {
          software: viewport.software,
          triangles: meshView.geometry.index.count / 3,
          proxyTriangles: meshView.proxy ? meshView.proxy.geometry.index.count / 3 : 0,
          sharesPositions: meshView.proxy?.geometry.attributes.position === meshView.geometry.attributes.position,
          stillProxy: meshView.drawingProxy,
          stillMeshVisible: meshView.mesh.visible,
          stillPixelRatio: viewport.renderer.getPixelRatio(),
          fullPixelRatio: viewport.fullPixelRatio,
        };
      });
      assert.ok(r.software, 'headless Chromium renders with SwiftShader here');
      assert.ok(r.proxyTriangles > 0 && r.proxyTriangles < r.triangles / 4, `proxy ${r.proxyTriangles} of ${r.triangles} triangles`);
      assert.ok(r.sharesPositions, 'the proxy follows the solver through the shared position buffer');
      assert.equal(drag.proxyFrames, 5, `${drag.proxyFrames} of ${drag.frames} drag frames drew the proxy`);
      assert.equal(r.stillProxy, false, 'still: the full mesh is drawn again');
      assert.equal(r.stillMeshVisible, true);
      assert.equal(r.stillPixelRatio, r.fullPixelRatio);
      await t.screenshot(page, 'bar-fine-still');
      assert.deepEqual(page.errors, []);
    },
  },
];
