// The project's layout rules, read from the sources:
// - web/: no import cycle between its modules (a cycle is how the app and its panel once knew each other),
//   and no file longer than 400 lines (one concept per file). Imports are the static imports, re-exports
//   and dynamic import() calls with a relative path; type-only JSDoc imports are comments and do not count.
// - cpp/bindings: reaches only public headers of the core, never one under an `internal/` folder (private
//   to its concept, docs/architecture.md), directly or through the headers it includes.
import { existsSync, readdirSync, readFileSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const repo = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..');
const web = join(repo, 'web');
const cpp = join(repo, 'cpp');
const MAX_LINES = 400;

function sourceFiles(dir, pattern = /\.(js|mjs)$/) {
  return readdirSync(dir, { withFileTypes: true }).flatMap((entry) => {
    const path = join(dir, entry.name);
    if (entry.isDirectory()) return entry.name === 'node_modules' ? [] : sourceFiles(path, pattern);
    return pattern.test(entry.name) ? [path] : [];
  });
}

/** The project headers a C++ source includes ("core/...", "bindings/...": paths relative to cpp/). */
export function includesOf(source) {
  return [...source.matchAll(/^\s*#\s*include\s+"([^"]+)"/gm)].map((m) => m[1]);
}

/**
 * Every project header reachable from `files` through quoted includes, with the file that included it first.
 * @returns {Map<string, string>} header path (relative to cpp/) -> the including file (relative to cpp/)
 */
function reachableHeaders(files) {
  const reached = new Map();
  const queue = files.map((f) => relative(cpp, f));
  while (queue.length) {
    const from = queue.shift();
    for (const header of includesOf(readFileSync(join(cpp, from), 'utf8'))) {
      if (reached.has(header)) continue;
      reached.set(header, from);
      queue.push(header);
    }
  }
  return reached;
}

/** The relative module paths a source imports (comments removed first, so JSDoc type imports do not count). */
export function importsOf(source) {
  const code = source.replace(/\/\*[\s\S]*?\*\//g, '').replace(/(^|[^:\\])\/\/.*$/gm, '$1');
  const specifiers = [];
  const patterns = [/\b(?:import|export)\s[^'"`;]*?\bfrom\s*['"]([^'"]+)['"]/g, /\bimport\s*['"]([^'"]+)['"]/g, /\bimport\(\s*['"]([^'"]+)['"]\s*\)/g];
  for (const pattern of patterns) for (const match of code.matchAll(pattern)) specifiers.push(match[1]);
  return specifiers.filter((s) => s.startsWith('.'));
}

/**
 * A cycle in a directed graph, as the list of its nodes (first repeated at the end), or null.
 * @param {Map<string, string[]>} graph node -> nodes it points to
 */
export function findCycle(graph) {
  const state = new Map(); // undefined: unseen, 1: on the current path, 2: done
  const path = [];
  const visit = (node) => {
    state.set(node, 1);
    path.push(node);
    for (const next of graph.get(node) ?? []) {
      if (state.get(next) === 1) return [...path.slice(path.indexOf(next)), next];
      if (state.get(next) === undefined) {
        const cycle = visit(next);
        if (cycle) return cycle;
      }
    }
    path.pop();
    state.set(node, 2);
    return null;
  };
  for (const node of graph.keys()) {
    if (state.get(node) === undefined) {
      const cycle = visit(node);
      if (cycle) return cycle;
    }
  }
  return null;
}

const files = sourceFiles(web);

describe('web/ layout', () => {
  it('finds the JS sources, and their imports between each other', () => {
    const names = files.map((f) => relative(web, f));
    expect(names).toContain('app/deformer_app.js');
    expect(names).toContain('lib/deformer.js');
    const app = importsOf(readFileSync(join(web, 'app', 'deformer_app.js'), 'utf8'));
    expect(app).toContain('./settings.js');
  });

  it('reads static, re-exported and dynamic imports, but not those in comments', () => {
    const source = [
      "import { a } from './a.js';",
      "import b, { c as d } from '../b.js';",
      "export { e } from './e.js';",
      "export * from './f.js';",
      "import './side_effect.js';",
      "const g = await import('./g.js');",
      "import { Vector3 } from 'three';",
      "/** @param {import('./typed.js').T} t */",
      "// import { h } from './commented.js';",
      "const url = 'http://example.org/x.js'; // from './trailing.js'",
    ].join('\n');
    expect(importsOf(source)).toEqual(['./a.js', '../b.js', './e.js', './f.js', './side_effect.js', './g.js']);
  });

  it('the cycle finder reports a cycle, and none in a tree', () => {
    expect(findCycle(new Map([['a', ['b']], ['b', ['c']], ['c', ['a']], ['d', ['a']]]))).toEqual(['a', 'b', 'c', 'a']);
    expect(findCycle(new Map([['a', ['b', 'c']], ['b', ['c']], ['c', []]]))).toBeNull();
    expect(findCycle(new Map([['a', ['a']]]))).toEqual(['a', 'a']);
  });

  it('has no import cycle', () => {
    const graph = new Map(files.map((file) => [file, importsOf(readFileSync(file, 'utf8')).map((s) => resolve(dirname(file), s))]));
    // Every import inside web/ names a source there (imports of build outputs, e.g. the wasm loader, are outside).
    for (const [file, targets] of graph) {
      for (const target of targets.filter((t) => !relative(web, t).startsWith('..'))) {
        // Data (a lesson's .json) is no source: it must only exist.
        const found = target.endsWith('.json') ? existsSync(target) : graph.has(target);
        expect(found, `${relative(web, file)} imports a missing ${relative(web, target)}`).toBe(true);
      }
    }
    const cycle = findCycle(graph);
    expect(cycle && cycle.map((f) => relative(web, f)).join(' -> '), 'import cycle').toBeNull();
  });

  it(`has no file over ${MAX_LINES} lines`, () => {
    const long = files
      .map((file) => ({ file: relative(web, file), lines: readFileSync(file, 'utf8').split('\n').length - 1 }))
      .filter((f) => f.lines > MAX_LINES);
    expect(long).toEqual([]);
  });
});

describe('cpp/bindings layout', () => {
  it('reads quoted includes only', () => {
    const source = '#include <emscripten/bind.h>\n#include "core/mesh/mesh.h"\n  #  include "bindings/convert.h"\n// #include "x.h" is a comment\n';
    expect(includesOf(source)).toEqual(['core/mesh/mesh.h', 'bindings/convert.h']);
  });

  it('includes no header under an internal/ folder, directly or through another header', () => {
    const bindings = sourceFiles(join(cpp, 'bindings'), /\.(cpp|h)$/);
    expect(bindings.length).toBeGreaterThan(3);
    const reached = reachableHeaders(bindings);
    expect(reached.has('core/solver/deformer.h')).toBe(true);
    const internal = [...reached].filter(([header]) => header.split('/').includes('internal')).map(([header, from]) => `${from} -> ${header}`);
    expect(internal).toEqual([]);
  });
});
