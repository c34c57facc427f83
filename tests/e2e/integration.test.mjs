// Reduced integration while dragging a large model (integration_policy.js, docs/app.md): bar-fine (43k vertices)
// iterates on the reduced rule (its clusters' centres are the stats' samples) while its handle moves and settles on
// the full answer once it rests; the built-in bar (5k) never reduces in 'auto'; the panel's setting forces either.
import assert from 'node:assert/strict';
import { appReady } from './app_probe.mjs';

// Moves the moving group along y every animation frame (a handle being dragged), recording which integration each
// solver reply used, until `enough(samples)` says the replies seen are enough (or 400 frames have passed); then
// waits for the settled solve.
async function dragAndSettle(page, enough) {
  return page.evaluate(async (enough) => {
    const app = globalThis.subspaceDeformer;
    const isEnough = new Function('samples', `return (${enough})(samples)`);
    await app.solve();
    const group = app.handles.groups.findIndex((g) => g.moving);
    const samples = [];
    const onFrame = () => samples.push(app.stats.samples);
    app.addEventListener('frame', onFrame);
    await new Promise((resolve) => {
      let frames = 0;
      const tick = () => {
        if (isEnough(samples) || frames >= 400) return resolve();
        frames++;
        app.handles.setTransform(group, [0, 0.6 * Math.sin(0.05 * frames), 0.2]);
        requestAnimationFrame(tick);
      };
      requestAnimationFrame(tick);
    });
    const settled = await app.solve();
    app.removeEventListener('frame', onFrame);
    return { samples, settled: { state: settled.state, samples: settled.samples, stopReason: settled.stopReason } };
  }, enough.toString());
}

export default [
  {
    name: 'a 43k-vertex model uses the reduced rule while its handle moves and settles on the full answer',
    timeout: 120000,
    async run(t) {
      const page = await t.page('index.html?example=bar-fine');
      await appReady(page);
      const r = await dragAndSettle(page, (samples) => samples.filter((s) => s > 0).length >= 3);
      const reduced = r.samples.filter((s) => s > 0);
      assert.ok(reduced.length >= 1, `no reduced frame while dragging: ${JSON.stringify(r.samples)}`);
      assert.ok(reduced.every((s) => s >= 100 && s <= 800), `samples ${JSON.stringify(reduced)}`);
      assert.equal(r.settled.state, 'converged', r.settled.stopReason);
      assert.equal(r.settled.samples, 0, 'the settled shape is the full integration\'s');
      await t.screenshot(page, 'integration-bar-fine-settled');
    },
  },
  {
    name: 'the built-in bar (5k vertices) never reduces in auto; the setting forces reduced or full',
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html?example=bar');
      await appReady(page);
      const auto = await dragAndSettle(page, (samples) => samples.length >= 10);
      assert.ok(auto.samples.every((s) => s === 0), `auto sampled: ${JSON.stringify(auto.samples)}`);
      await page.evaluate(() => globalThis.subspaceDeformer.setOptions({ dragIntegration: 'reduced' }));
      const forced = await dragAndSettle(page, (samples) => samples.some((s) => s > 0));
      assert.ok(forced.samples.some((s) => s > 0), `'reduced' did not sample: ${JSON.stringify(forced.samples)}`);
      assert.equal(forced.settled.samples, 0);
      assert.equal(forced.settled.state, 'converged', forced.settled.stopReason);
      const refused = await page.evaluate(() => {
        try {
          globalThis.subspaceDeformer.setOptions({ dragIntegration: 'sampled' });
          return null;
        } catch (error) {
          return error.message;
        }
      });
      assert.match(refused ?? '', /dragIntegration must be one of 'auto', 'full', 'reduced'/);
    },
  },
];
