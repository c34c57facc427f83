// @ts-check
// Every built-in example, for the app, its workers and the CLI: the procedural ones made in C++
// (core/mesh/examples.h: mesh and cage) and those whose mesh comes from elsewhere and whose cage is generated
// on load: the npm package `bunny` and Spot, the one model file the library ships (data/README.md).
import { PROCEDURAL_EXAMPLES } from '../../build/wasm/solver_schema.js';
import { EXAMPLE_NAMES, GENERATED_EXAMPLE_NAMES } from './example_names.js';
import { generateCage, meshFromCells } from './cage.js';
import { InputError } from './errors.js';
import { describeValue } from './options.js';
import { makeExample, readMesh } from './mesh.js';

/** @typedef {import('./solver_module.js').SolverModule} SolverModule */
/** @typedef {import('./mesh.js').MeshData} MeshData */
/** @typedef {import('./cage.js').CageResult} CageResult */
/**
 * Which vertices an example's default handles take, as fractions of the mesh's extent along an axis.
 * @typedef {{ axis: number, fixedBelow: number, movingAbove: number }} ExampleHandles
 */

/**
 * The bytes of a file shipped beside this module: fetched in a browser, read from disk in Node.
 * @param {URL} url
 * @returns {Promise<Uint8Array>}
 */
async function shippedFile(url) {
  if (url.protocol === 'file:') {
    const fs = 'node:fs/promises'; // a variable: bundlers for the browser leave it alone
    const { readFile } = await import(/* @vite-ignore */ fs);
    return new Uint8Array(await readFile(url));
  }
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url.pathname.split('/').pop()}: HTTP ${response.status}`);
  return new Uint8Array(await response.arrayBuffer());
}

// A Map: the name comes from users (a scene's "example", ?example=), and no name may reach Object's own
// properties ('constructor', '__proto__').
const GENERATED_EXAMPLES = new Map(Object.entries({
  bunny: {
    description: 'Stanford bunny (npm "bunny", public domain, 1839 vertices) in a generated 120-vertex cage',
    // Loaded on demand: the app bundles it as its own chunk.
    // An optional peer dependency of the package (the app installs it): say so when it is absent.
    load: async () => {
      let bunny;
      try {
        // @ts-ignore: bunny has no declarations (and is optional)
        bunny = await import('bunny');
      } catch (error) {
        throw new InputError('the bunny example needs the optional package "bunny": npm install bunny', { code: 'unreadable_file', cause: error });
      }
      return meshFromCells(bunny.default);
    },
    cageVertices: 120,
    // Feet fixed, ears moving (y is up): fractions of the extent along `axis`.
    defaultHandles: { axis: 1, fixedBelow: 0.05, movingAbove: 0.85 },
  },
  spot: {
    description: 'Spot, the cow by Keenan Crane (public domain, 2930 vertices) in a generated 120-vertex cage',
    // A literal URL, so that Vite copies the file into the build (assets/) and points here.
    load: async (/** @type {SolverModule} */ solver) => readMesh(solver, await shippedFile(new URL('./data/spot.obj', import.meta.url)), 'spot.obj'),
    cageVertices: 120,
    // Hooves fixed, the head and horns moving (y is up).
    defaultHandles: { axis: 1, fixedBelow: 0.05, movingAbove: 0.8 },
    // Spot faces -z: seen from the front and a little from its left and above (the app's default looks along -z).
    defaultView: { direction: [0.35, -0.4, 1] },
  },
}));

// Every built-in example's name, the default first (example_names.js, which the page imports instead of this
// module: one list of the generated examples' names, checked against GENERATED_EXAMPLES here).
export { EXAMPLE_NAMES };
if (GENERATED_EXAMPLE_NAMES.join() !== [...GENERATED_EXAMPLES.keys()].join()) {
  throw new Error('example_names.js: GENERATED_EXAMPLE_NAMES must name the examples of GENERATED_EXAMPLES');
}

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
 * @param {SolverModule} solver the module from loadSolver()
 * @param {string} name one of EXAMPLE_NAMES
 * @param {{ onProgress?: (fraction: number) => (boolean|void) }} [options]
 * @returns {Promise<{ name: string, description: string, mesh: MeshData, cage: MeshData, cageInfo?: CageResult,
 *   defaultHandles?: ExampleHandles, defaultView?: { direction: number[] } }>}
 *   cageInfo: generateCage's statistics when the cage was generated; defaultView: { direction } to look along.
 */
export async function loadExample(solver, name, { onProgress } = {}) {
  const generated = GENERATED_EXAMPLES.get(name);
  if (!generated && !PROCEDURAL_EXAMPLES.includes(name)) {
    // The core knows only its procedural shapes: name every example here, the loaded ones too.
    throw new InputError(`unknown example ${describeValue(name)} (built-in examples: ${EXAMPLE_NAMES.join(', ')})`);
  }
  if (!generated) return makeExample(solver, name);
  const mesh = await generated.load(solver);
  const cage = generateCage(solver, mesh, { vertices: generated.cageVertices, onProgress });
  return { name, description: generated.description, mesh, cage, cageInfo: cage, defaultHandles: generated.defaultHandles,
    defaultView: generated.defaultView };
}
