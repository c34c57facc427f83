// `check <mesh> [cage]`: validates a mesh, and a cage around it, with the same checks the app and the
// solver use. Exit 0 and a summary when valid; exit 1 and every finding when not.
import { Deformer, checkMesh, checkPair } from 'subspace-deform';
import { UsageError, loadCommandSolver, memoryBudgetFlag, parseArgs, readModelFile } from '../lib/cli_support.mjs';
import { duration } from '../lib/timer.mjs';
import { unusedOutside, unusedOutsideText } from './unused_outside.mjs';
import { withCageSeamAdvice } from './cage_seams.mjs';

const HELP = `usage: node scripts/deform.mjs check <mesh> [cage] [--quality [--memory-budget MB]] [--json] [--threads N]

Validates a triangle mesh (OBJ, OFF, PLY, STL, .glb or .gltf) as the deformer takes it: vertices split at
seams are welded, vertices no face uses are carried along, non-manifold vertices are split; then it must be
manifold, consistently and outward oriented, with finite coordinates and no degenerate or duplicate faces.
Open meshes are accepted (each hole is capped for the volume); notes say what was welded, split or capped.
A closed mesh whose faces cross each other is valid with a warning, mesh_self_intersecting (how many pairs
of faces, up to 100 counted, and the first ones).
With a cage, also checks the cage (closed, as given) and that every mesh vertex is strictly inside it; a
vertex no face uses is carried along and may lie outside, with a warning, unused_outside_cage, as weights
refuses it (W has a row for every vertex of the file; judged with mean value coordinates, weights' default).
  --quality     with a valid cage (a usage error without one), also bind the weights and report the cage's
                quality (weak cage vertices, influence ratio, volume ratio; docs/cage.md) with a warning per
                poor number;
                a W too large to bind leaves the pair valid with a warning, cage_quality_skipped
  --memory-budget MB
                with --quality: refuse to bind a larger W (default 1073.7 MB; W cannot pass 2146 MB)
  --json        print the report as JSON
  --threads N   solver threads (default: every core, or SD_THREADS)
Exit status: 0 valid, 1 invalid (every finding is printed), 2 bad usage.`;

export async function checkCommand(argv) {
  const { positionals, flags } = parseArgs(argv, {
    help: 'boolean', json: 'boolean', quality: 'boolean', threads: 'string', 'memory-budget': 'string',
  });
  if (flags.help) {
    console.log(HELP);
    return 0;
  }
  if (positionals.length < 1 || positionals.length > 2) throw new UsageError(`check takes a mesh and an optional cage\n\n${HELP}`);
  const memoryBudgetMB = memoryBudgetFlag(flags);
  if (memoryBudgetMB !== undefined && !flags.quality) throw new UsageError('--memory-budget is for --quality (only it binds W)');
  // Without a cage there is nothing to judge: --quality was silently ignored.
  if (flags.quality && positionals.length < 2) throw new UsageError('--quality needs a cage: check <mesh> <cage> --quality');
  const solver = await loadCommandSolver(flags);
  const [meshPath, cagePath] = positionals;
  const { mesh, gltf } = await readModelFile(solver, meshPath);
  const cageModel = cagePath ? await readModelFile(solver, cagePath) : null;
  const cage = cageModel?.mesh ?? null;
  const report = cage ? checkPair(solver, mesh, cage) : checkMesh(solver, mesh);
  if (cage) report.findings = withCageSeamAdvice(cage, report.findings);
  report.findings.push(...selfIntersectionWarnings(solver, mesh), ...(gltf?.warnings ?? []), ...(cageModel?.gltf?.warnings ?? []));
  if (cage && report.ok) report.findings.push(...unusedOutsideWarnings(solver, mesh, cage));
  if (flags.quality && cage && report.ok) {
    const quality = cageQuality(solver, mesh, cage, memoryBudgetMB);
    if (quality.skipped) report.findings.push(quality.skipped);
    else report.cageQuality = quality;
  }
  if (flags.json) console.log(JSON.stringify(report, null, 2));
  else printReport(meshPath, cagePath, report);
  return report.ok ? 0 : 1;
}

// A tetrahedron far smaller than any model: the mesh that the model is checked around as if it were a cage.
const PROBE = { positions: new Float64Array([0, 0, 0, 1e-6, 0, 0, 0, 1e-6, 0, 0, 0, 1e-6]),
  indices: new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]) };

/**
 * The mesh's faces that cross each other (handbones: 43 pairs, cow: at least 100), as a warning: the solver
 * accepts such a mesh, but its volume counts the overlaps by their winding and a cage cannot wrap the parts
 * apart. The wasm module tests self-intersection only for a cage (checkPair's self_intersecting, counting up
 * to 100 pairs), so the mesh, its seams welded, is checked as the cage of a tiny tetrahedron and that one
 * finding kept. A mesh the cage rules refuse (open, non-manifold, ...) is not tested.
 */
function selfIntersectionWarnings(solver, mesh) {
  const { welded, fileFace } = weldedAtSamePoints(mesh);
  const crossing = checkPair(solver, PROBE, welded).findings.find((f) => f.code === 'self_intersecting');
  const pairs = crossing?.message.match(/^cage: ((at least )?\d+ pairs? of faces intersect \(first: [^)]*\))/);
  if (!pairs) return [];
  const inFile = pairs[1].replace(/faces (\d+) and (\d+)/g, (_, f, g) => `faces ${fileFace[f]} and ${fileFace[g]}`);
  return [{ severity: 'warning', code: 'mesh_self_intersecting',
    message: `mesh: ${inFile}: the surface crosses itself, so its volume counts the overlaps by their winding` }];
}

/**
 * The mesh with the vertices at one point made one (a glTF's seams) and the faces that leaves without area
 * (a capsule's poles) left out, as the solver's layout does; fileFace: each face's number in the file.
 */
function weldedAtSamePoints(mesh) {
  const first = new Map();
  const index = new Uint32Array(mesh.positions.length / 3);
  for (let v = 0; v < index.length; ++v) {
    const key = `${mesh.positions[3 * v]} ${mesh.positions[3 * v + 1]} ${mesh.positions[3 * v + 2]}`;
    if (!first.has(key)) first.set(key, v);
    index[v] = first.get(key);
  }
  const indices = [], fileFace = [];
  for (let f = 0; f < mesh.indices.length / 3; ++f) {
    const [a, b, c] = [0, 1, 2].map((k) => index[mesh.indices[3 * f + k]]);
    if (a === b || b === c || c === a) continue;
    indices.push(a, b, c);
    fileFace.push(f);
  }
  return { welded: { positions: mesh.positions, indices: Uint32Array.from(indices) }, fileFace };
}

/**
 * Vertices no face uses outside the cage, as a warning: deform carries them along (the pair is valid), but
 * weights gives them rows of W and refuses them (unused_outside.mjs).
 */
function unusedOutsideWarnings(solver, mesh, cage) {
  const found = unusedOutside(solver, mesh, cage);
  if (!found) return [];
  return [{ severity: 'warning', code: 'unused_outside_cage', message: `mesh: ${unusedOutsideText(found)}: deform carries ` +
    'such vertices along with their nearest triangles, but weights (with mean value coordinates, its default) refuses ' +
    'the pair (W has a row for every vertex of the file, and cage coordinates exist only strictly inside the cage)' }];
}

/**
 * The cage quality from a fresh binding of W (Deformer.cageQuality); { skipped: a warning saying why } when W is
 * over the memory budget or cannot be allocated: the pair's validity does not depend on it, so it is kept.
 */
function cageQuality(solver, mesh, cage, memoryBudgetMB) {
  let deformer;
  try {
    deformer = Deformer.create(solver, mesh, cage, { memoryBudgetMB });
  } catch (error) {
    if (!['memory_budget', 'out_of_memory'].includes(error?.code)) throw error;
    const message = error.message.replace(/raise the budget$/, 'raise the budget (--memory-budget MB)');
    return { skipped: { severity: 'warning', code: 'cage_quality_skipped', message: `cage quality not computed: ${message}` } };
  }
  try {
    return { ...deformer.cageQuality(), bindMs: deformer.bindMs };
  } finally {
    deformer.dispose();
  }
}

function printQuality(q) {
  const influence = Number.isNaN(q.influenceRatio) ? 'not computed (over 400 cage vertices)' : q.influenceRatio.toExponential(2);
  console.log(`  cage quality: ${q.weakVertices} of ${q.cageVertices} cage vertices weak (smallest largest weight ` +
    `${q.minColumnMax.toExponential(2)}), influence ratio ${influence}, volume ratio ${q.volumeRatio.toFixed(2)} ` +
    `(${duration(q.ms)}, ${q.sampledRows} rows of W)`);
  q.warnings.forEach((warning, k) => console.log(`  warning (${q.warningCodes[k]}): poor cage: ${warning}`));
}

function printReport(meshPath, cagePath, report) {
  const s = report.summary;
  const fmt = (v) => v.map((x) => Number(x).toPrecision(6)).join(', ');
  console.log(`${meshPath}${cagePath ? ` in cage ${cagePath}` : ''}`);
  console.log(`  vertices ${s.vertices}, faces ${s.faces}, edges ${s.edges}, components ${s.components}, genus ${s.genus < 0 ? 'n/a' : s.genus}`);
  console.log(`  bounding box (${fmt(s.bboxMin)}) to (${fmt(s.bboxMax)}), volume ${Number(s.volume).toPrecision(8)}` +
    `${s.holes ? ` (${s.holes} ${s.holes === 1 ? 'hole' : 'holes'} capped)` : ''}`);
  const l = s.layout;
  if (l.solverVertices !== l.fileVertices || l.solverFaces !== l.fileFaces) {
    console.log(`  for the solver: ${l.solverVertices} vertices, ${l.solverFaces} faces (welded ${l.welded}, ` +
      `unreferenced ${l.unreferenced}, collapsed faces ${l.collapsedFaces}, split ${l.splitVertices})`);
  }
  for (const severity of ['error', 'warning', 'note']) {
    for (const f of report.findings) if (f.severity === severity) console.log(`  ${severity} (${f.code}): ${f.message}`);
  }
  if (report.cageQuality) printQuality(report.cageQuality);
  console.log(report.ok ? 'valid' : 'INVALID');
}
