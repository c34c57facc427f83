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
  {
    // The same attack found stepping.next() left pending for ever by a removal (the pause it takes waited for the
    // answers of a worker dispose() had terminated), and so was `ready` while a lone mesh waited for the banner's
    // choice of a cage: both now reject with a CancelledError, as a setCompare() under way does. The loader had no
    // dispose(): a loadUrls() whose fetch ended after the removal failed with a TypeError (the views were gone), and
    // setCompare() on the disposed app made new views with their own workers; both are cancelled now.
    name: 'embed: a removed element rejects its pending stepping.next(), setCompare(), loadUrls() and a ready waiting for a no-cage choice',
    timeout: 90000,
    async run(t) {
      const { page, el } = await embedPage(t, 'example="bar"');
      const obj = await page.evaluate(`${el}.exportObj('mesh')`);
      await page.route('**/lone-bar.obj', (route) => route.fulfill({ contentType: 'text/plain', body: obj }));
      // Answered 3 s late, if the page still wants it (the removal aborts the fetch).
      await page.route('**/slow-bar.obj', (route) => setTimeout(() => route.fulfill({ contentType: 'text/plain', body: obj }).catch(() => {}), 3000));
      const outcomes = await page.evaluate(async () => {
        const pause = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
        const outcome = (promise) => Promise.race([promise.then((s) => `resolved ${JSON.stringify(s)?.slice(0, 60)}`, (e) => `${e.name} (${e.code})`),
          pause(10000).then(() => 'still pending 10 s after the removal')]);
        // A fresh element per case, as a page would add it; each removed while its promise waits.
        const fresh = (attributes) => {
          const element = document.createElement('subspace-deformer');
          for (const [name, value] of Object.entries(attributes)) element.setAttribute(name, value);
          element.style.height = '300px';
          document.body.append(element);
          return element;
        };
        const result = {};
        let element = fresh({ example: 'bar' });
        await element.ready;
        element.drag(1, [0, 1.5, 0.5]).catch(() => {}); // steps in flight: the pause of next() waits for their answers
        await pause(30);
        const next = element.stepping.next();
        await pause(5);
        element.remove();
        result.next = await outcome(next);

        element = fresh({ example: 'bar' });
        await element.ready;
        const compare = element.setCompare(['arap', 'subspace']);
        await pause(5);
        const app = element.app; // mount()'s API stays callable after the removal
        element.remove();
        result.setCompare = await outcome(compare);
        await pause(10);
        result.setCompareAfter = await outcome(app.setCompare(['arap', 'subspace']));
        result.viewsAfter = app.views.length;

        element = fresh({ example: 'bar' });
        await element.ready;
        const load = element.loadUrls('slow-bar.obj'); // its fetch answers 3 s later
        await pause(100);
        element.remove();
        const started = performance.now();
        result.loadUrls = await outcome(load);
        result.loadUrlsSoon = performance.now() - started < 1000;

        element = fresh({ mesh: 'lone-bar.obj' }); // no cage: the banner asks, `ready` waits for the choice
        for (let i = 0; i < 200 && ![...element.querySelectorAll('button')].some((b) => b.textContent === 'Generate cage'); ++i) await pause(50);
        const ready = element.ready;
        element.remove();
        result.ready = await outcome(ready);
        return result;
      });
      const cancelled = 'CancelledError (cancelled)';
      assert.deepEqual(outcomes, { next: cancelled, setCompare: cancelled, setCompareAfter: cancelled, viewsAfter: 0, loadUrls: cancelled,
        loadUrlsSoon: true, ready: cancelled }, JSON.stringify(outcomes));
      assert.deepEqual(page.errors.filter((e) => !/slow-bar\.obj net::ERR_ABORTED/.test(e)), []); // the fetch the removal stopped
    },
  },
  {
    // A reviewer's find: the API checked the app's end only after starting the call, so on a disposed app drag()
    // still moved the group and recorded an undo step, stepping.setPaused() still fired 'stepping', and solve()
    // after a removal during loading left a rejected promise unhandled (a page error). Now each rejects at once.
    name: 'embed: a disposed app\'s solve(), drag() and stepping.setPaused() reject at once, changing nothing',
    timeout: 60000,
    async run(t) {
      const { page } = await embedPage(t, 'example="bar"');
      const got = await page.evaluate(async () => {
        const pause = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
        const outcome = (promise) => promise.then(() => 'resolved', (e) => `${e.name} (${e.code})`);
        const fresh = () => {
          const element = document.createElement('subspace-deformer');
          element.setAttribute('example', 'bar');
          element.style.height = '300px';
          document.body.append(element);
          return element;
        };
        let element = fresh();
        const loading = element.app; // removed while its model loads
        loading.ready.catch(() => {});
        element.remove();
        await pause(0);
        const result = { solveWhileLoading: await outcome(loading.solve()) };

        element = fresh();
        await element.ready;
        const app = element.app;
        element.remove();
        await pause(0);
        const events = [];
        for (const type of ['handles', 'stepping']) app.addEventListener(type, () => events.push(type));
        const before = JSON.stringify(app.handles.groups[1].translate);
        result.drag = await outcome(app.drag(1, [0, 1, 0]));
        result.setPaused = await outcome(app.stepping.setPaused(true));
        result.moved = JSON.stringify(app.handles.groups[1].translate) !== before;
        result.paused = app.stepping.paused;
        result.events = events;
        await pause(500); // an unhandled rejection is reported by then
        return result;
      });
      const cancelled = 'CancelledError (cancelled)';
      assert.deepEqual(page.errors, []);
      assert.deepEqual(got, { solveWhileLoading: cancelled, drag: cancelled, setPaused: cancelled, moved: false, paused: false, events: [] }, JSON.stringify(got));
    },
  },
];
