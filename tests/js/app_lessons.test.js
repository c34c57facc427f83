// Lessons (web/app/lessons/lessons.js) against stand-ins for the loader, the step-through and the app's setCompare:
// a lesson loads its scene with the solver settings of a fresh start, and a lesson that a later request replaces
// (or that fails, or is cancelled) changes nothing: a tester chose lesson "volume", then example "sphere" 50 ms
// later, and the sphere came up as ARAP | subspace with "compare methods" ticked.
import { describe, expect, it } from 'vitest';
import { EventDispatcher } from 'three';
import { Lessons } from '../../web/app/lessons/lessons.js';
import { CancelledError } from '../../web/lib/errors.js';

/** The loader's tickets as ModelLoader has them, views by key, and a loadScene the test settles by hand. */
class StandInLoader extends EventDispatcher {
  newest = 0;
  views = { list: [{ key: 'subspace' }] };
  model = { name: 'bar', defaultView: null };
  scenes = [];
  request() {
    this.dispatchEvent({ type: 'request', ticket: ++this.newest });
    return this.newest;
  }
  isNewest(ticket) { return ticket === this.newest; }
  checkNewest(ticket, what) { if (!this.isNewest(ticket)) throw new CancelledError(`${what} cancelled`); }
  loadScene(raw, options) {
    return new Promise((resolve, reject) => this.scenes.push({ raw, options, resolve, reject }));
  }
}

function make({ paused = false } = {}) {
  const loader = new StandInLoader();
  const stepping = { paused, setPaused(on) { this.paused = on; return Promise.resolve(); } };
  const compares = [];
  const setCompare = (compare) => {
    compares.push(compare);
    loader.views.list = (compare || ['subspace']).map((key) => ({ key }));
    return Promise.resolve();
  };
  const lessons = new Lessons({ loader, banner: { show() {} }, stepping, setCompare, fitView() {} });
  return { loader, stepping, compares, lessons };
}

/** Waits until the lesson has asked for its scene. */
async function sceneAsked(loader) {
  for (let i = 0; i < 100 && !loader.scenes.length; ++i) await new Promise((r) => setTimeout(r, 5));
  expect(loader.scenes.length).toBe(1);
  return loader.scenes[0];
}

const keys = (loader) => loader.views.list.map((v) => v.key);

describe('Lessons', () => {
  it('loads its scene with the settings of a fresh start and its own views', async () => {
    const { loader, lessons } = make();
    const loading = lessons.load('volume');
    const scene = await sceneAsked(loader);
    expect(scene.options).toMatchObject({ fresh: true, ticket: 1 });
    expect(keys(loader)).toEqual(['arap', 'subspace']);
    loader.model = { name: 'spot' };
    scene.resolve(loader.model);
    expect((await loading).id).toBe('volume');
    expect(keys(loader)).toEqual(['arap', 'subspace']);
  });

  it('a later request puts the views and the step-through back before it binds, and the lesson rejects as cancelled', async () => {
    const { loader, stepping, lessons } = make({ paused: true });
    const loading = lessons.load('volume');
    const scene = await sceneAsked(loader);
    expect([keys(loader), stepping.paused]).toEqual([['arap', 'subspace'], false]);
    let seen = null;
    loader.addEventListener('request', () => (seen = keys(loader))); // what the later request binds in
    loader.request(); // the example "sphere"
    expect(seen).toEqual(['subspace']);
    expect(stepping.paused).toBe(true);
    scene.reject(new CancelledError('replaced'));
    await expect(loading).rejects.toBeInstanceOf(CancelledError);
    expect([keys(loader), stepping.paused]).toEqual([['subspace'], true]);
  });

  it('a lesson cancelled (the progress bar) or failing leaves the views as they were; a later lesson\'s views stay', async () => {
    const { loader, compares, lessons } = make();
    loader.views.list = [{ key: 'subspace' }, { key: 'full' }];
    const first = lessons.load('volume');
    (await sceneAsked(loader)).reject(new CancelledError('Cancel'));
    await expect(first).rejects.toBeInstanceOf(CancelledError);
    expect(keys(loader)).toEqual(['subspace', 'full']);
    expect(compares.at(-1)).toEqual(['subspace', 'full']);
    // Lesson A replaced by lesson B: A's undoing happens before B changes the views, never after.
    loader.scenes = [];
    const a = lessons.load('volume');
    const sceneA = await sceneAsked(loader);
    loader.scenes = [];
    const b = lessons.load('volume-parts');
    const sceneB = await sceneAsked(loader);
    sceneA.reject(new CancelledError('replaced'));
    await expect(a).rejects.toBeInstanceOf(CancelledError);
    expect(keys(loader)).toEqual(['subspace']); // volume-parts compares nothing
    loader.model = { name: 'spot' };
    sceneB.resolve(loader.model);
    expect((await b).id).toBe('volume-parts');
  });
});
