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

export async function appReady(page, app = 'globalThis.subspaceDeformer') {
  await page.waitForFunction(`!!${app}`);
  await page.evaluate(`${app}.ready`);
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

/** The screen position of a world point given as an expression over `app` (the first view's camera). */
export function project(page, expression, view = 0) {
  return page.evaluate(({ expression, view }) => {
    const app = globalThis.subspaceDeformer;
    const v = app.views[view].viewport;
    const p = new Function('app', `return ${expression}`)(app);
    const r = v.canvas.getBoundingClientRect();
    const q = p.clone().project(v.camera);
    return { x: r.left + ((q.x + 1) / 2) * r.width, y: r.top + ((1 - q.y) / 2) * r.height };
  }, { expression, view });
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
  await page.waitForFunction(`!!${el}.app`);
  await page.evaluate(`${el}.ready`);
  return { page, el };
}
