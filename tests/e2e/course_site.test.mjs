// A course site built from one dist/ on a plain static host (no headers): pages in two folders (week1/,
// week2/figures/) load ../dist/subspace-deformer.js. With the one-line setup per site (coi-serviceworker.js in
// the site's top folder, loaded by every page) both pages are isolated and run the threaded build; the same
// line per page (the shim beside the page) works too (its solver and pthread workers start from bootstrap
// blobs: web/lib/worker/worker_start.js); a page without it works single-threaded and says so in its status
// bar; and the minimal copy of docs/embed.md runs threaded, while a copy without threads/ says why it does not.
import assert from 'node:assert/strict';
import { cpSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { VOLUME_TOLERANCE } from './geometry.mjs';
import { appReady, waitForIsolation } from './app_probe.mjs';

const dist = process.env.SD_E2E_DIST ?? join(dirname(fileURLToPath(import.meta.url)), '..', '..', 'dist');

/** A course page: the shim (a script path, or none), the embed script and one element. */
function coursePage(shim, embed, attributes) {
  return '<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,">' +
    (shim ? `<script src="${shim}"></script>` : '') + `<script type="module" src="${embed}"></script></head><body>` +
    `<h1>A course page</h1><subspace-deformer id="e" ${attributes} style="height: 380px"></subspace-deformer></body></html>`;
}

/** Writes files { path: text } under a fresh folder that also holds the build (whole, or `distFiles` of it). */
function makeSite(pages, { distFiles = null } = {}) {
  const root = mkdtempSync(join(tmpdir(), 'sd-course-'));
  if (distFiles) for (const f of distFiles) cpSync(join(dist, f), join(root, 'dist', f), { recursive: true });
  else cpSync(dist, join(root, 'dist'), { recursive: true });
  for (const [path, text] of Object.entries(pages)) {
    mkdirSync(dirname(join(root, path)), { recursive: true });
    if (text === 'shim') cpSync(join(dist, 'coi-serviceworker.js'), join(root, path));
    else writeFileSync(join(root, path), text);
  }
  return root;
}

/**
 * Opens a page of the site, waits for its element (after the shim's reload when it has the shim), drags,
 * checks the volume.
 */
async function openAndDrag(t, url, { shim = true } = {}) {
  const page = await t.page(null);
  await page.goto(url);
  if (shim) await waitForIsolation(page);
  const el = "document.getElementById('e')";
  await appReady(page, `${el}?.app`);
  const stats = await page.evaluate(`${el}.drag(1, [0, 0.4, 0.1])`);
  assert.ok(stats.iterations > 0 && Math.abs(stats.volumeRelError) <= VOLUME_TOLERANCE, `${url}: ${stats.state}, volume ${stats.volumeRelError}`);
  const solver = await page.evaluate(`${el}.app.model.solver`);
  const note = await page.locator('.sd-build-note').textContent();
  // The shim's reload aborts the first load's requests; nothing else may fail.
  const errors = page.errors.filter((e) => !/ERR_ABORTED/.test(e));
  return { page, solver, note, isolated: await page.evaluate('crossOriginIsolated'), errors };
}

export default [
  {
    name: 'a two-folder course site from one dist/: one line per site gives every page threads; a page without it says it runs single-threaded',
    timeout: 150000,
    async run(t) {
      const root = makeSite({
        'coi-serviceworker.js': 'shim',
        'week1/index.html': coursePage('../coi-serviceworker.js', '../dist/subspace-deformer.js', 'example="bar"'),
        'week2/figures/bend.html': coursePage('../../coi-serviceworker.js', '../../dist/subspace-deformer.js', 'example="bar" compare="subspace,arap"'),
      });
      try {
        const url = await t.serve({ root, prefix: '/site/' });
        for (const path of ['week1/index.html', 'week2/figures/bend.html']) {
          const r = await openAndDrag(t, `${url}${path}`);
          assert.equal(r.isolated, true, `${path} is cross-origin isolated`);
          assert.equal(r.solver.build, 'threads', `${path}: ${JSON.stringify(r.solver)}`);
          assert.equal(r.note, '', `${path}: no single-threaded note`);
          assert.deepEqual(r.errors, [], path);
          await t.screenshot(r.page, `course-site-${path.split('/')[0]}`);
        }
        // Without the line: single-threaded, and the status bar says so and why.
        const plain = makeSite({ 'week3/plain.html': coursePage('', '../dist/subspace-deformer.js', 'example="bar"') });
        try {
          const r = await openAndDrag(t, `${await t.serve({ root: plain, prefix: '/site/' })}week3/plain.html`, { shim: false });
          assert.equal(r.solver.build, 'single');
          assert.equal(r.note, 'single-threaded: page not cross-origin isolated');
          assert.match(await r.page.locator('.sd-build-note').getAttribute('title'), /coi-serviceworker\.js/);
          assert.deepEqual(r.errors, []);
          await t.screenshot(r.page, 'course-site-plain');
        } finally {
          rmSync(plain, { recursive: true, force: true });
        }
      } finally {
        rmSync(root, { recursive: true, force: true });
      }
    },
  },
  {
    name: 'a course page with the shim beside it (outside dist/\'s folder) runs threaded: its workers start from bootstrap blobs',
    timeout: 90000,
    async run(t) {
      const root = makeSite({
        'week4/coi-serviceworker.js': 'shim',
        'week4/page.html': coursePage('coi-serviceworker.js', '../dist/subspace-deformer.js', 'example="bar"'),
      });
      try {
        const r = await openAndDrag(t, `${await t.serve({ root, prefix: '/site/' })}week4/page.html`);
        assert.equal(r.isolated, true);
        assert.equal(r.solver.build, 'threads', JSON.stringify(r.solver));
        assert.deepEqual(r.errors, []);
      } finally {
        rmSync(root, { recursive: true, force: true });
      }
    },
  },
  {
    name: 'the minimal copy of docs/embed.md runs threaded; without threads/ the page says the threaded build did not load',
    timeout: 120000,
    async run(t) {
      // docs/embed.md: subspace-deformer.js, assets/ and threads/ together, coi-serviceworker.js in the site's top folder.
      const minimal = ['subspace-deformer.js', 'assets', 'threads'];
      const page = coursePage('../coi-serviceworker.js', '../dist/subspace-deformer.js', 'example="bar"');
      for (const [files, build] of [[minimal, 'threads'], [minimal.filter((f) => f !== 'threads'), 'single']]) {
        const root = makeSite({ 'coi-serviceworker.js': 'shim', 'notes/page.html': page }, { distFiles: files });
        try {
          const r = await openAndDrag(t, `${await t.serve({ root, prefix: '/site/' })}notes/page.html`);
          assert.equal(r.isolated, true, `${files.join(', ')}: isolated`);
          assert.equal(r.solver.build, build, `${files.join(', ')}: ${JSON.stringify(r.solver)}`);
          if (build === 'single') {
            assert.equal(r.note, 'single-threaded: the threaded build did not load');
            assert.match(await r.page.locator('.sd-build-note').getAttribute('title'), /threads\/subspace_deform\.js|did not load/);
          }
        } finally {
          rmSync(root, { recursive: true, force: true });
        }
      }
    },
  },
];
