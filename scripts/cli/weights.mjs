// `weights <mesh> <cage> --out W.npy [--float32] [--coordinates mvc|pmvc|harmonic]`: the cage coordinates W
// (n x m) of the mesh's vertices with respect to the cage, written as a NumPy .npy file (v1.0, C order, '<f8'
// or '<f4').
import { computeWeights, writeFileBytes } from 'subspace-deform';
import { UsageError, checkOutputs, loadCommandSolver, memoryBudgetFlag, parseArgs, readModelFile } from '../lib/cli_support.mjs';
import { duration } from '../lib/timer.mjs';
import { COORDINATES_FLAGS, COORDINATES_HELP, coordinatesChoice } from './coordinates_flags.mjs';
import { checkOutputPaths } from '../lib/output_paths.mjs';
import { requireValidPair } from './valid_pair.mjs';

const HELP = `usage: node scripts/deform.mjs weights <mesh> <cage> --out W.npy [--float32] [--memory-budget MB]
                                    [--coordinates mvc|pmvc|harmonic] [--resolution N]

Computes the cage coordinates of every mesh vertex with respect to the cage: 3D mean value coordinates
(Ju, Schaefer, Warren 2005; the default), positive mean value coordinates (Lipman et al. 2007) or harmonic
coordinates (Joshi et al. 2007). W is n x m (mesh vertices x cage vertices) and rows sum to 1; mean value
coordinates also reproduce the mesh, W * cage = mesh. Writes W as a NumPy .npy array (C order) and prints
n, m, the size, the minimum weight and the bind time (and the rays cast, or the harmonic grid). Mesh and cage
may be OBJ, OFF, PLY, STL, .glb or .gltf; W has one row per vertex of the mesh file as it is (seam copies too).
  --out FILE           output .npy file (required)
  --float32            store single precision ('<f4', half the size); default double ('<f8')
  --memory-budget MB   refuse when W (harmonic: with its grid and factor) would be larger (default 1073.7 MB;
                       W cannot pass 2146 MB whatever the budget: docs/mvc.md#memory)
${COORDINATES_HELP}
  --threads N          solver threads (default: every core, or SD_THREADS)
The mesh and the cage are checked first, as \`check\` checks them (a closed, outward cage with every mesh
vertex strictly inside): W of an invalid pair would not reproduce the mesh. W also has rows for the vertices
no face uses, which check and deform carry along: one of them outside the cage is refused by name.
Exit status: 0 written, 1 invalid pair (every error is printed) or failure, 2 bad usage.`;

export async function weightsCommand(argv) {
  const { positionals, flags } = parseArgs(argv, {
    help: 'boolean', out: 'string', float32: 'boolean', 'memory-budget': 'string', threads: 'string', ...COORDINATES_FLAGS,
  });
  if (flags.help) {
    console.log(HELP);
    return 0;
  }
  if (positionals.length !== 2) throw new UsageError(`weights takes a mesh and a cage\n\n${HELP}`);
  if (!flags.out) throw new UsageError(`weights needs --out W.npy\n\n${HELP}`);
  const memoryBudgetMB = memoryBudgetFlag(flags);
  const choice = coordinatesChoice(flags);
  checkOutputs(flags, ['out']);
  if (!/\.npy$/i.test(flags.out)) throw new UsageError(`--out must name a .npy file (got '${flags.out}')`);
  checkOutputPaths({ '--out': flags.out }, { 'the mesh': positionals[0], 'the cage': positionals[1] });
  const solver = await loadCommandSolver(flags);
  const [meshPath, cagePath] = positionals;
  const { mesh } = await readModelFile(solver, meshPath);
  const cage = (await readModelFile(solver, cagePath)).mesh;  // any format, a glTF cage too (as deform and check read it)
  requireValidPair(solver, { mesh, name: meshPath }, { mesh: cage, name: cagePath }, choice);
  const result = computeWeights(solver, mesh, cage, { float32: !!flags.float32, memoryBudgetMB, ...choice });
  writeFileBytes(flags.out, npyBytes(result.weights, result.rows, result.cols));
  console.log(`W (${result.coordinates}): ${result.rows} x ${result.cols} (${flags.float32 ? 'float32' : 'float64'}, ${(result.bytes / 1e6).toFixed(2)} MB) -> ${flags.out}`);
  console.log(`min weight ${result.minWeight.toPrecision(6)} (row ${result.minWeightRow}, column ${result.minWeightCol}); ` +
    `bind ${duration(result.bindMs)}${bindDetails(result)}`);
  return 0;
}

// What the binding's time went into, per coordinate type.
function bindDetails(r) {
  if (r.coordinates === 'pmvc') return ` (${(r.rays / r.rows).toFixed(0)} rays per vertex into the hidden parts, behind ${(r.hiddenFaces / r.rows).toFixed(1)} back-facing triangles)`;
  if (r.coordinates === 'harmonic') {
    return ` (resolution ${r.resolution}: ${r.grid.join(' x ')} grid, ${r.unknowns} nodes inside, factor ${(r.factorNonzeros / 1e6).toFixed(2)} M entries ` +
      `in ${duration(r.factorMs)}, solves ${duration(r.solveMs)}; ${r.boundaryCells} vertices in cells next to the cage)`;
  }
  return ` (${(r.evaluations / r.bindMs / 1e3).toFixed(1)} M point-triangle evaluations/s)`;
}

/**
 * A NumPy .npy v1.0 file: magic, header length, a Python-dict header padded with spaces to a multiple of
 * 64 bytes (ending in '\n'), then the raw little-endian data in C order.
 * @param {Float64Array|Float32Array} data rows * cols values, row-major
 */
export function npyBytes(data, rows, cols) {
  const descr = data instanceof Float32Array ? '<f4' : '<f8';
  let header = `{'descr': '${descr}', 'fortran_order': False, 'shape': (${rows}, ${cols}), }`;
  const unpadded = 10 + header.length + 1;  // magic (6) + version (2) + length (2) + header + '\n'
  header += ' '.repeat((64 - (unpadded % 64)) % 64) + '\n';
  const bytes = new Uint8Array(10 + header.length + data.byteLength);
  bytes.set([0x93, ...Buffer.from('NUMPY'), 1, 0]);
  new DataView(bytes.buffer).setUint16(8, header.length, true);
  bytes.set(Buffer.from(header, 'latin1'), 10);
  // Typed arrays are in the platform's byte order; every platform Node runs on is little-endian.
  bytes.set(new Uint8Array(data.buffer, data.byteOffset, data.byteLength), 10 + header.length);
  return bytes;
}
