// Reduced integration while dragging a large model (integration_policy.js, docs/app.md): bar-fine (43k vertices)
// iterates on the reduced rule (its clusters' centres are the stats' samples) while its handle moves and settles on
// the full answer once it rests; the built-in bar (5k) never reduces in 'auto'; the panel's setting forces either.
import assert from 'node:assert/strict';
import { appReady, project } from './app_probe.mjs';

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
    name: 'releasing the gizmo switches to the full integration at once, without waiting for the drag to rest',
    timeout: 120000,
    async run(t) {
      const page = await t.page('index.html?example=bar-fine');
      await appReady(page);
      // Every integration the session tells its worker, and the handles' release, with their times.
      await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        await app.solve();
        const log = (globalThis.integrationLog = []);
        const client = app.views[0].session.client;
        const request = client.request.bind(client);
        client.request = (type, payload) => {
          if (type === 'setOptions') log.push({ integration: payload.options.integration, at: performance.now() });
          return request(type, payload);
        };
        app.handles.addEventListener('release', () => log.push({ release: true, at: performance.now() }));
      });
      // A slow drag (a move every 600 ms): a pause would count as a rest only after three of its intervals, 1.8 s.
      const start = await project(page, 'app.views[0].gizmo.pivot.position.clone()');
      await page.mouse.move(start.x, start.y);
      await page.mouse.move(start.x + 1, start.y + 1);
      await page.mouse.down();
      for (let i = 1; i <= 5; ++i) {
        await page.mouse.move(start.x + 1, start.y + 1 - 8 * i);
        await new Promise((resolve) => setTimeout(resolve, 600));
      }
      await page.mouse.up();
      const { log, settled } = await page.evaluate(async () => {
        const stats = await globalThis.subspaceDeformer.solve();
        return { log: globalThis.integrationLog, settled: { state: stats.state, samples: stats.samples, stopReason: stats.stopReason } };
      });
      const release = log.findIndex((e) => e.release);
      assert.ok(release >= 0, `no release event: ${JSON.stringify(log)}`);
      assert.ok(log.slice(0, release).some((e) => e.integration === 'reduced'), `not reduced while dragging: ${JSON.stringify(log)}`);
      const full = log.slice(release).find((e) => e.integration === 'full');
      assert.ok(full, `no switch to full after the release: ${JSON.stringify(log)}`);
      const after = full.at - log[release].at;
      assert.ok(after < 900, `full integration ${after.toFixed(0)} ms after the release (the drag's rest: 1800 ms)`);
      assert.equal(settled.state, 'converged', settled.stopReason);
      assert.equal(settled.samples, 0, 'the settled shape is the full integration\'s');
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
