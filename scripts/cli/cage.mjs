// `cage <mesh> --vertices K --out cage.obj [--offset d] [--resolution N]`: a generated cage around a mesh
// (docs/cage.md).
import { basename } from 'node:path';
import { CAGE_LIMITS, SolverError, generateCage, writeFileBytes, writeModel } from 'subspace-deform';
import {
  UsageError, checkOutputs, loadCommandSolver, numberFlag, outputFormat, parseArgs, readModelFile,
} from '../lib/cli_support.mjs';
import { checkOutputPaths } from '../lib/output_paths.mjs';
import { duration } from '../lib/timer.mjs';

const HELP = `usage: node scripts/deform.mjs cage <mesh> --vertices K --out cage.obj [--offset d] [--resolution N]

Generates a cage around a triangle mesh (OBJ, OFF, PLY, STL, .glb or .gltf; split vertices are welded, and an
open mesh is enclosed with its holes capped): a voxel-dilated surface at distance >= d outside the mesh,
decimated by progressive hulls (Sander et al. 2000) to K vertices, then checked (closed, manifold, outward,
no self-intersection, no contact with the mesh, every mesh vertex inside). Prints the vertex count, the
cage/mesh volume ratio, the clearance and the time; progress goes to stderr every 10%.
  --vertices K     target vertex count, 4..20000 (the result has K, or at most 20% more); tested for 20..1000
  --out FILE       the cage, OBJ (.obj) or binary glTF (.glb) (required)
  --offset d       clearance in mesh units (default 0.5% of the bounding-box diagonal; at most the diagonal)
  --resolution N   voxels along the longest side, 8..512 (default from K; higher is tighter and slower; the
                   grid holds at most 64M voxels: near 512 only a long, thin mesh fits, a cube up to about 385)
  --threads N      solver threads (default: every core, or SD_THREADS)
Exit status: 0 written, 1 failure (invalid mesh, no valid cage), 2 bad usage.`;

// Prints "cage: 10%" ... "cage: 90%" to stderr as the generator reports progress, so a long run is visibly alive.
function progressPrinter() {
  let shown = 0;
  return (fraction) => {
    const tenth = Math.floor(10 * fraction);
    if (tenth > shown && tenth < 10) {
      shown = tenth;
      process.stderr.write(`cage: ${10 * tenth}%\n`);
    }
    return true;
  };
}

/**
 * A voxel grid over the memory budget says to use "a larger voxel size or a smaller offset" (the core's terms);
 * here the voxel size is set by --resolution, so the message names the flags that shrink the grid.
 * @param {unknown} error @param {{ resolution?: number }} options @returns {unknown}
 */
function withFlagAdvice(error, { resolution }) {
  if (!(error instanceof SolverError) || error.code !== 'memory_budget') return error;
  const now = resolution === undefined ? 'than the automatic one' : `than ${resolution}`;
  return new SolverError(`${error.message} (here: a lower --resolution ${now}, or a smaller --offset)`, { code: error.code, cause: error });
}

export async function cageCommand(argv) {
  const { positionals, flags } = parseArgs(argv, {
    help: 'boolean', vertices: 'string', out: 'string', offset: 'string', resolution: 'string', threads: 'string',
  });
  if (flags.help) {
    console.log(HELP);
    return 0;
  }
  if (positionals.length !== 1) throw new UsageError(`cage takes one mesh\n\n${HELP}`);
  if (!flags.out) throw new UsageError(`cage needs --out cage.obj\n\n${HELP}`);
  if (flags.vertices === undefined) throw new UsageError(`cage needs --vertices K\n\n${HELP}`);
  const options = { vertices: numberFlag(flags.vertices, '--vertices', { integer: true, ...CAGE_LIMITS.vertices }) };
  // The offset's upper limit depends on the mesh (its diagonal): the generator refuses a larger one (exit 1).
  if (flags.offset !== undefined) options.offset = numberFlag(flags.offset, '--offset', { min: 0, minOpen: true });
  if (flags.resolution !== undefined) {
    options.resolution = numberFlag(flags.resolution, '--resolution', { integer: true, ...CAGE_LIMITS.resolution });
  }
  checkOutputs(flags, ['out']);
  outputFormat(flags.out, '--out');
  checkOutputPaths({ '--out': flags.out }, { 'the mesh': positionals[0] });
  const solver = await loadCommandSolver(flags);
  const meshPath = positionals[0];
  const { mesh } = await readModelFile(solver, meshPath);
  let cage;
  try {
    cage = generateCage(solver, mesh, { ...options, onProgress: progressPrinter() });
  } catch (error) {
    throw withFlagAdvice(error, options);
  }
  const comment = `cage of ${basename(meshPath)}: ${cage.positions.length / 3} vertices, offset ${cage.offset.toPrecision(4)}, ` +
    `volume ratio ${cage.volumeRatio.toFixed(3)} (subspace-deform cage generation)`;
  writeFileBytes(flags.out, await writeModel(solver, { mesh: cage }, cage.positions, flags.out, { comment }));
  console.log(`cage: ${cage.positions.length / 3} vertices, ${cage.indices.length / 3} triangles -> ${flags.out}`);
  console.log(`volume ratio ${cage.volumeRatio.toFixed(3)} (voxel surface ${cage.startVolumeRatio.toFixed(3)}), ` +
    `clearance ${cage.minClearance.toPrecision(4)} (offset ${cage.offset.toPrecision(4)}), ` +
    `${cage.attempts} attempt(s), ${duration(cage.ms)}`);
  return 0;
}
