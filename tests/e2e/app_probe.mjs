// Helpers of the browser tests that look at the app from outside: waiting for it, where things are on
// screen, what its views frame, and the real meshes of ../shared/data served to the page.
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

export const SHARED_DATA = join(dirname(fileURLToPath(import.meta.url)), '..', '..', '..', 'shared', 'data');

/** Whether ../shared/data has these files (tests that need them skip, saying why, when not). */
export function haveSharedData(...names) {
  return names.every((name) => existsSync(join(SHARED_DATA, name)));
}

/** Serves ../shared/data/<name> to the page at <page's folder>/shared-data/<name>. */
export async function routeSharedData(page) {
  await page.route('**/shared-data/*', (route) => {
    const name = new URL(route.request().url()).pathname.split('/').pop();
    route.fulfill({ contentType: 'text/plain', body: readFileSync(join(SHARED_DATA, name)) });
  });
}

/**
 * Waits for an app's first model: `get` is a page expression for the app (an embed's: `${element}.app`), which
 * may not exist yet.
 */
export async function appReady(page, get = 'globalThis.subspaceDeformer', { timeout = 30000 } = {}) {
  await page.waitForFunction(`!!(${get})`, null, { timeout });
  await page.evaluate(`(${get}).ready`);
}

/**
 * The shim's service worker isolates the page by reloading it once the worker is active. On a fresh browser
 * profile coi-serviceworker 0.1.7 may reload on "updatefound" before its worker controls the page, and then not
 * again (a CI run of 2026-11-28 left a page unisolated for 30 s that takes about a second otherwise); the user's next
 * load is isolated. This waits for the shim's own reload and, when that race left the page without it, reloads
 * once as that user would.
 */
export async function waitForIsolation(page) {
  try {
    await page.waitForFunction('crossOriginIsolated === true', null, { timeout: 15000 });
  } catch {
    await page.reload();
    await page.waitForFunction('crossOriginIsolated === true', null, { timeout: 30000 });
  }
}

/** Resolves after `count` animation frames of the page. */
export function animationFrames(page, count = 1) {
  return page.evaluate((count) => new Promise((resolve) => {
    const tick = () => (--count > 0 ? requestAnimationFrame(tick) : resolve());
    requestAnimationFrame(tick);
  }), count);
}

/**
 * Resolves once what an app shows is current, before a screenshot: every view still (a software renderer has
 * drawn at full resolution again after motion) with nothing left to draw, then the stats lines redrawn (the app
 * refreshes them a few times a second, not every frame) and one more frame.
 */
export async function appShown(page, get = 'globalThis.subspaceDeformer') {
  await page.waitForFunction(`(${get}).views.every((v) => !v.viewport.inMotion && !v.viewport.needsRender)`, null, { polling: 'raf' });
  await page.evaluate(`new Promise((resolve) => {
    const loop = (${get}).frameLoop;
    const tick = loop.tick;
    loop.tick = (now) => {
      loop.tick = tick;
      tick(now);
      requestAnimationFrame(() => resolve());
    };
  })`);
}

/**
 * Lets a test hold the replies of the page's solver workers, as a very slow solver would (their progress
 * messages still come): in the page, replyGate.hold(), replyGate.held (the replies held now), replyGate.release()
 * (delivers them in order) and replyGate.progress (every progress message seen: { phase, fraction }). Call before
 * the page loads (page.goto): it wraps the onmessage of every Worker the page starts. holdAtPhase: holding starts
 * with the first progress message of that phase (so the reply of the load that reports it is held).
 */
export async function installReplyGate(page, { holdAtPhase = null } = {}) {
  await page.addInitScript((holdAtPhase) => {
    const gate = {
      holding: false,
      heldAtPhase: false,
      queue: [],
      progress: [],
      hold() { this.holding = true; },
      release() {
        this.holding = false;
        const queue = this.queue;
        this.queue = [];
        for (const deliver of queue) deliver();
      },
      get held() { return this.queue.length; },
    };
    globalThis.replyGate = gate;
    const onmessage = Object.getOwnPropertyDescriptor(Worker.prototype, 'onmessage');
    Object.defineProperty(Worker.prototype, 'onmessage', {
      configurable: true,
      get() { return onmessage.get.call(this); },
      set(handler) {
        if (typeof handler !== 'function') {
          onmessage.set.call(this, handler);
          return;
        }
        onmessage.set.call(this, function (event) {
          const data = event.data;
          if (data?.type === 'progress') {
            gate.progress.push({ phase: data.phase, fraction: data.fraction });
            if (data.phase === holdAtPhase && !gate.heldAtPhase) gate.holding = gate.heldAtPhase = true;
          }
          // A reply of the solver's protocol ({ id, ok, ... }); anything else (progress, pthread messages) passes.
          if (gate.holding && data && typeof data === 'object' && 'id' in data && 'ok' in data) {
            gate.queue.push(() => handler.call(this, event));
          } else {
            handler.call(this, event);
          }
        });
      },
    });
  }, holdAtPhase);
}

/** Client rectangle of the first element matching a selector (null when none or hidden). */
export function rect(page, selector) {
  return page.evaluate((selector) => {
    const el = document.querySelector(selector);
    if (!el || el.hidden || !el.offsetParent) return null;
    const r = el.getBoundingClientRect();
    return { left: r.left, top: r.top, right: r.right, bottom: r.bottom };
  }, selector);
}

export function overlaps(a, b) {
  return a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
}

/**
 * What each view frames: every vertex of its current mesh and every handle target projected with its
 * camera, as the largest |x| and |y| in normalized device coordinates (1 = the view's edge), and whether
 * everything is in front of the camera.
 */
export function framing(page) {
  return page.evaluate(() => {
    const app = globalThis.subspaceDeformer;
    const targets = app.handles.groups.length ? app.handles.targets() : [];
    return app.views.map((view) => {
      const camera = view.viewport.camera;
      camera.updateMatrixWorld();
      const point = camera.position.clone();
      let x = 0;
      let y = 0;
      let inFront = true;
      for (const list of [view.positions, targets]) {
        for (let i = 0; i < list.length; i += 3) {
          point.set(list[i], list[i + 1], list[i + 2]).project(camera);
          x = Math.max(x, Math.abs(point.x));
          y = Math.max(y, Math.abs(point.y));
          inFront &&= point.z > -1 && point.z < 1;
        }
      }
      return { method: view.method, x, y, inFront, aspect: camera.aspect };
    });
  });
}

/**
 * The screen position of a world point given as an expression over `app` (the view's camera); `get`: a page
 * expression for the app (an embed's: its element's `.app`).
 */
export function project(page, expression, view = 0, get = 'globalThis.subspaceDeformer') {
  return page.evaluate(({ expression, view, get }) => {
    const app = new Function(`return ${get}`)();
    const v = app.views[view].viewport;
    const p = new Function('app', `return ${expression}`)(app);
    const r = v.canvas.getBoundingClientRect();
    const q = p.clone().project(v.camera);
    return { x: r.left + ((q.x + 1) / 2) * r.width, y: r.top + ((1 - q.y) / 2) * r.height };
  }, { expression, view, get });
}

/** Presses the mouse just off `point` (a gizmo's centre, say) and drags it up by `steps` moves of `px` pixels. */
export async function dragUp(page, point, { steps = 8, px = 6 } = {}) {
  await page.mouse.move(point.x, point.y);
  await page.mouse.move(point.x + 1, point.y + 1);
  await page.mouse.down();
  for (let i = 1; i <= steps; ++i) await page.mouse.move(point.x + 1, point.y + 1 - px * i);
  await page.mouse.up();
}

/**
 * A course page of one <subspace-deformer id="e"> with these attributes, served at `name` beside the build
 * (the embed script only: no service-worker shim); resolves once the element's first model is bound.
 * @returns {Promise<{ page, el: string }>} el: a page expression for the element
 */
export async function embedPage(t, attributes, { name = 'embed-page.html', height = 420 } = {}) {
  const html = '<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,">' +
    '<script type="module" src="subspace-deformer.js"></script></head><body>' +
    `<subspace-deformer id="e" ${attributes} style="height: ${height}px"></subspace-deformer></body></html>`;
  const page = await t.page(null);
  await page.route(`**/${name}`, (route) => route.fulfill({ contentType: 'text/html', body: html }));
  await page.goto(`${t.url}${name}`);
  const el = "document.getElementById('e')";
  await appReady(page, `${el}.app`);
  return { page, el };
}
