// The scene a user saves (docs/scene-format.md): what the model came from, the handles, the solver options, the
// volume parts and the skeleton, so that loading it (the app or the CLI) gives the same state.
import { isSpectral } from '../../lib/subspace.js';
import { METHODS } from '../../lib/options.js';

/**
 * @param {object|null} model the bound model with its `source` ({ example } or { files, generateCage? }), its
 *   basis ('cage' | 'spectral', basisSize) and the `subspace` it was bound with (the cage's coordinates)
 * @param {object[]} handles the handle groups in scene form (HandleSet.toScene)
 * @param {object} solver the scene's "solver" (AppSettings.toScene)
 * @param {object|null} [volumeParts] the parts description the solvers keep (web/lib/parts.js), or null
 * @param {{ joints: number[][], bones: number[][] }|null} [skeleton] the bones the solvers keep, or null
 * @param {string[]|null} [compared] in compare mode the views' keys, or null: the methods compared are the scene's
 *   "view" (its solver's method stays the panel's, the one of a single view), so that loading it shows them again
 */
export function savedScene(model, handles, solver, volumeParts = null, skeleton = null, compared = null) {
  const scene = {};
  const source = model?.source ?? {};
  if (source.files) {
    scene.mesh = source.files[0];
    if (source.files[1]) scene.cage = source.files[1];
  } else {
    scene.example = model?.name;
  }
  // An app extension of the scene format: regenerate the cage on load (the cage file was never saved).
  if (source.generateCage) scene.generateCage = { vertices: source.generateCage.vertices };
  scene.handles = handles;
  scene.solver = solver;
  if (isSpectral(model)) scene.subspace = { basis: 'spectral', modes: model.basisSize - 4 };
  // Other coordinates than the default mean value ones, with the resolution they were bound at.
  const { coordinates, pmvcResolution, harmonicResolution } = model?.subspace ?? {};
  if (model?.basis === 'cage' && coordinates && coordinates !== 'mvc') {
    scene.subspace = { basis: 'cage', coordinates, ...(pmvcResolution ? { pmvcResolution } : {}),
      ...(harmonicResolution ? { harmonicResolution } : {}) };
  }
  if (volumeParts) scene.volumeParts = volumeParts;
  if (skeleton) scene.skeleton = skeleton;
  // "compare coordinates" (keys 'subspace:<coordinates>') has no place in a scene: it is the cage's coordinates' choice.
  if (compared?.every((key) => METHODS.includes(key))) scene.view = { compare: [...compared] };
  return scene;
}

// A JSON string (kept as it is: a description's "[1,2]" is the user's text), or an array of numbers.
const STRING_OR_NUMBERS = /"(?:[^"\\]|\\.)*"|\[\s*(-?[\d.eE+-]+(?:,\s*-?[\d.eE+-]+)*)\s*\]/g;

/**
 * A scene as JSON text for people and diffs: indented, but every array of numbers (vertex lists, vectors) on
 * one line, instead of JSON.stringify's one number per line. Strings are left as they are.
 * @param {object} scene
 */
export function sceneText(scene) {
  return JSON.stringify(scene, null, 2).replace(STRING_OR_NUMBERS,
    (match, numbers) => (numbers === undefined ? match : `[${numbers.split(/,\s*/).join(', ')}]`));
}
