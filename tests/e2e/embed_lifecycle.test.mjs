// <subspace-deformer> removed while a drag() was solving (an attack found it): that drag() never settled or rejected
// with "Cannot read properties of undefined (reading 'stats')".
import assert from 'node:assert/strict';
import { embedPage } from './app_probe.mjs';

export default [
  {
    name: 'embed: a removed element rejects its pending drag() as cancelled',
    timeout: 60000,
    async run(t) {
      const { page, el } = await embedPage(t, 'example="bar"');
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
