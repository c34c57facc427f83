// The user's last load request wins (issue 32, item 7a): a lesson or a cage generation waits (the lesson's scene,
// the app being ready) before it binds, so a model load issued right after it used to bind first and then be
// cancelled by the older request, whose success hid the "Loading cancelled" banner. Now the older request
// rejects as cancelled (or resolves without replacing the newer model) and the newer one stays on screen.
import assert from 'node:assert/strict';
import { appReady } from './app_probe.mjs';

// Runs `older` then, without awaiting it, `newer` (both app method calls as text), and reports how each ended,
// the model on screen and in every view's session, the banner and the lesson.
function race(page, older, newer) {
  return page.evaluate(async ([older, newer]) => {
    const a = globalThis.subspaceDeformer;
    const settle = (p) => p.then((value) => ({ ok: true, model: value?.name ?? null }), (e) => ({ ok: false, name: e.name, message: e.message }));
    const first = settle(new Function('a', `return ${older}`)(a));
    const second = settle(new Function('a', `return ${newer}`)(a));
    const [o, n] = await Promise.all([first, second]);
    // Anything the older request still does after settling would show within a few frames.
    for (let i = 0; i < 5; i++) await new Promise((r) => requestAnimationFrame(r));
    const banner = document.querySelector('.sd-banner');
    return { older: o, newer: n, model: a.model.name, sessions: a.views.map((v) => v.session.model?.name),
      banner: banner && !banner.hidden ? banner.querySelector('.sd-message').textContent : '', lesson: a.lesson?.id ?? null,
      basis: a.model.subspace?.basis, setting: a.settings.basis };
  }, [older, newer]);
}

// A worker terminated while its threads still start (the replaced model's) aborts their script's request.
const unexpected = (errors) => errors.filter((e) => !/subspace_deform\.worker\.js net::ERR_ABORTED/.test(e));

function assertNewerWon(got, what) {
  assert.deepEqual(got.newer, { ok: true, model: 'sphere' }, `${what}: the later load ${JSON.stringify(got.newer)}`);
  assert.equal(got.model, 'sphere', `${what}: the model on screen (${JSON.stringify(got)})`);
  assert.deepEqual(got.sessions, got.sessions.map(() => 'sphere'), `${what}: every view's model`);
  // The older request was cancelled (or finished before the newer one replaced its model): nothing else.
  if (!got.older.ok) assert.equal(got.older.name, 'CancelledError', `${what}: ${got.older.message}`);
  assert.doesNotMatch(got.banner, /cancelled/i, `${what}: the newer load was not cancelled: ${got.banner}`);
}

/**
 * A test: on a new page (once its first model is bound, or `early`: while it binds), `older` then at once
 * loadExample('sphere'); the sphere must win, and `more(got, page)` checks the rest.
 */
function lastLoadWins(name, older, { early = false, more = () => {} } = {}) {
  return {
    name: `${older} then at once loadExample('sphere')${early ? ' during the first load' : ''}: ${name}`,
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html');
      if (early) await page.waitForFunction('!!globalThis.subspaceDeformer');
      else await appReady(page);
      const got = await race(page, older, "a.loadExample('sphere')");
      assertNewerWon(got, older);
      await more(got, page);
      assert.deepEqual(unexpected(page.errors), []);
    },
  };
}

export default [
  lastLoadWins('the sphere stays on screen, the lesson is cancelled', "a.loadLesson('volume-parts')", {
    async more(got, page) {
      assert.equal(got.older.name, 'CancelledError', 'the lesson waited for its scene: it cannot have bound first');
      assert.equal(got.lesson, null, 'no lesson caption over the sphere');
      // The app still works on the sphere.
      assert.equal(await page.evaluate('globalThis.subspaceDeformer.solve().then((s) => s.state)'), 'converged');
    },
  }),
  lastLoadWins('the sphere stays on screen, the cage generation is cancelled', 'a.generateCage(60)'),
  // setBasis waits for the first load as generateCage does.
  lastLoadWins('the sphere keeps the cage basis it was loaded with', "a.setBasis('spectral', 12)", {
    early: true,
    more: (got) => assert.deepEqual([got.basis, got.setting], ['cage', 'cage']),
  }),
  {
    name: 'a lesson after a lesson: the later one wins, with its caption',
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const got = await page.evaluate(async () => {
        const a = globalThis.subspaceDeformer;
        const settle = (p) => p.then((l) => ({ ok: true, id: l.id }), (e) => ({ ok: false, name: e.name }));
        const [first, second] = await Promise.all([settle(a.loadLesson('volume')), settle(a.loadLesson('spectral'))]);
        return { first, second, lesson: a.lesson?.id, basis: a.settings.basis };
      });
      assert.deepEqual(got.second, { ok: true, id: 'spectral' });
      assert.equal(got.lesson, 'spectral');
      assert.equal(got.basis, 'spectral');
      if (!got.first.ok) assert.equal(got.first.name, 'CancelledError');
      assert.deepEqual(unexpected(page.errors), []);
    },
  },
];
