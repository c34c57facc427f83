// A tiny static file server for dist/ (the e2e tests and the browser benchmark): plain GET, correct MIME
// types for .js/.wasm, 404 otherwise. Started on a free port and closed by its own handle. With
// `isolated` it sends COOP/COEP (cross-origin isolation, as a server configured for threads would);
// without, it is a plain static host (GitHub Pages and the like), where the service worker shim must do it.
import { createServer } from 'node:http';
import { readFile, stat } from 'node:fs/promises';
import { extname, join, normalize, resolve } from 'node:path';

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.wasm': 'application/wasm',
  '.json': 'application/json',
  '.css': 'text/css',
  '.obj': 'text/plain',
  '.off': 'text/plain',
  '.png': 'image/png',
};

const ISOLATION_HEADERS = { 'cross-origin-opener-policy': 'same-origin', 'cross-origin-embedder-policy': 'require-corp' };

/**
 * @param {string} root folder to serve
 * @param {{ prefix?: string, isolated?: boolean }} [options] serve under this URL prefix (e.g.
 *   '/course/week3/') to check that the build works from a sub-folder; isolated: send COOP/COEP
 * @returns {Promise<{ url: string, close: () => Promise<void> }>}
 */
export async function serveStatic(root, { prefix = '/', isolated = false } = {}) {
  const base = resolve(root);
  const server = createServer(async (req, res) => {
    try {
      let path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
      if (!path.startsWith(prefix)) throw Object.assign(new Error('outside prefix'), { code: 'ENOENT' });
      path = normalize(path.slice(prefix.length - 1));
      let file = join(base, path);
      if (!file.startsWith(base)) throw Object.assign(new Error('outside root'), { code: 'ENOENT' });
      if ((await stat(file)).isDirectory()) file = join(file, 'index.html');
      const body = await readFile(file);
      res.writeHead(200, { 'content-type': TYPES[extname(file)] ?? 'application/octet-stream', 'cache-control': 'no-store',
        ...(isolated ? ISOLATION_HEADERS : {}) });
      res.end(body);
    } catch {
      res.writeHead(404, { 'content-type': 'text/plain' });
      res.end('not found');
    }
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  const { port } = server.address();
  return {
    url: `http://127.0.0.1:${port}${prefix}`,
    close: () => new Promise((ok) => {
      server.closeAllConnections?.();
      server.close(() => ok());
    }),
  };
}
