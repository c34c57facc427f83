// Reduced integration while dragging a large model (integration_policy.js, docs/app.md): bar-fine (43k vertices)
// iterates on samples while its handle moves and settles on the full answer once it rests; the built-in bar (5k)
// never samples in 'auto'; the panel's setting forces either.
import assert from 'node:assert/strict';

async function ready(page) {
  await page.waitForFunction('!!globalThis.subspaceDeformer');
  await page.evaluate('globalThis.subspaceDeformer.ready');
}

// Moves the moving group along y for `ms` (a handle being dragged), recording which integration each solver reply
// used; then waits for the settled solve.
async function dragAndSettle(page, ms) {
  return page.evaluate(async (duration) => {
    const app = globalThis.subspaceDeformer;
    await app.solve();
    const group = app.handles.groups.findIndex((g) => g.moving);
    const samples = [];
    const onFrame = () => samples.push(app.stats.samples);
    app.addEventListener('frame', onFrame);
    const t0 = performance.now();
    await new Promise((resolve) => {
      const tick = (now) => {
        if (now - t0 >= duration) return resolve();
        app.handles.setTransform(group, [0, 0.6 * Math.sin(Math.PI * (now - t0) / duration), 0.2]);
        requestAnimationFrame(tick);
      };
      requestAnimationFrame(tick);
    });
    const settled = await app.solve();
    app.removeEventListener('frame', onFrame);
    return { samples, settled: { state: settled.state, samples: settled.samples, stopReason: settled.stopReason } };
  }, ms);
}

export default [
  {
    name: 'a 43k-vertex model samples the Laplacian term while its handle moves and settles on the full answer',
    timeout: 120000,
    async run(t) {
      const page = await t.page('index.html?example=bar-fine');
      await ready(page);
      const r = await dragAndSettle(page, 2500);
      const reduced = r.samples.filter((s) => s > 0);
      assert.ok(reduced.length >= 1, `no reduced frame while dragging: ${JSON.stringify(r.samples)}`);
      assert.ok(reduced.every((s) => s >= 100 && s <= 400), `samples ${JSON.stringify(reduced)}`);
      assert.equal(r.settled.state, 'converged', r.settled.stopReason);
      assert.equal(r.settled.samples, 0, 'the settled shape is the full integration\'s');
      await t.screenshot(page, 'integration-bar-fine-settled');
    },
  },
  {
    name: 'the built-in bar (5k vertices) never samples in auto; the setting forces reduced or full',
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html?example=bar');
      await ready(page);
      const auto = await dragAndSettle(page, 1200);
      assert.ok(auto.samples.every((s) => s === 0), `auto sampled: ${JSON.stringify(auto.samples)}`);
      await page.evaluate(() => globalThis.subspaceDeformer.setOptions({ dragIntegration: 'reduced' }));
      const forced = await dragAndSettle(page, 1200);
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
