// @ts-check
// The built-in examples' names without their loaders (examples.js): a page checks ?example= or an embed's
// example attribute with them on the main thread, while only the solver worker loads an example. Importing
// examples.js there instead put its import('bunny') in the page's bundle too: the build held the bunny twice.
import { PROCEDURAL_EXAMPLES } from '../../build/wasm/solver_schema.js';

/** The examples whose mesh comes from elsewhere and whose cage is generated on load (examples.js loads them). */
export const GENERATED_EXAMPLE_NAMES = Object.freeze(['bunny', 'spot']);

/**
 * Every built-in example's name, the default first: known without a loaded module (the procedural ones come
 * from the generated schema), so a page can check a name before its worker has started.
 */
export const EXAMPLE_NAMES = Object.freeze([...PROCEDURAL_EXAMPLES, ...GENERATED_EXAMPLE_NAMES]);
