// What the build puts in dist/: the bunny's data once, in the chunk the solver worker loads it from (issue 31,
// item 4: there were two copies, since the page imported web/lib/examples.js for the examples' names and so
// bundled its import('bunny') as well; the page now takes the names from example_names.js). cage.test.mjs
// loads the bunny in the app.
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';
import { dirname, join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';

const dist = process.env.SD_E2E_DIST ?? join(dirname(fileURLToPath(import.meta.url)), '..', '..', 'dist');
// The bunny's first vertex as a bundle writes it (1.301895, 0.122622, 2.550061), minified or not.
const BUNNY_FIRST_VERTEX = /1\.301895,\s*0?\.122622,\s*2\.550061/;

/** Every file under `dir`. */
function filesUnder(dir) {
  return readdirSync(dir, { withFileTypes: true }).flatMap((e) => (e.isDirectory() ? filesUnder(join(dir, e.name)) : [join(dir, e.name)]));
}

export default [
  {
    name: 'the build holds one copy of the bunny, the solver worker\'s',
    async run() {
      const scripts = filesUnder(dist).filter((f) => /\.m?js$/.test(f));
      const copies = scripts.filter((f) => BUNNY_FIRST_VERTEX.test(readFileSync(f, 'latin1'))).map((f) => relative(dist, f));
      assert.equal(copies.length, 1, `copies of the bunny in ${dist}: ${copies.join(', ')}`);
      const worker = scripts.find((f) => /solver_worker-[\w-]+\.js$/.test(f));
      assert.ok(worker, 'the solver worker\'s chunk');
      assert.match(readFileSync(join(dist, copies[0]), 'utf8'), /from"\.\/solver_worker-[\w-]+\.js"|from '\.\/solver_worker-/,
        'the bunny chunk is the worker\'s');
    },
  },
];
