// Starting Web Workers so that they run on every page of a course site. A cross-origin isolated page (COEP
// require-corp, which the threaded build needs) may only start a worker whose script response carries COEP
// too. On a static host the coi-serviceworker shim adds the header, but only to what lies in its folder: a page
// with the shim beside it in week1/ that loads the build from ../dist/ got its solver worker blocked
// (ERR_BLOCKED_BY_RESPONSE: "solver worker failed: could not start"). A worker started from a blob: URL has no
// script response of its own: it takes the page's isolation and service worker, and the real script arrives
// as an ordinary same-origin import, which COEP allows wherever it lies. So every worker of the library starts
// from a one-line blob that imports (module workers) or importScripts (classic ones) the real script.

/** Whether blob: workers can be made here (browsers; not Node, where no Worker of this kind exists). */
function blobsAvailable() {
  return typeof Blob === 'function' && typeof URL?.createObjectURL === 'function';
}

/** A blob: URL of a script of one line: the real script's import (module) or importScripts (classic). */
export function bootstrapUrl(url, { module = true } = {}) {
  const href = JSON.stringify(String(url));
  const source = module ? `import ${href};\n` : `importScripts(${href});\n`;
  return URL.createObjectURL(new Blob([source], { type: 'text/javascript' }));
}

/**
 * Used as `new ModuleWorker(new URL('./x.js', import.meta.url), { type: 'module' })`: bundlers (Vite) see
 * that shape and put the worker's bundled chunk's URL there; at run time the worker starts from a bootstrap
 * blob that imports it.
 */
export function ModuleWorker(url, options) {
  if (!blobsAvailable()) return new Worker(url, options);
  const blobUrl = bootstrapUrl(new URL(url, globalThis.location?.href).href, { module: true });
  const worker = new Worker(blobUrl, { ...options, type: 'module' });
  // The blob is read when the worker starts; afterwards its URL is not needed.
  setTimeout(() => URL.revokeObjectURL(blobUrl), 60000);
  return worker;
}
