// Vite configuration for the browser app. Rooted at web/, built into dist/ at the repository root.
// `base: './'` makes every URL in the build relative, so dist/ works from any sub-folder of a plain
// static server (course pages). The wasm module comes from build/wasm (outside the root), hence
// server.fs.allow; its loader references the .wasm with new URL(..., import.meta.url), so Vite copies it.
//
// Threads (docs/threads.md): the dev and preview servers send COOP/COEP, so `npm start` is cross-origin
// isolated and the solver workers load the threaded build. That build is served and copied as-is (never
// bundled: its pthread workers load it again by its own URL) into threads/ at the site root, and
// coi-serviceworker.js sits at the root so that a static host that cannot send headers gets isolation
// from the service worker (index.html and embed-example.html load it first).
import { existsSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vite';

const webRoot = fileURLToPath(new URL('.', import.meta.url));
const repoRoot = fileURLToPath(new URL('..', import.meta.url));

const ISOLATION_HEADERS = {
  'Cross-Origin-Opener-Policy': 'same-origin',
  'Cross-Origin-Embedder-Policy': 'require-corp',
};

// Site path -> file. The threaded build is optional: without it pages fall back to single-threaded.
const AS_IS_FILES = {
  'threads/subspace_deform.js': 'build/wasm/threads/subspace_deform.js',
  'threads/subspace_deform.wasm': 'build/wasm/threads/subspace_deform.wasm',
  'threads/subspace_deform.worker.js': 'build/wasm/threads/subspace_deform.worker.js',
  'coi-serviceworker.js': 'node_modules/coi-serviceworker/coi-serviceworker.min.js',
};
const TYPES = { '.js': 'text/javascript; charset=utf-8', '.wasm': 'application/wasm' };

function asIsFiles() {
  const present = () => Object.entries(AS_IS_FILES).filter(([, file]) => existsSync(repoRoot + file));
  return {
    name: 'subspace-deform-as-is-files',
    configureServer(server) {
      server.middlewares.use((req, res, next) => {
        const path = decodeURIComponent(new URL(req.url, 'http://x').pathname).replace(/^\/+/, '');
        const file = AS_IS_FILES[path];
        if (!file || !existsSync(repoRoot + file)) return next();
        res.writeHead(200, { 'Content-Type': TYPES[path.slice(path.lastIndexOf('.'))], 'Cache-Control': 'no-store', ...ISOLATION_HEADERS });
        res.end(readFileSync(repoRoot + file));
      });
    },
    generateBundle() {
      const files = present();
      if (!files.some(([path]) => path.startsWith('threads/'))) {
        this.warn('build/wasm/threads is missing: the site will run single-threaded everywhere');
      }
      for (const [fileName, file] of files) this.emitFile({ type: 'asset', fileName, source: readFileSync(repoRoot + file) });
    },
  };
}

export default defineConfig({
  root: webRoot,
  base: './',
  publicDir: false,
  plugins: [asIsFiles()],
  server: { fs: { allow: [repoRoot] }, headers: ISOLATION_HEADERS },
  preview: { headers: ISOLATION_HEADERS },
  worker: { format: 'es' },
  build: {
    outDir: fileURLToPath(new URL('../dist', import.meta.url)),
    emptyOutDir: true,
    target: 'es2022',
    chunkSizeWarningLimit: 1500,
    rolldownOptions: {
      input: {
        index: fileURLToPath(new URL('./index.html', import.meta.url)),
        'embed-example': fileURLToPath(new URL('./embed-example.html', import.meta.url)),
        // The one-tag embed for course pages: a stable, unhashed file name (dist/subspace-deformer.js).
        'subspace-deformer': fileURLToPath(new URL('./app/embed/index.js', import.meta.url)),
      },
      // Keep the exports of the embed entry (mount, SubspaceDeformerElement) even though no page imports them.
      preserveEntrySignatures: 'exports-only',
      output: {
        entryFileNames: (chunk) => (chunk.name === 'subspace-deformer' ? 'subspace-deformer.js' : 'assets/[name]-[hash].js'),
      },
    },
  },
});
