// What the app asks a worker to bind (the `subspace` of its load requests, web/lib/worker/protocol.js): from
// the settings, the spectral basis with its modes or the cage with the settings' coordinates and that type's
// resolution; a view of "compare coordinates" (methods.js: key 'subspace:<coordinates>') always binds the cage
// with its own coordinates. And the other way: the settings a scene's subspace sets, applied for one binding and
// taken back if it fails (withSettings), and those a setCoordinates call binds with (given to the binding as values).
import { SPECTRAL_MODES_RANGE, checkSettings } from '../settings.js';

/**
 * @param {{ basis: string, spectralModes: number, coordinates: string, pmvcResolution: number,
 *           harmonicResolution: number }} settings the app's settings (settings.js)
 * @param {string|null} [viewCoordinates] the view's own coordinates, or null
 * @returns {import('../../lib/subspace.js').Subspace}
 */
export function subspaceChoice({ basis, spectralModes, coordinates, pmvcResolution, harmonicResolution }, viewCoordinates = null) {
  if (basis === 'spectral' && !viewCoordinates) return { basis, modes: spectralModes };
  const type = viewCoordinates ?? coordinates;
  const subspace = { basis: 'cage', coordinates: type };
  if (type === 'pmvc') subspace.pmvcResolution = pmvcResolution;
  if (type === 'harmonic' && harmonicResolution) subspace.harmonicResolution = harmonicResolution; // 0: chosen
  return subspace;
}

/**
 * The settings a scene's `subspace` (lib/scene.js) names: its basis, the spectral modes, or the cage's
 * coordinates (none: mean value) with a resolution if the scene gives one.
 */
export function sceneSubspaceSettings({ basis, modes, coordinates = 'mvc', ...resolution }) {
  return { basis, ...(modes ? { spectralModes: Math.min(modes, SPECTRAL_MODES_RANGE.max) } : {}),
    ...(basis === 'cage' ? { coordinates, ...resolution } : {}) };
}

/**
 * What the page should tell about a scene's `subspace` it cannot take as it is: more spectral modes than the app
 * binds (the library and the CLI take any number up to the vertex count - 5). Null when it is taken as it is.
 */
export function sceneSubspaceNote({ modes } = {}) {
  if (!(modes > SPECTRAL_MODES_RANGE.max)) return null;
  return `The scene asks for ${modes} spectral modes; the app binds at most ${SPECTRAL_MODES_RANGE.max}, so it uses ` +
    `${SPECTRAL_MODES_RANGE.max} (the command-line tool and the library take more).`;
}

/**
 * The settings of setCoordinates(coordinates, resolution): the cage basis, the type, its resolution if given;
 * checked as setOptions checks them (an InputError before anything is bound).
 */
export function coordinatesSettings(coordinates, resolution) {
  const change = { basis: 'cage', coordinates };
  if (resolution !== undefined && coordinates !== 'mvc') change[`${coordinates}Resolution`] = resolution;
  return checkSettings(change, 'setOptions');
}

/**
 * Applies `change` to the settings (AppSettings) and runs `bind`; if it fails, the settings it changed go back
 * (the model stays as it was bound).
 */
export async function withSettings(settings, change, bind) {
  const old = Object.fromEntries(Object.keys(change).map((key) => [key, settings.values[key]]));
  settings.update(change);
  try {
    return await bind();
  } catch (error) {
    settings.update(old);
    throw error;
  }
}
