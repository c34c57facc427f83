// What the app asks a worker to bind (the `subspace` of its load requests, web/lib/worker/protocol.js): from
// the settings, the spectral basis with its modes or the cage with the settings' coordinates and that type's
// resolution; a view of "compare coordinates" (methods.js: key 'subspace:<coordinates>') always binds the cage
// with its own coordinates.

/**
 * @param {{ basis: string, spectralModes: number, coordinates: string, pmvcResolution: number,
 *           harmonicResolution: number }} settings the app's settings (settings.js)
 * @param {string|null} [viewCoordinates] the view's own coordinates, or null
 * @returns {import('../../lib/worker/protocol.js').Subspace}
 */
export function subspaceChoice({ basis, spectralModes, coordinates, pmvcResolution, harmonicResolution }, viewCoordinates = null) {
  if (basis === 'spectral' && !viewCoordinates) return { basis, modes: spectralModes };
  const type = viewCoordinates ?? coordinates;
  const subspace = { basis: 'cage', coordinates: type };
  if (type === 'pmvc') subspace.pmvcResolution = pmvcResolution;
  if (type === 'harmonic' && harmonicResolution) subspace.harmonicResolution = harmonicResolution; // 0: chosen
  return subspace;
}
