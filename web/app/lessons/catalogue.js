// The built-in lessons: the report's experiments as scene files (docs/scene-format.md) that the app loads by
// name: `?lesson=arap-vs-subspace`, `<subspace-deformer lesson="...">`, `app.loadLesson(id)`, the panel. Each
// file is a scene with a title ("name"), a caption of two or three sentences ("description"), the model, its
// handles already moved, solver options and what the app shows ("view": the methods side by side, the camera
// direction, whether the solver starts paused). scripts/lessons.mjs writes them from geometric queries on the
// models, and tests/js/lessons.test.js checks that they are up to date and that what each caption says holds.
import { InputError } from '../../lib/errors.js';

/** Each lesson's scene file, loaded on demand (its own chunk). */
const LESSON_FILES = new Map([
  ['subspace-vs-full', () => import('./subspace-vs-full.json')],
  ['arap-vs-subspace', () => import('./arap-vs-subspace.json')],
  ['volume', () => import('./volume.json')],
  ['spectral', () => import('./spectral.json')],
  ['volume-parts', () => import('./volume-parts.json')],
  ['skeleton', () => import('./skeleton.json')],
]);

/** The lessons' names, in the order of the report. */
export const LESSON_IDS = Object.freeze([...LESSON_FILES.keys()]);

/**
 * A lesson's scene (the object of its JSON file, for parseScene).
 * @param {string} id
 * @returns {Promise<object>}
 */
export async function lessonScene(id) {
  const load = typeof id === 'string' ? LESSON_FILES.get(id) : undefined;
  if (!load) throw new InputError(`lesson must be one of ${LESSON_IDS.join(', ')} (got ${JSON.stringify(id) ?? String(id)})`);
  return structuredClone((await load()).default);
}
