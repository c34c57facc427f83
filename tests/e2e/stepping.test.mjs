// Step-through in the app and the embed: paused, a drag moves only the targets; each step is one Gauss-Newton
// iteration (numbered from 1, the mesh moving, the merit and energies shown in the view's trace); ARAP goes by
// halves (the local step moves nothing and lowers the energy, the global step moves the mesh and lowers it);
// resuming solves to convergence; the tool strip's pause / step / local buttons do the same.
import assert from 'node:assert/strict';
import { appReady, embedPage } from './app_probe.mjs';

const app = 'globalThis.subspaceDeformer';
const maxDistance = (a, b) => a.reduce((m, x, i) => Math.max(m, Math.abs(x - b[i])), 0);

export default [
  {
    name: 'step-through: paused, each step is one Gauss-Newton iteration shown in the view; resuming converges',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      await page.locator('.sd-tool[data-action="stepping"]').click();
      assert.equal(await page.evaluate(`${app}.stepping.paused`), true, 'the pause button paused the solver');
      assert.equal(await page.locator('.sd-tool[data-action="next"]').isVisible(), true, 'the step button shows when paused');
      const rest = await page.evaluate(`Array.from(${app}.restPositions())`);
      await page.evaluate(`${app}.drag(1, [0, 0.6, 0.2])`);
      assert.ok(maxDistance(await page.evaluate(`Array.from(${app}.positions())`), rest) < 1e-12, 'paused: the drag moved only the targets');
      const steps = [];
      for (let i = 0; i < 4; ++i) {
        const [trace] = i === 0 ? await Promise.all([page.evaluate(() => new Promise((r) => globalThis.subspaceDeformer.addEventListener('trace', (e) => r(e.trace), { once: true }))),
          page.locator('.sd-tool[data-action="next"]').click()]) : await page.evaluate(`${app}.stepping.next()`);
        steps.push({ stats: trace.stats, positions: await page.evaluate(`Array.from(${app}.positions())`) });
      }
      const first = steps[0].stats.iteration; // the Deformer counts from its last reset (the load's solve at rest is one)
      assert.deepEqual(steps.map((s) => s.stats.iteration), [first, first + 1, first + 2, first + 3], 'one iteration per step');
      assert.ok(maxDistance(steps[0].positions, rest) > 0.05, 'the first step moved the mesh');
      for (const s of steps) assert.ok(Math.abs(s.stats.volumeRelError) < 1e-6, `volume kept in every step: ${s.stats.volumeRelError}`);
      for (let i = 1; i < steps.length; ++i) {
        assert.ok(steps[i].stats.energy <= steps[i - 1].stats.energy * (1 + 1e-9), `energy ${steps[i - 1].stats.energy} -> ${steps[i].stats.energy}`);
      }
      const text = await page.locator('.sd-trace').first().textContent();
      assert.match(text, new RegExp(`Gauss-Newton iteration ${first + 3}`));
      assert.match(text, /multiplier lambda/);
      // The solver's trace of the line search: each trial with its alpha and merit, the accepted one named.
      const last = steps.at(-1).stats;
      assert.ok(last.lineSearch.length >= 1 && last.lineSearch.length === last.lineSearchTrials, `trials ${JSON.stringify(last.lineSearch)}`);
      assert.equal(last.lineSearch.filter((trial) => trial.restored).length, 1, 'one trial accepted');
      assert.equal(last.lineSearch.find((trial) => trial.restored).alpha, last.alpha);
      assert.match(text, /line search \(Armijo c1 = 0\.0001, backtracking c2 = 0\.5\):/);
      assert.match(text, /alpha 1 +merit [-\d.e]+ +(accepted|not enough decrease)/);
      assert.match(text, /energy E = Laplacian .* \+ position .* = /);
      await t.screenshot(page, 'stepping-gauss-newton');
      // Resume: the solve goes on to convergence from there, and the trace goes away.
      await page.evaluate(`${app}.stepping.setPaused(false)`);
      const stats = await page.evaluate(`${app}.solve()`);
      assert.equal(stats.state, 'converged');
      assert.ok(stats.iterations > 4);
      assert.equal(await page.locator('.sd-trace').first().isVisible(), false);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'step-through of ARAP by halves: the local step moves nothing, the global step moves the mesh, each lowers the energy',
    timeout: 45000,
    async run(t) {
      const page = await t.page('index.html?method=arap&paused=1');
      await appReady(page);
      assert.equal(await page.evaluate(`${app}.stepping.paused`), true, '?paused=1 starts paused');
      await page.evaluate(`${app}.drag(1, [0, 0.8, 0])`);
      assert.equal(await page.locator('.sd-tool[data-action="half"]').textContent(), 'local');
      const before = await page.evaluate(`Array.from(${app}.positions())`);
      await page.locator('.sd-tool[data-action="half"]').click();
      await page.waitForFunction(() => /local step/.test(document.querySelector('.sd-trace')?.textContent ?? ''));
      assert.ok(maxDistance(await page.evaluate(`Array.from(${app}.positions())`), before) < 1e-12, 'the local step moved no vertex');
      assert.equal(await page.locator('.sd-tool[data-action="half"]').textContent(), 'global');
      const [global] = await page.evaluate(`${app}.stepping.nextHalf()`);
      assert.equal(global.half.phase, 'global');
      assert.ok(global.half.energyAfter <= global.half.energyBefore, `global: ${global.half.energyBefore} -> ${global.half.energyAfter}`);
      assert.ok(global.half.step > 0.05, `the global step moved the mesh by ${global.half.step}`);
      const moved = await page.evaluate(`Array.from(${app}.positions())`);
      assert.ok(maxDistance(moved, before) > 0.05);
      const [next] = await page.evaluate(`${app}.stepping.nextHalf()`);
      assert.equal(next.half.phase, 'local');
      assert.ok(next.half.energyAfter <= next.half.energyBefore * (1 + 1e-12), `local: ${next.half.energyBefore} -> ${next.half.energyAfter}`);
      assert.ok(next.half.maxRotation > 0.05, `the local step's rotations: largest ${next.half.maxRotation} rad`);
      await t.screenshot(page, 'stepping-arap-halves');
      // A whole iteration after the halves goes on from where they left the mesh.
      const [whole] = await page.evaluate(`${app}.stepping.next()`);
      assert.ok(whole.stats.energy <= next.half.energyAfter * (1 + 1e-9), `iteration: ${whole.stats.energy} after ${next.half.energyAfter}`);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'step-through in the embed: <subspace-deformer paused> steps through its element API',
    timeout: 45000,
    async run(t) {
      const { page, el } = await embedPage(t, 'example="bar" paused compare="arap,subspace"', { name: 'stepping-page.html' });
      assert.equal(await page.evaluate(`${el}.stepping.paused`), true);
      await page.evaluate(`${el}.drag(1, [0, 0.5, 0])`);
      const traces = await page.evaluate(`${el}.stepping.next()`);
      assert.deepEqual(traces.map((tr) => [tr.method, tr.stats.iteration]), [['arap', 1], ['subspace', 1]]);
      const texts = await page.locator('.sd-trace').allTextContents();
      assert.equal(texts.length, 2);
      assert.match(texts[0], /ARAP: iteration 1/);
      assert.match(texts[1], /Subspace.*Gauss-Newton iteration 1/);
      await t.screenshot(page, 'stepping-embed-compare');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'step-through says what it did: compare views binding are waited for, each volume part\'s multiplier, nothing to do once converged',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      await page.evaluate(`${app}.stepping.setPaused(true)`);
      await page.evaluate(`${app}.drag(1, [0, 0.6, 0.2])`);
      // A step while new compare views still bind waits for them: every view steps, none says it has no handles.
      page.evaluate(`${app}.setCompare(['subspace', 'full'])`).catch(() => {});
      const traces = await page.evaluate(`${app}.stepping.next()`);
      assert.deepEqual(traces.map((tr) => [tr.method, !!tr.stats]), [['subspace', true], ['full', true]]);
      for (const text of await page.locator('.sd-trace').allTextContents()) assert.doesNotMatch(text, /no handles|nothing to step/);
      await page.evaluate(`${app}.setCompare(false)`);
      // Stepped to convergence, the next step runs no iteration and says so, with the iteration the stats count.
      let trace;
      for (let i = 0; i < 60 && !trace?.idle; ++i) [trace] = await page.evaluate(`${app}.stepping.next()`);
      const iterations = await page.evaluate(`${app}.stats.iterations`);
      assert.match(trace.idle, new RegExp(`^converged at iteration ${iterations}: nothing to do`));
      const before = await page.evaluate(`Array.from(${app}.positions())`);
      [trace] = await page.evaluate(`${app}.stepping.next()`);
      assert.equal(trace.stats, null);
      assert.equal(await page.evaluate(`${app}.stats.iterations`), iterations, 'no iteration counted');
      assert.equal(maxDistance(await page.evaluate(`Array.from(${app}.positions())`), before), 0);
      assert.match(await page.locator('.sd-trace').first().textContent(), /converged at iteration \d+: nothing to do/);
      // With volume parts the box gives each part's multiplier, and the merit sums them.
      assert.equal(await page.evaluate(`${app}.parts.auto(3)`), 3);
      await page.evaluate(`${app}.drag(1, [0, 1.2, 0])`);
      [trace] = await page.evaluate(`${app}.stepping.next()`);
      assert.equal(trace.stats.partLambda.length, 3);
      const text = await page.locator('.sd-trace').first().textContent();
      assert.match(text, /volume parts 3: one multiplier each\npart 0: multiplier .*\npart 1: .*\npart 2: /);
      assert.doesNotMatch(text, /multiplier lambda/);
      assert.match(text, /merit E.* \+ sum of lambda_k g_k over the parts = /);
      assert.deepEqual(page.errors, []);
    },
  },
];
