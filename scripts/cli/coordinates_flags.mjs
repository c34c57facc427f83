// The --coordinates and --resolution flags of `weights` and `deform`: which cage coordinates to bind and the
// resolution of that type (web/lib/coordinates.js), over what a scene says.
import { COORDINATES } from 'subspace-deform';
import { UsageError, numberFlag } from '../lib/cli_support.mjs';

export const COORDINATES_HELP = `  --coordinates mvc|pmvc|harmonic
                                the cage's coordinates: mean value (default; negative where the cage is
                                concave), positive mean value, or harmonic (docs/method.md 18, 19)
  --resolution N                pmvc: the hidden parts' sampling (a cube map of N^2 pixels per face, ${COORDINATES.pmvcResolution.min}-${COORDINATES.pmvcResolution.max},
                                default ${COORDINATES.pmvcResolution.default}); harmonic: grid cells along the cage box's longest side
                                (${COORDINATES.harmonicResolution.min}-${COORDINATES.harmonicResolution.max}; default: chosen from the cage)`;

export const COORDINATES_FLAGS = { coordinates: 'string', resolution: 'string' };

/**
 * The coordinates choice of the flags over `base` (a scene's, already checked, or nothing): --coordinates
 * replaces the type (and drops a resolution of another type), --resolution sets the chosen type's.
 * @param {{ coordinates?: string, resolution?: string }} flags
 * @param {import('subspace-deform').CoordinatesChoice} [base]
 * @returns {import('subspace-deform').CoordinatesChoice}
 */
export function coordinatesChoice(flags, base = {}) {
  let choice = { ...base };
  if (flags.coordinates !== undefined) {
    if (!COORDINATES.types.includes(flags.coordinates)) {
      throw new UsageError(`--coordinates must be ${COORDINATES.types.join(', ')} (got '${flags.coordinates}')`);
    }
    if (flags.coordinates !== base.coordinates) choice = { coordinates: flags.coordinates };
  }
  if (flags.resolution !== undefined) {
    const type = choice.coordinates ?? COORDINATES.types[0];
    const limits = { pmvc: COORDINATES.pmvcResolution, harmonic: COORDINATES.harmonicResolution }[type];
    if (!limits) throw new UsageError('--resolution is for --coordinates pmvc or harmonic');
    const n = numberFlag(flags.resolution, `--resolution (${type})`, { integer: true, min: limits.min, max: limits.max });
    choice[type === 'pmvc' ? 'pmvcResolution' : 'harmonicResolution'] = n;
  }
  return choice;
}
