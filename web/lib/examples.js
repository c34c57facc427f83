// Every built-in example, for the app, its workers and the CLI: the procedural ones made in C++
// (core/mesh/examples.h: mesh and cage) and those whose mesh comes from an npm package and whose cage is
// generated on load (issue 8). The project ships no third-party model files.
import { PROCEDURAL_EXAMPLES } from '../../build/wasm/solver_schema.js';
import { generateCage, meshFromCells } from './cage.js';
import { makeExample } from './mesh.js';

// A Map: the name comes from users (a scene's "example", ?example=), and no name may reach Object's own
// properties ('constructor', '__proto__').
const GENERATED_EXAMPLES = new Map(Object.entries({
  bunny: {
    description: 'Stanford bunny (npm "bunny", public domain, 1839 vertices) in a generated 120-vertex cage',
    // Loaded on demand: the app bundles it as its own chunk.
    load: async () => meshFromCells((await import('bunny')).default),
    cageVertices: 120,
    // Feet fixed, ears moving (y is up): fractions of the extent along `axis`.
    defaultHandles: { axis: 1, fixedBelow: 0.05, movingAbove: 0.85 },
  },
}));

/**
 * Every built-in example's name, the default first: known without a loaded module (the procedural ones come
 * from the generated schema), so a page can check a name before its worker has started.
 */
export const EXAMPLE_NAMES = Object.freeze([...PROCEDURAL_EXAMPLES, ...GENERATED_EXAMPLES.keys()]);

/**
 * Names of all built-in examples, the default first: a copy of EXAMPLE_NAMES.
 * @param {object} [_solver] not needed (accepted for callers that pass the module)
 * @returns {string[]}
 */
export function exampleNames(_solver) {
  return [...EXAMPLE_NAMES];
}

/**
 * Loads a built-in example. For generated-cage examples the cage takes a second or two; onProgress(fraction)
 * reports it (return false to cancel).
 * @returns {Promise<{ name, description, mesh, cage, cageInfo?: object, defaultHandles?: object }>}
 *   cageInfo: generateCage's statistics when the cage was generated.
 */
export async function loadExample(solver, name, { onProgress } = {}) {
  const generated = GENERATED_EXAMPLES.get(name);
  if (!generated) return makeExample(solver, name);
  const mesh = await generated.load();
  const cage = generateCage(solver, mesh, { vertices: generated.cageVertices, onProgress });
  return { name, description: generated.description, mesh, cage, cageInfo: cage, defaultHandles: generated.defaultHandles };
}
