// Every built-in example, for the app, its workers and the CLI: the procedural ones made in C++
// (core/mesh/examples.h: mesh and cage) and those whose mesh comes from an npm package and whose cage is
// generated on load (issue 8). The project ships no third-party model files.
import { generateCage, meshFromCells } from './cage.js';
import { exampleNames as proceduralNames, makeExample } from './mesh.js';

const GENERATED_EXAMPLES = {
  bunny: {
    description: 'Stanford bunny (npm "bunny", public domain, 1839 vertices) in a generated 120-vertex cage',
    // Loaded on demand: the app bundles it as its own chunk.
    load: async () => meshFromCells((await import('bunny')).default),
    cageVertices: 120,
    // Feet fixed, ears moving (y is up): fractions of the extent along `axis`.
    defaultHandles: { axis: 1, fixedBelow: 0.05, movingAbove: 0.85 },
  },
};

/** Names of all built-in examples, the default first. */
export function exampleNames(solver) {
  return [...proceduralNames(solver), ...Object.keys(GENERATED_EXAMPLES)];
}

/**
 * Loads a built-in example. For generated-cage examples the cage takes a second or two; onProgress(fraction)
 * reports it (return false to cancel).
 * @returns {Promise<{ name, description, mesh, cage, cageInfo?: object, defaultHandles?: object }>}
 *   cageInfo: generateCage's statistics when the cage was generated.
 */
export async function loadExample(solver, name, { onProgress } = {}) {
  const generated = GENERATED_EXAMPLES[name];
  if (!generated) return makeExample(solver, name);
  const mesh = await generated.load();
  const cage = generateCage(solver, mesh, { vertices: generated.cageVertices, onProgress });
  return { name, description: generated.description, mesh, cage, cageInfo: cage, defaultHandles: generated.defaultHandles };
}
