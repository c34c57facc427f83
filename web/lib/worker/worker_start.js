// @ts-check
// Starting Web Workers so that they run on every page of a course site. A cross-origin isolated page (COEP
// require-corp, which the threaded build needs) may only start a worker whose script response carries COEP
// too. On a static host the coi-serviceworker shim adds the header, but only to what lies in its folder: a page
// with the shim beside it in week1/ that loads the build from ../dist/ got its solver worker blocked
// (ERR_BLOCKED_BY_RESPONSE: "solver worker failed: could not start"). A worker started from a blob: URL has no
// script response of its own: it takes the page's isolation and service worker, and the real script arrives
// as an ordinary same-origin import, which COEP allows wherever it lies. So every worker of the library starts
// from a short blob that imports (module workers) or importScripts (classic ones) the real script.
//
// A module worker's blob first gives the worker its real script's location. Its self.location is the blob:
// URL, which cannot be the base of a relative URL; a worker bundled as a classic script (Vite's default worker
// format, 'iife') has no import.meta.url, and the bundler puts self.location.href in its place, so the bundled
// solver worker looked for its wasm at new URL('subspace_deform-....wasm', 'blob:...') and failed ("Invalid
// URL"). With the location shadowed by the script's URL, both worker formats find their assets beside the script.

/** Whether blob: workers can be made here (browsers; not Node, where no Worker of this kind exists). */
function blobsAvailable() {
  return typeof Blob === 'function' && typeof URL?.createObjectURL === 'function';
}

/**
 * The source of a module worker's bootstrap: a first module makes self.location the script's URL (an own
 * property of the global scope over WorkerGlobalScope's getter; a URL has WorkerLocation's fields), then the
 * script is imported. Both are static imports, run in order: the worker takes its first message only once they
 * have run (a dynamic import after the location lost the messages posted before the script had set onmessage),
 * and a script that fails to load fires the Worker's error event.
 * @param {string} href the script's URL as a JSON string
 */
function moduleBootstrap(href) {
  const prelude = `Object.defineProperty(self, 'location', { value: new URL(${href}), configurable: true, enumerable: true });`;
  return `import ${JSON.stringify(`data:text/javascript,${encodeURIComponent(prelude)}`)};\nimport ${href};\n`;
}

/**
 * A blob: URL of a bootstrap script: the real script's import (module) or importScripts (classic).
 * @param {string|URL} url the real script (absolute)
 * @param {{ module?: boolean }} [options]
 * @returns {string}
 */
export function bootstrapUrl(url, { module = true } = {}) {
  const href = JSON.stringify(String(url));
  const source = module ? moduleBootstrap(href) : `importScripts(${href});\n`;
  return URL.createObjectURL(new Blob([source], { type: 'text/javascript' }));
}

/**
 * Used as `new ModuleWorker(new URL('./x.js', import.meta.url), { type: 'module' })`: bundlers (Vite) see
 * that shape and put the worker's bundled chunk's URL there; at run time the worker starts from a bootstrap
 * blob that imports it. A function called with `new`: it returns the Worker it made.
 * @param {string|URL} url
 * @param {WorkerOptions} [options]
 * @returns {Worker}
 */
export function ModuleWorker(url, options) {
  if (!blobsAvailable()) return new Worker(url, options);
  const blobUrl = bootstrapUrl(new URL(url, globalThis.location?.href).href, { module: true });
  const worker = new Worker(blobUrl, { ...options, type: 'module' });
  // The blob is read when the worker starts; afterwards its URL is not needed.
  setTimeout(() => URL.revokeObjectURL(blobUrl), 60000);
  return worker;
}
