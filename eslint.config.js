// ESLint (flat config) for the project's JavaScript: the library and the app (web/), the scripts and the CLI
// (scripts/), the tests (tests/), and the module's post-js (cpp/bindings/js_errors.post.js). `npm run lint`
// runs it with the C++ format check.
import js from '@eslint/js';
import globals from 'globals';

export default [
  { ignores: ['build/**', 'dist/**', 'node_modules/**', 'test-results/**'] },
  js.configs.recommended,
  {
    languageOptions: { ecmaVersion: 2022, sourceType: 'module' },
    rules: {
      // A parameter named _x is accepted on purpose and unused (e.g. exampleNames(_solver), kept for callers
      // that pass the module).
      'no-unused-vars': ['error', { argsIgnorePattern: '^_' }],
    },
  },
  // The library and the app run in pages and Web Workers.
  { files: ['web/**/*.js'], languageOptions: { globals: { ...globals.browser, ...globals.worker } } },
  // The library's Node entry and its file reader.
  { files: ['web/lib/node.js', 'web/lib/node_files.js'], languageOptions: { globals: globals.node } },
  { files: ['scripts/**/*.{js,mjs}', 'web/vite.config.js', 'eslint.config.js'], languageOptions: { globals: globals.node } },
  // Browser benchmarks: Node scripts whose page.evaluate callbacks run in the page.
  { files: ['scripts/bench/browser.mjs', 'scripts/bench/compare.mjs', 'scripts/bench/big.mjs', 'scripts/bench/skeleton_drag.mjs', 'scripts/lib/browser_bench.mjs'], languageOptions: { globals: globals.browser } },
  // Tests run in Node; the browser tests' page.evaluate callbacks run in the page.
  { files: ['tests/**/*.{js,mjs}'], languageOptions: { globals: { ...globals.node, ...globals.browser } } },
  // Emscripten's --post-js: a classic script inside the generated module, with the module's own names.
  {
    files: ['cpp/**/*.js'],
    languageOptions: {
      sourceType: 'script',
      globals: { ...globals.browser, ...globals.node, Module: 'readonly', addOnPostRun: 'readonly' },
    },
  },
];
