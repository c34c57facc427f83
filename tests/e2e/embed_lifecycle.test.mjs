// <subspace-deformer> moved and removed (an attack found both): moved elsewhere in the page (wrap.append(el)) it
// disposed its app and mounted a fresh one from its attributes, losing the pose and handles; removed while a drag()
// was solving, that drag() never settled or rejected with "Cannot read properties of undefined (reading 'stats')".
import assert from 'node:assert/strict';
import { embedPage } from './app_probe.mjs';

export default [
  {
    name: 'embed: a moved element keeps its app and pose; a removed one rejects its pending drag() as cancelled',
    timeout: 60000,
    async run(t) {
      const { page, el } = await embedPage(t, 'example="bar"');
      const moved = await page.evaluate(async (el) => {
        const element = new Function(`return ${el}`)();
        await element.drag(1, [0, 0.6, 0]);
        const app = element.app;
        const before = Array.from(element.positions());
        const wrap = document.createElement('div');
        document.body.append(wrap);
        wrap.append(element); // a disconnect, then a connect, in one task
        await new Promise((resolve) => setTimeout(resolve, 200));
        await element.solve();
        const after = Array.from(element.positions());
        return { same: element.app === app, translate: element.app.handles.groups[1].translate, drift: Math.max(...after.map((x, i) => Math.abs(x - before[i]))) };
      }, el);
      assert.deepEqual(moved, { same: true, translate: [0, 0.6, 0], drift: 0 }, JSON.stringify(moved));

      const removed = await page.evaluate(async (el) => {
        const element = new Function(`return ${el}`)();
        const drag = element.drag(1, [0, 1.5, 0.5]);
        await new Promise((resolve) => setTimeout(resolve, 30));
        element.remove();
        const timeout = new Promise((resolve) => setTimeout(() => resolve('still pending 10 s after the removal'), 10000));
        const outcome = await Promise.race([drag.then((s) => `resolved ${s?.state}`, (e) => `${e.name} (${e.code}): ${e.message}`), timeout]);
        return { outcome, app: element.app };
      }, el);
      assert.match(removed.outcome, /^CancelledError \(cancelled\)/, removed.outcome);
      assert.equal(removed.app, null, 'the removed element has no app');
      assert.deepEqual(page.errors, []);
    },
  },
];
