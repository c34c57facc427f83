// Phones and small embeds (issue 31, items 3 and 5), measured by bounding boxes in a phone's browser (390 x 844 CSS
// px, touch: hasTouch, isMobile; and 844 x 390, the phone in landscape: one column of icons, the views beside it): the tool strip is one row of icons no taller than 15% of the app's width; compare
// and lesson views are stacked, each at least 90% of the width; a banner covers neither the views (the model)
// nor the strip, and a tap on its x dismisses it; the stats stay inside their view; the panel button does not
// move when the panel opens, so the same tap closes it; the default view's gizmo stays inside the view. The
// embed runs on a plain static server (a course page: two elements, one comparing three methods), the app as
// index.html. Screenshots go to test-results/small-*.png.
import assert from 'node:assert/strict';
import { cpSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { animationFrames, appReady, appShown, overlaps } from './app_probe.mjs';
import { Fingers, PHONE, centre } from './touch.mjs';

const dist = process.env.SD_E2E_DIST ?? join(dirname(fileURLToPath(import.meta.url)), '..', '..', 'dist');
const SLACK = 1; // px of rounding

/**
 * The layout of one app (`root`: a page expression for its .sd-app element): boxes of the strip, its visible
 * buttons, the views, their stats, the banner, the open panel and the lesson bar (null when hidden).
 */
function layout(page, root) {
  return page.evaluate((root) => {
    const app = new Function(`return ${root}`)();
    const box = (el) => {
      if (!el || el.hidden || el.offsetParent === null || getComputedStyle(el).display === 'none') return null;
      const r = el.getBoundingClientRect();
      return { left: r.left, top: r.top, right: r.right, bottom: r.bottom, width: r.width, height: r.height };
    };
    const strip = app.querySelector('.sd-tools');
    const views = [...app.querySelectorAll('.sd-view')];
    return {
      app: box(app),
      strip: box(strip),
      // Buttons inside the strip's scrolled box (a row scrolls sideways when they do not all fit).
      buttons: [...(strip?.querySelectorAll('.sd-tool') ?? [])].map((b) => ({ action: b.dataset.action, ...box(b) })).filter((b) => b.width),
      views: views.map(box),
      stats: views.map((v) => {
        const s = v.querySelector('.sd-stats');
        return { ...box(s), clipped: s.scrollWidth > s.clientWidth + 1 || s.scrollHeight > s.clientHeight + 1 };
      }),
      banner: box(app.querySelector('.sd-banner')),
      panel: box(app.querySelector('.lil-gui.lil-root')),
      lesson: box(app.querySelector('.sd-lesson')),
      // The status bar: cut at its edge or not, and how wide the model's name and size are.
      status: { cut: app.querySelector('.sd-status').scrollWidth > app.querySelector('.sd-status').clientWidth + 1,
        model: box(app.querySelector('.sd-model'))?.width ?? 0 },
    };
  }, root);
}

/** The strip is one row across the top of the app: every button on one line, the row at most 15% of the width. */
function assertOneRow(l, what) {
  assert.ok(l.strip, `${what}: a tool strip`);
  assert.ok(l.strip.height <= 0.15 * l.app.width, `${what}: the strip is ${l.strip.height} px high, more than 15% of ${l.app.width} px`);
  assert.ok(l.strip.width >= l.app.width - 2 - SLACK, `${what}: the strip is a row across the app (${l.strip.width} of ${l.app.width} px)`);
  const tops = new Set(l.buttons.map((b) => Math.round(b.top)));
  assert.equal(tops.size, 1, `${what}: the buttons are on ${tops.size} lines (${[...tops]})`);
  for (const b of l.buttons) assert.ok(b.width >= 40 && b.height >= 40, `${what}: button ${b.action} is ${b.width} x ${b.height} px`);
}

/**
 * A phone in landscape: the strip is one column of icons down the side, at most 8% of the app's width (its
 * labelled buttons wrapped into three columns, 157 px of 844), and the views lie side by side in the rest.
 */
function assertOneColumn(l, views, what) {
  assert.ok(l.strip, `${what}: a tool strip`);
  assert.ok(l.strip.width <= 0.08 * l.app.width, `${what}: the strip is ${l.strip.width} px wide, more than 8% of ${l.app.width} px`);
  const lefts = new Set(l.buttons.map((b) => Math.round(b.left)));
  assert.equal(lefts.size, 1, `${what}: the buttons are in ${lefts.size} columns (${[...lefts]})`);
  for (const b of l.buttons) assert.ok(b.width >= 40 && b.height >= 40, `${what}: button ${b.action} is ${b.width} x ${b.height} px`);
  assert.equal(l.views.length, views, `${what}: ${views} views`);
  const room = l.app.width - l.strip.width;
  l.views.forEach((v, i) => {
    assert.ok(v.left >= l.strip.right - SLACK, `${what}: view ${i} lies beside the strip`);
    assert.ok(v.width >= (0.95 * room) / views, `${what}: view ${i} is ${v.width} px wide of ${room}`);
    assert.ok(Math.abs(v.top - l.views[0].top) <= SLACK, `${what}: view ${i} is beside view 0`);
  });
}

/** The views are stacked, each at least 90% of the app's width, and below the strip. */
function assertStacked(l, count, what) {
  assert.equal(l.views.length, count, `${what}: ${count} views`);
  l.views.forEach((v, i) => {
    assert.ok(v.width >= 0.9 * l.app.width, `${what}: view ${i} is ${v.width} px wide of ${l.app.width}`);
    assert.ok(v.top >= l.strip.bottom - SLACK, `${what}: view ${i} starts under the strip`);
    if (i) assert.ok(v.top >= l.views[i - 1].bottom - SLACK, `${what}: view ${i} is under view ${i - 1}`);
  });
}

/** Each view's stats lie inside it, nothing cut off. */
function assertStatsInside(l, what) {
  l.stats.forEach((s, i) => {
    const v = l.views[i];
    assert.ok(s.width > 0, `${what}: view ${i} shows its stats`);
    assert.ok(s.left >= v.left - SLACK && s.right <= v.right + SLACK && s.top >= v.top - SLACK && s.bottom <= v.bottom + SLACK,
      `${what}: the stats of view ${i} (${JSON.stringify(s)}) leave the view (${JSON.stringify(v)})`);
    assert.equal(s.clipped, false, `${what}: the stats of view ${i} are cut off`);
  });
}

/** The status bar's texts end inside it, the model's name and size in sight. */
function assertStatus(l, what) {
  assert.equal(l.status.cut, false, `${what}: the status bar's text runs past its edge`);
  assert.ok(l.status.model >= 0.4 * l.app.width, `${what}: the model's line is ${l.status.model} px wide`);
}

/** The banner covers no view and not the strip. */
function assertBannerAside(l, what) {
  assert.ok(l.banner, `${what}: the banner is shown`);
  l.views.forEach((v, i) => assert.ok(!overlaps(l.banner, v), `${what}: the banner ${JSON.stringify(l.banner)} covers view ${i} ${JSON.stringify(v)}`));
  assert.ok(!overlaps(l.banner, l.strip), `${what}: the banner covers the tool strip`);
}

/**
 * The gizmo's handles as drawn in view `view` of the app `get` (a page expression): every vertex of the visible
 * handles of its current mode, projected; the extreme x and y in the view's device coordinates (1: the edge).
 */
function gizmoExtent(page, get, view = 0) {
  return page.evaluate(({ get, view }) => {
    const v = new Function(`return ${get}`)().views[view];
    const camera = v.viewport.camera;
    const controls = v.gizmo.controls;
    controls.getHelper().updateMatrixWorld(true);
    const handles = controls._gizmo.gizmo[controls.mode];
    let x = 0;
    let y = 0;
    let count = 0;
    handles.traverse((o) => {
      if (!o.isMesh && !o.isLine) return;
      if (!o.visible || o.scale.x < 1e-6) return;
      const p = o.geometry.attributes.position;
      const q = camera.position.clone();
      for (let i = 0; i < p.count; ++i) {
        q.fromBufferAttribute(p, i).applyMatrix4(o.matrixWorld).project(camera);
        x = Math.max(x, Math.abs(q.x));
        y = Math.max(y, Math.abs(q.y));
        count++;
      }
    });
    return { x, y, count, aspect: camera.aspect, size: controls.size };
  }, { get, view });
}

/** A course page of two elements, on a plain static host (no isolation headers, no shim). */
function coursePage() {
  return '<!doctype html><html><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">' +
    '<link rel="icon" href="data:,"><style>body { margin: 24px 12px; font: 15px system-ui; } subspace-deformer { display: block; margin: 12px 0; }</style>' +
    '<script type="module" src="dist/subspace-deformer.js"></script></head><body><h1>Week 3</h1>' +
    // method="bogus": the element names the bad attribute in its banner (a banner to place and dismiss).
    '<subspace-deformer id="bar" example="bar" method="bogus" style="height: 380px"></subspace-deformer>' +
    '<subspace-deformer id="cmp" example="bar" compare="arap,subspace,full" panel="none" style="height: 340px"></subspace-deformer>' +
    '</body></html>';
}

// The lowest point of view `view`'s mesh on the page (its vertices through the camera's projection, view offset
// included) and the top of that view's stats box.
function meshBottomAndStatsTop(page, view = 0) {
  return page.evaluate((view) => {
    const v = globalThis.subspaceDeformer.views[view];
    const vp = v.viewport;
    const p = v.positions;
    vp.camera.updateMatrixWorld();
    const m = vp.camera.matrixWorldInverse.elements;
    const q = vp.camera.projectionMatrix.elements;
    const rect = vp.canvas.getBoundingClientRect();
    let bottom = -Infinity;
    for (let i = 0; i < p.length; i += 3) {
      const e = [0, 1, 2, 3].map((r) => m[r] * p[i] + m[4 + r] * p[i + 1] + m[8 + r] * p[i + 2] + m[12 + r]);
      const c = [1, 3].map((r) => q[r] * e[0] + q[4 + r] * e[1] + q[8 + r] * e[2] + q[12 + r] * e[3]);
      bottom = Math.max(bottom, rect.top + ((1 - c[0] / c[1]) / 2) * rect.height);
    }
    return { bottom, statsTop: vp.statsLine.getBoundingClientRect().top, viewTop: rect.top };
  }, view);
}

export default [
  {
    // A tester's phone: the skeleton lesson's arm sat under the stats and plot while the top 40% of the view was empty.
    name: 'phone (390 x 844, touch): a lesson\'s model is framed above the stats and the plot, not under them',
    timeout: 90000,
    async run(t) {
      const page = await t.touchPage('index.html?lesson=skeleton', PHONE);
      await appReady(page);
      await page.waitForFunction(() => globalThis.subspaceDeformer.lesson?.id === 'skeleton', null, { timeout: 60000 });
      await page.evaluate(() => globalThis.subspaceDeformer.solve());
      await page.evaluate(() => globalThis.subspaceDeformer.fitView());
      await animationFrames(page, 2);
      const { bottom, statsTop, viewTop } = await meshBottomAndStatsTop(page);
      assert.ok(bottom <= statsTop + SLACK, `the mesh reaches ${bottom.toFixed(0)} px, the stats start at ${statsTop.toFixed(0)}`);
      assert.ok(statsTop - viewTop > 250, 'a view tall enough to test');
      await t.screenshot(page, 'phone-skeleton-lesson');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'phone embed (390 x 844, touch, plain static server): one row of icons, stacked compare views, the banner beside the model and dismissed by a tap',
    timeout: 120000,
    async run(t) {
      const root = mkdtempSync(join(tmpdir(), 'sd-small-'));
      try {
        cpSync(dist, join(root, 'dist'), { recursive: true });
        writeFileSync(join(root, 'course.html'), coursePage());
        const url = await t.serve({ root, prefix: '/site/' });
        const page = await t.touchPage(null, PHONE);
        await page.goto(`${url}course.html`);
        for (const id of ['bar', 'cmp']) await appReady(page, `document.getElementById('${id}').app`, { timeout: 60000 });
        const fingers = await Fingers.on(page);

        // The figure with a banner: one row of icons, the banner under the view, not over the model or the strip.
        const bar = "document.querySelector('#bar .sd-app')";
        await page.locator('#bar').scrollIntoViewIfNeeded();
        await appShown(page, "document.getElementById('bar').app");
        let l = await layout(page, bar);
        assertOneRow(l, 'embed');
        assertStacked(l, 1, 'embed');
        assertBannerAside(l, 'embed');
        assertStatsInside(l, 'embed');
        assertStatus(l, 'embed');
        assert.match(await page.locator('#bar .sd-banner .sd-message').textContent(), /method/);
        await t.screenshot(page, 'small-embed-banner');
        const viewHeight = l.views[0].height;
        await fingers.tap(await centre(page.locator('#bar .sd-banner .sd-close')));
        l = await layout(page, bar);
        assert.equal(l.banner, null, 'a tap on the x dismissed the banner');
        assert.ok(l.views[0].height > viewHeight, `the view took the banner's room (${viewHeight} -> ${l.views[0].height} px)`);
        await animationFrames(page, 3); // the view framed again for its new size
        await appShown(page, "document.getElementById('bar').app");
        const gizmo = await gizmoExtent(page, "document.getElementById('bar').app");
        assert.ok(gizmo.count > 0 && gizmo.x <= 1 && gizmo.y <= 1, `embed: the gizmo reaches ${gizmo.x.toFixed(2)}, ${gizmo.y.toFixed(2)} of the view`);

        // Three methods compared: stacked, each the width of the element, stats inside.
        const cmp = "document.querySelector('#cmp .sd-app')";
        await page.locator('#cmp').scrollIntoViewIfNeeded();
        await appShown(page, "document.getElementById('cmp').app");
        l = await layout(page, cmp);
        assertOneRow(l, 'compare embed');
        assertStacked(l, 3, 'compare embed');
        assertStatsInside(l, 'compare embed');
        assertStatus(l, 'compare embed');
        await t.screenshot(page, 'small-embed-compare');
        assert.deepEqual(page.errors, []);
      } finally {
        rmSync(root, { recursive: true, force: true });
      }
    },
  },
  {
    name: 'phone app (390 x 844, touch): the gizmo inside the view, the panel closed by the tap that opened it, a lesson stacked, banners aside',
    timeout: 120000,
    async run(t) {
      const page = await t.touchPage('index.html', PHONE);
      await appReady(page);
      await appShown(page);
      const fingers = await Fingers.on(page);
      const root = "document.querySelector('.sd-app')";
      let l = await layout(page, root);
      assertOneRow(l, 'app');
      assertStacked(l, 1, 'app');
      assertStatsInside(l, 'app');
      assertStatus(l, 'app');
      // The default view (the bar, its right end moving): the gizmo's handles stay inside the view.
      const gizmo = await gizmoExtent(page, 'globalThis.subspaceDeformer');
      assert.ok(gizmo.count > 0 && gizmo.x <= 1 && gizmo.y <= 1, `the gizmo reaches ${gizmo.x.toFixed(2)}, ${gizmo.y.toFixed(2)} of the view (aspect ${gizmo.aspect.toFixed(2)}, size ${gizmo.size})`);
      await t.screenshot(page, 'small-app-start');

      // The panel button: one tap opens the panel, a second tap at the same point closes it.
      const button = page.locator('.sd-tool[data-action="panel"]');
      const at = await centre(button);
      await fingers.tap(at);
      assert.equal(await page.evaluate('globalThis.subspaceDeformer.panelOpen'), true, 'the tap opened the panel');
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      const after = await centre(button);
      assert.ok(Math.abs(after.x - at.x) <= SLACK && Math.abs(after.y - at.y) <= SLACK, `the panel button moved from ${JSON.stringify(at)} to ${JSON.stringify(after)}`);
      l = await layout(page, root);
      assert.ok(l.panel && !overlaps(l.panel, l.views[0]) && !overlaps(l.panel, l.strip), 'the open panel covers neither the view nor the strip');
      await t.screenshot(page, 'small-app-panel');
      await fingers.tap(at);
      assert.equal(await page.evaluate('globalThis.subspaceDeformer.panelOpen'), false, 'the same tap closed it');

      // A lesson comparing two methods: the views stacked, the lesson bar under them.
      await page.evaluate("globalThis.subspaceDeformer.loadLesson('arap-vs-subspace')");
      await appShown(page);
      l = await layout(page, root);
      assertOneRow(l, 'lesson');
      assertStacked(l, 2, 'lesson');
      assertStatsInside(l, 'lesson');
      assert.ok(l.lesson && l.views.every((v) => !overlaps(v, l.lesson)), 'the lesson bar is under the views');
      await t.screenshot(page, 'small-app-lesson');

      // A banner (an action that needs a selection): beside the views and the strip; its x dismisses it.
      await page.evaluate('globalThis.subspaceDeformer.addGroupFromSelection(true)');
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      l = await layout(page, root);
      assertBannerAside(l, 'app');
      assertStatsInside(l, 'app with a banner');
      await t.screenshot(page, 'small-app-banner');
      await fingers.tap(await centre(page.locator('.sd-banner .sd-close')));
      assert.equal((await layout(page, root)).banner, null, 'a tap on the x dismissed the banner');
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'phone app in landscape (844 x 390, touch): one column of icons beside the views, a lesson side by side',
    timeout: 120000,
    async run(t) {
      const page = await t.touchPage('index.html', { width: PHONE.height, height: PHONE.width });
      await appReady(page);
      await appShown(page);
      const root = "document.querySelector('.sd-app')";
      let l = await layout(page, root);
      assert.equal(await page.evaluate(`${root}.className`).then((c) => c.includes('sd-narrow')), false, 'wider than a phone in portrait');
      assertOneColumn(l, 1, 'landscape app');
      assertStatsInside(l, 'landscape app');
      assert.equal(l.status.cut, false, 'landscape app: the status bar\'s text runs past its edge');
      await t.screenshot(page, 'small-landscape-start');
      // The panel button, first in the column, opens the panel and the same tap closes it.
      const fingers = await Fingers.on(page);
      const at = await centre(page.locator('.sd-tool[data-action="panel"]'));
      assert.ok(at.y < l.buttons[0].bottom, 'the panel button is first in the column');
      await fingers.tap(at);
      assert.equal(await page.evaluate('globalThis.subspaceDeformer.panelOpen'), true, 'the tap opened the panel');
      await fingers.tap(at);
      assert.equal(await page.evaluate('globalThis.subspaceDeformer.panelOpen'), false, 'the same tap closed it');
      await page.evaluate("globalThis.subspaceDeformer.loadLesson('arap-vs-subspace')");
      await appShown(page);
      l = await layout(page, root);
      assertOneColumn(l, 2, 'landscape lesson');
      assertStatsInside(l, 'landscape lesson');
      await t.screenshot(page, 'small-landscape-lesson');
      assert.deepEqual(page.errors, []);
    },
  },
];
