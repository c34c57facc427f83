// The skeleton in the app (issue 30): with the bone tool (key B, or the tool strip's bone button by touch) clicks
// on the default bar place joints midway through it, consecutive joints make bones, undo and redo take them back
// in one timeline with the handle edits, and after the drag (the free end folded down by (-1.2, -2.2, 0))
// the worker's report gives each bone its rest length (the length error small) while the sticks follow the
// deformed mesh; the bones go into the saved scene and come back with it. The lesson 'skeleton' brings its bones,
// and compare mode and the step-through show each view's bone errors and multipliers. Screenshots go to test-results/.
import assert from 'node:assert/strict';
import { appReady, appShown, project } from './app_probe.mjs';
import { Fingers, PHONE, tapButton } from './touch.mjs';

const skeleton = (page) => page.evaluate(() => {
  const s = globalThis.subspaceDeformer.skeleton;
  const r = s.report; // its joints: 3 numbers each, flat
  const report = r && { bones: r.bones, joints: Array.from({ length: r.joints.length / 3 }, (_, k) => Array.from(r.joints.slice(3 * k, 3 * k + 3))) };
  return { joints: s.state.joints, bones: s.state.bones, tip: s.state.tip, report };
});

/** The screen position of the rest point (x, 0, 0) on the bar's axis, seen by view 0. */
const onAxis = (page, x) => project(page, `app.views[0].viewport.controls.target.clone().set(${x}, 0, 0)`);

/** The bar's rest extent along x. */
const barSpan = (page) => page.evaluate(() => {
  const P = globalThis.subspaceDeformer.model.mesh.positions;
  let lo = Infinity, hi = -Infinity;
  for (let i = 0; i < P.length; i += 3) { lo = Math.min(lo, P[i]); hi = Math.max(hi, P[i]); }
  return { lo, hi };
});

/** Joints along the bar (x = -2, 0, 1.5 of the arm of length 5): x = 2 is under the gizmo, whose press it is. */
const JOINT_FRACTIONS = [0.1, 0.5, 0.8];

export default [
  {
    name: 'bone tool: clicks place joints inside the bar, bones keep their length through a drag, undo and scenes',
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const centre = await onAxis(page, 0);
    await page.mouse.move(centre.x, centre.y); // the keys are the app's under the pointer
    await page.keyboard.press('b');
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.settings.tool), 'bone', 'B turns the bone tool on');
      assert.equal(await page.locator('.sd-tool[data-action="bone"]').getAttribute('aria-pressed'), 'true');
      const { lo, hi } = await barSpan(page);
      const xs = JOINT_FRACTIONS.map((f) => lo + f * (hi - lo));
      for (const x of xs) {
        const at = await onAxis(page, x);
        await page.mouse.click(at.x, at.y);
        await page.waitForFunction((n) => globalThis.subspaceDeformer.skeleton.state.joints.length === n, xs.indexOf(x) + 1);
      }
      await page.waitForFunction(() => globalThis.subspaceDeformer.skeleton.report?.bones.length === 2, null, { timeout: 20000 });
      let s = await skeleton(page);
      assert.deepEqual(s.bones, [[0, 1], [1, 2]], 'consecutive joints make a chain of bones');
      s.joints.forEach((p, k) => {
        // Midway through the bar: on its axis (y and z near 0: the capsule is symmetric), at the clicked x.
        assert.ok(Math.abs(p[0] - xs[k]) < 0.05 * (hi - lo), `joint ${k} at x ${p[0].toFixed(3)}, clicked ${xs[k].toFixed(3)}`);
        assert.ok(Math.hypot(p[1], p[2]) < 0.03 * (hi - lo), `joint ${k} is ${Math.hypot(p[1], p[2]).toFixed(4)} off the axis`);
      });
      await appShown(page);
      await t.screenshot(page, 'skeleton-placed');

      // Undo takes back the last bone (and its joint), redo brings it back; the handles' undo comes after.
      await page.keyboard.press('Control+z');
      await page.waitForFunction(() => globalThis.subspaceDeformer.skeleton.state.bones.length === 1);
      await page.keyboard.press('Control+Shift+z');
      await page.waitForFunction(() => globalThis.subspaceDeformer.skeleton.state.bones.length === 2);

      // The drag of the free end; the bones keep their rest lengths and follow the mesh.
      const stats = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        const moving = app.handles.groups.findIndex((g) => g.moving);
        return app.drag(moving, [-1.2, -2.2, 0]); // the bar example is the arm of length 5
      });
      // With bones Gauss-Newton converges only linearly (docs/method.md section 5.4): the app's cap of 100
      // iterations may end the settle first; every iterate keeps the lengths.
      assert.ok(['converged', 'stopped'].includes(stats.state), `the drag ${stats.state}: ${stats.stopReason}`);
      s = await skeleton(page);
      assert.equal(s.report.bones.length, 2);
      for (const [k, bone] of s.report.bones.entries()) {
        assert.ok(Math.abs(bone.lengthError) < 1e-6, `bone ${k}: length error ${bone.lengthError}`);
      }
      const moved = Math.hypot(...s.report.joints[2].map((x, d) => x - s.joints[2][d]));
      assert.ok(moved > 0.3, `the free end's joint follows the mesh (moved ${moved.toFixed(3)})`);
      const line = await page.evaluate(() => globalThis.subspaceDeformer.views[0].viewport.statsLine.textContent);
      assert.match(line, /bones 2: length error/, 'the view\'s stats give the bones\' errors');
      await appShown(page);
      await t.screenshot(page, 'skeleton-dragged');

      // Saved with the scene, and back when it loads.
      const scene = await page.evaluate(() => globalThis.subspaceDeformer.sceneJson());
      assert.deepEqual(scene.skeleton, { joints: s.joints, bones: s.bones });
      await page.evaluate(async (scene) => {
        const app = globalThis.subspaceDeformer;
        await app.skeleton.clear();
        await app.loadScene(scene);
      }, scene);
      await page.waitForFunction(() => globalThis.subspaceDeformer.skeleton.report?.bones.length === 2, null, { timeout: 20000 });
      assert.deepEqual((await skeleton(page)).bones, [[0, 1], [1, 2]], 'a scene with a skeleton brings it back');
      // A joint outside the mesh: the worker refuses it, the banner says why, the skeleton stays as it was.
      const refused = await page.evaluate(() => globalThis.subspaceDeformer.skeleton.use({ joints: [[0, 0, 0], [9, 0, 0]], bones: [[0, 1]] })
        .then(() => null, (error) => ({ code: error.code, message: error.message })));
      assert.equal(refused?.code, 'invalid_skeleton', JSON.stringify(refused));
      assert.match(await page.locator('.sd-banner').textContent(), /skeleton: /);
      assert.deepEqual((await skeleton(page)).bones, [[0, 1], [1, 2]], 'the refused skeleton changed nothing');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'bone tool by touch on a phone: the strip\'s bone button, taps make a bone, a tap on it selects it, Del by the panel',
    timeout: 60000,
    async run(t) {
      const page = await t.touchPage('index.html', PHONE);
      await appReady(page);
      const fingers = await Fingers.on(page);
      await tapButton(page.locator('.sd-tool[data-action="bone"]'));
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.settings.tool), 'bone');
      const { lo, hi } = await barSpan(page);
      const a = await onAxis(page, lo + 0.3 * (hi - lo));
      const b = await onAxis(page, lo + 0.7 * (hi - lo));
      await fingers.tap(a);
      await fingers.tap(b);
      await page.waitForFunction(() => globalThis.subspaceDeformer.skeleton.report?.bones.length === 1, null, { timeout: 20000 });
      // A tap on the middle of the stick selects the bone; deleting it leaves no bone.
      await fingers.tap(await onAxis(page, lo + 0.5 * (hi - lo)));
      assert.equal((await skeleton(page)).tip, -1);
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.skeleton.state.selectedBone), 0, 'the tap selected the bone');
      await appShown(page);
      await t.screenshot(page, 'skeleton-phone');
      await page.evaluate(() => globalThis.subspaceDeformer.skeleton.deleteSelected());
      assert.equal((await skeleton(page)).bones.length, 0);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'lesson skeleton: its caption, the bones in each compared view\'s stats (ARAP does not keep them) and in the step-through\'s box',
    timeout: 120000,
    async run(t) {
      const page = await t.page('index.html?lesson=skeleton');
      await appReady(page);
      const caption = await page.locator('.sd-lesson').textContent();
      assert.match(caption, /figure posed by its skeleton/);
      assert.match(caption, /shorten and sag like cloth/);
      // The caption names what the stats say and why the bones are red (it used to call them straight, drawn red).
      const sag = Number(caption.match(/still sag by (\d+(?:\.\d+)?)% of their length \(the stats' straightness\), over the 2% that draws a bone red/)[1]);
      assert.deepEqual((await skeleton(page)).bones, [[0, 1], [1, 2]], 'the lesson\'s scene brought its skeleton');
      await page.evaluate(() => globalThis.subspaceDeformer.setCompare(['arap', 'subspace']));
      const all = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.solve();
        return app.statsAll().map((s) => ({ method: s.method, bones: s.skeleton?.bones ?? null }));
      });
      const worst = (bones) => Math.max(...bones.map((b) => Math.abs(b.lengthError)));
      const arap = all.find((s) => s.method === 'arap');
      const subspace = all.find((s) => s.method === 'subspace');
      assert.ok(worst(arap.bones) > 0.02, `ARAP keeps no bones: length error ${worst(arap.bones)}`);
      assert.ok(worst(subspace.bones) < 1e-9, `the subspace keeps them: length error ${worst(subspace.bones)}`);
      const straightness = Math.max(...subspace.bones.map((b) => Math.abs(b.straightnessError)));
      assert.ok(Math.abs(100 * straightness - sag) < 0.1, `the caption's ${sag}% is the stats' ${straightness}`);
      const lines = await page.evaluate(() => globalThis.subspaceDeformer.views.map((v) => ({ method: v.method, text: v.viewport.statsLine.textContent })));
      for (const { method, text } of lines) {
        // ARAP's line says its bones are only measured (it had shown the subspace solve's multipliers as its own).
        assert.match(text, method === 'arap' ? /bones 2: not kept by this method {3}length error \S+ {3}straightness \S+\n/
          : /bones 2: length error \S+ {3}straightness \S+ {3}\|\u03bb\|/);
      }
      // The ARAP view warns that it ignores the bones, in the CLI report's words (skeleton_ignored); the subspace view does not.
      const warned = await page.evaluate(() => globalThis.subspaceDeformer.statsAll().map((s) => [s.method, s.warnings.map((w) => w.code).includes('skeleton_ignored')]));
      assert.deepEqual(warned, [['arap', true], ['subspace', false]], JSON.stringify(warned));
      await page.waitForFunction(() => /skeleton_ignored: ARAP does not keep the skeleton's bones/
        .test(globalThis.subspaceDeformer.views.find((v) => v.method === 'arap').viewport.statsLine.textContent), null, { timeout: 5000 });
      await appShown(page);
      await t.screenshot(page, 'skeleton-lesson-compare');
      // One step: the subspace view's box gives each bone's multiplier and errors.
      const traces = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.stepping.setPaused(true);
        await app.resolveFromRest();
        return app.stepping.next();
      });
      const step = traces.find((tr) => tr.method === 'subspace');
      assert.equal(step.skeleton.bones.length, 2, 'the trace carries the bones\' report');
      const box = await page.evaluate(() => globalThis.subspaceDeformer.views.find((v) => v.method === 'subspace').trace.element.textContent);
      assert.match(box, /bone 0: multiplier \S+ {3}length error/);
      assert.deepEqual(page.errors, []);
    },
  },
];
