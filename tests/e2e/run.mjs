#!/usr/bin/env node
// Browser tests in Debian's Chromium (playwright-core). Builds the app (vite build -> dist/), serves dist/
// from a sub-folder URL (/course/week3/, as a course page would) with a tiny static server that sends the
// cross-origin isolation headers (so the app runs the threaded build), then runs every tests/e2e/*.test.mjs.
// Each test file default-exports [{ name, run(t) }]; t = { context, url, page(), touchPage(path, viewport),
// serve({ isolated, root, prefix }), screenshot(page, name) }; touchPage() opens a page in a touch screen's
// browser (tests/e2e/touch.mjs); serve() starts another server on dist/ or `root` (a fresh origin, closed after
// the test).
// Screenshots go to test-results/. Prints "N passed, M failed".
//   node tests/e2e/run.mjs [filter] [--json FILE]   SD_E2E_NO_BUILD=1 skips the build; SD_E2E_DIST / SD_E2E_CONFIG override.
//   --json FILE writes {passed, failed, skipped} for scripts/lib/test_summary.mjs.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readdirSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { serveStatic } from './static_server.mjs';
import { launchBrowser, watchErrors } from './browser.mjs';
import { launchTouch } from './touch.mjs';
import { Timer } from '../../scripts/lib/timer.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const repo = join(here, '..', '..');
const dist = process.env.SD_E2E_DIST ?? join(repo, 'dist');
const results = join(repo, 'test-results');
const args = process.argv.slice(2);
const jsonIndex = args.indexOf('--json');
const jsonFile = jsonIndex >= 0 ? args.splice(jsonIndex, 2)[1] : null;
const filter = args[0] ?? '';
const started = new Timer();

if (!process.env.SD_E2E_NO_BUILD) {
  const config = process.env.SD_E2E_CONFIG ?? join(repo, 'web', 'vite.config.js');
  if (!existsSync(join(repo, 'build', 'wasm', 'subspace_deform.js')) && !process.env.SD_E2E_CONFIG) {
    console.error('e2e: build/wasm/subspace_deform.js is missing: run `bash scripts/build.sh --wasm` first');
    process.exit(1);
  }
  const build = spawnSync(process.execPath, [join(repo, 'node_modules', 'vite', 'bin', 'vite.js'), 'build', '--config', config, '--logLevel', 'warn'],
    { cwd: repo, stdio: 'inherit', env: { ...process.env, NO_COLOR: '1' } });
  if (build.status !== 0) {
    console.error('e2e: vite build failed');
    process.exit(1);
  }
}
mkdirSync(results, { recursive: true });

const files = readdirSync(here).filter((f) => f.endsWith('.test.mjs')).sort();
const tests = [];
for (const file of files) {
  const mod = await import(pathToFileURL(join(here, file)).href);
  for (const test of mod.default) tests.push({ ...test, file });
}

const server = await serveStatic(dist, { prefix: '/course/week3/', isolated: true });
const browser = await launchBrowser();
const pages = new Set();
const extraServers = new Set();
const touchBrowsers = new Set();
const t = {
  context: browser.context,
  url: server.url,
  async page(path = 'index.html') {
    const page = await browser.context.newPage();
    page.errors = watchErrors(page);
    pages.add(page);
    if (path) await page.goto(server.url + path);
    return page;
  },
  /** A page in a phone's or tablet's browser (touch, coarse pointer, its viewport); closed after the test. */
  async touchPage(path, viewport) {
    const touch = await launchTouch(viewport);
    touchBrowsers.add(touch);
    const page = await touch.context.newPage();
    page.errors = watchErrors(page);
    if (path) await page.goto(server.url + path);
    return page;
  },
  /**
   * Another server (its own port, so its own origin and service workers), on dist/ under /course/week3/ or on
   * `root` under `prefix`; closed after the test.
   */
  async serve({ isolated = false, root = dist, prefix = '/course/week3/' } = {}) {
    const extra = await serveStatic(root, { prefix, isolated });
    extraServers.add(extra);
    return extra.url;
  },
  async screenshot(page, name) {
    const file = join(results, `${name}.png`);
    await page.screenshot({ path: file });
    return file;
  },
};

let passed = 0;
let failed = 0;
for (const test of tests) {
  if (filter && !`${test.file} ${test.name}`.includes(filter)) continue;
  const timer = new Timer();
  try {
    await Promise.race([
      test.run(t),
      new Promise((_, reject) => setTimeout(() => reject(new Error(`timed out after ${test.timeout ?? 30000} ms`)), test.timeout ?? 30000)),
    ]);
    passed++;
    console.log(`ok   ${test.name} (${timer.ms().toFixed(0)} ms)`);
  } catch (error) {
    failed++;
    console.log(`FAIL ${test.name} (${timer.ms().toFixed(0)} ms)\n     ${String(error?.stack ?? error).split('\n').join('\n     ')}`);
  } finally {
    for (const page of pages) await page.close().catch(() => {});
    pages.clear();
    for (const extra of extraServers) await extra.close();
    extraServers.clear();
    for (const touch of touchBrowsers) await touch.close();
    touchBrowsers.clear();
  }
}

await browser.close();
await server.close();
console.log(`e2e: ${started.seconds().toFixed(1)} s, screenshots in test-results/`);
console.log(`${passed} passed, ${failed} failed`);
if (jsonFile) writeFileSync(jsonFile, JSON.stringify({ passed, failed, skipped: 0 }));
process.exit(failed ? 1 : 0);
