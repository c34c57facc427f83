// Vite configuration for the browser app. Rooted at web/, built into dist/ at the repository root.
// `base: './'` makes every URL in the build relative, so dist/ works from any sub-folder of a plain
// static server (course pages). The wasm module comes from build/wasm (outside the root), hence
// server.fs.allow; its loader references the .wasm with new URL(..., import.meta.url), so Vite copies it.
import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vite';

const webRoot = fileURLToPath(new URL('.', import.meta.url));
const repoRoot = fileURLToPath(new URL('..', import.meta.url));

export default defineConfig({
  root: webRoot,
  base: './',
  publicDir: false,
  server: { fs: { allow: [repoRoot] } },
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
