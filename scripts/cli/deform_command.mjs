// `deform <scene.json>`: solves a scene file (docs/scene-format.md) with the same wasm solver as the app and
// writes the deformed mesh, the deformed cage and a convergence report.
import { basename, dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import {
  BASES, InputError, Deformer, JACOBIANS, MAX_VOLUME_PARTS, METHODS, describeValue, generateCage, handleLineWarnings,
  handleTargets, loadExample, optionAllows, optionSchema, parseScene, skeletonWarnings, volumeParts, writeFileBytes,
  writeModel,
} from 'subspace-deform';
import {
  UsageError, checkOutputs, loadCommandSolver, memoryBudgetFlag, numberFlag, outputFormat, parseArgs, readInputFile,
  readModelFile,
} from '../lib/cli_support.mjs';
import { COORDINATES_FLAGS, COORDINATES_HELP, coordinatesChoice } from './coordinates_flags.mjs';
import { solveInterruptibly } from './interruptible_solve.mjs';
import { cageSeamError } from './cage_seams.mjs';
import { checkOutputPaths } from '../lib/output_paths.mjs';
import { Timer, duration } from '../lib/timer.mjs';

const HELP = `usage: node scripts/deform.mjs deform <scene.json> [options]

Solves a scene: the mesh (and cage) it names -- or a built-in "example", or a mesh with "generateCage" --
its handle groups moved by their translate/rotate, with the scene's solver options. Command-line options
override the scene.
  --method subspace|full|arap   deformation method (subspace needs a cage or the spectral basis)
  --jacobian exact|fast         Gauss-Newton step: dense reference or matrix-free PCG
  --max-iterations N            iteration cap
  --weighting area|uniform      energy weighted by area (the same shape at every resolution; default) or
                                per vertex as in the original report
  --integration full|reduced    subspace method: the Laplacian term over every vertex (default) or by one
                                rotation per cluster of vertices (an iteration costs about two passes over W),
                                the solve then finishing on every vertex (until a step would move no vertex
                                by 1e-4 of the diagonal); the report gives the clusters, the rule's test
                                error and the full energy
  --basis cage|spectral         the subspace: the cage's coordinates (default) or the mesh's own lowest
                                Laplacian modes (no cage needed; needs --modes unless the scene sets them)
  --modes K                     the spectral basis' number of eigenvectors (it has K + 4 columns)
${COORDINATES_HELP}
  --parts K                     keep the volume of K parts made automatically (spectral clustering)
                                instead of the scene's "volumeParts" or the one global volume
  --float32                     store the weights W (or the spectral basis) in single precision
  --memory-budget MB            refuse to bind a larger W (default 1073.7 MB; W cannot pass 2146 MB)
  --out mesh.obj|mesh.glb       write the deformed mesh in the model's own vertex layout: OBJ, or binary glTF
                                (a glTF model keeps its materials, textures, UVs, nodes and extensions;
                                normals and tangents follow the deformed surface)
  --cage-out cage.obj|cage.glb  write the deformed cage (the rest cage for full/arap and the spectral basis):
                                OBJ or binary glTF; bad usage without a cage file or example cage (a scene's
                                "generateCage" under the spectral basis makes none: that basis ignores a cage)
  --report report.json          write the convergence report: iterations[] (energy, volume, step, ms,
                                ...), volumeRelError, handleMaxError, handleDistances (per group: from
                                its targets, or its lines with "along"/"from"), converged, stop (why it stopped),
                                iterationCount, bindMs, coordinates (the cage's: type, smallest
                                weight, ...); with volume parts (or several components, or an
                                open mesh) partVolumeChange per part; with a scene "skeleton": skeleton
                                (deformed joints; per bone lengthError, straightnessError, lambda); layout
                                (welding); warnings with codes
                                (poor cage, folded triangles, a deformed cage that crosses itself)
  --time-limit S                stop the solve after S seconds (the result so far is written)
  --quiet                       print nothing but errors and no progress
  --threads N                   solver threads (default: every core, or SD_THREADS)
The output paths are checked before anything is computed. A solve running longer than a few seconds prints
its progress to stderr; Ctrl-C stops it and writes the result so far (the report says "cutShort").
Exit status: 0 solved (converged or not, or stopped by --time-limit: see the report), 1 invalid input or
failed run, 2 bad usage, 130 stopped by Ctrl-C (the result so far is written).`;

const FLAGS = {
  help: 'boolean', method: 'string', jacobian: 'string', 'max-iterations': 'string', float32: 'boolean',
  weighting: 'string', integration: 'string',
  out: 'string', 'cage-out': 'string', report: 'string', quiet: 'boolean', threads: 'string', basis: 'string', modes: 'string',
  parts: 'string', 'time-limit': 'string', 'memory-budget': 'string', ...COORDINATES_FLAGS,
};
const OUTPUTS = ['out', 'cage-out', 'report'];
const GENERATE_CAGE_IGNORED = {
  severity: 'warning', code: 'generate_cage_ignored',
  message: 'the spectral basis needs no cage: the scene\'s "generateCage" was ignored (no cage generated)',
};

// The scene's model (any format readModelFile reads) and cage: files relative to the scene, a built-in example,
// or a generated cage. model keeps what writing a glTF back needs. The spectral basis ignores a cage, so none is
// generated for it (that cost seconds, or failed the run when the cage could not be made): cageIgnored says so.
async function sceneModel(solver, scene, base, basis) {
  if (scene.example) {
    const example = await loadExample(solver, scene.example);
    return { model: { mesh: example.mesh }, cage: example.cage };
  }
  const model = await readSceneModel(solver, scene, base, scene.mesh);
  if (scene.generateCage && basis === 'spectral') return { model, cage: null, cageIgnored: true };
  if (scene.generateCage) return { model, cage: generateCage(solver, model.mesh, { vertices: scene.generateCage.vertices }) };
  const cage = scene.cage ? (await readSceneModel(solver, scene, base, scene.cage)).mesh : null;
  return { model, cage };
}

const EXPERIMENTS = fileURLToPath(new URL('../../docs/experiments', import.meta.url));

// The scenes of docs/experiments name real models that are not shipped (docs/experiments/README.md): run in place
// without them, "cannot read .../armadillo.obj: no such file" alone did not say where they come from.
async function readSceneModel(solver, scene, base, file) {
  try {
    return await readModelFile(solver, resolve(base, file));
  } catch (error) {
    if (error?.code !== 'unreadable_file' || !error.message.endsWith('no such file') || resolve(base) !== EXPERIMENTS) throw error;
    const names = [scene.mesh, scene.cage].filter(Boolean);
    const files = names.length > 1 ? `{${names.join(',')}}` : names[0];
    throw new InputError(`${error.message}; the experiments' real models are not shipped: link them beside the scene first: ` +
      `ln -s "$PWD"/../shared/data/${files} docs/experiments/ (docs/experiments/README.md)`, { code: 'unreadable_file', cause: error });
  }
}

export async function deformCommand(argv) {
  const { positionals, flags } = parseArgs(argv, FLAGS);
  if (flags.help) {
    console.log(HELP);
    return 0;
  }
  if (positionals.length !== 1) throw new UsageError(`deform takes exactly one scene file\n\n${HELP}`);
  for (const name of ['out', 'cage-out']) if (flags[name]) outputFormat(flags[name], `--${name}`);
  const options = overrides(flags);
  const memoryBudgetMB = memoryBudgetFlag(flags);
  const timeLimitMs = flags['time-limit'] === undefined ? Infinity
    : 1000 * numberFlag(flags['time-limit'], '--time-limit', { min: 0, minOpen: true });
  checkOutputs(flags, OUTPUTS);
  const solverPromise = loadCommandSolver(flags);
  const scenePath = positionals[0];
  const scene = parseScene(new TextDecoder().decode(readInputFile(scenePath)));
  const subspace = subspaceOverride(scene.subspace, flags);
  const partsSpec = flags.parts !== undefined
    ? { auto: numberFlag(flags.parts, '--parts', { integer: true, min: 1, max: MAX_VOLUME_PARTS }) } : scene.volumeParts;
  const base = dirname(resolve(scenePath));
  checkOutputPaths(Object.fromEntries(OUTPUTS.map((name) => [`--${name}`, flags[name]])), {
    'the scene': scenePath, 'the scene\'s mesh': scene.mesh && resolve(base, scene.mesh), 'the scene\'s cage': scene.cage && resolve(base, scene.cage),
  });
  const solver = await solverPromise;
  const { model, cage, cageIgnored } = await sceneModel(solver, scene, base, subspace.basis);
  const { mesh } = model;
  if (flags['cage-out'] && cageIgnored) throw new UsageError('--cage-out: no cage is generated under the spectral basis (the scene\'s "generateCage" is ignored)');
  if (flags['cage-out'] && !cage) throw new UsageError('--cage-out: the scene has no cage (it names none, and no "generateCage")');
  const { groups, targets, lines } = handleTargets(mesh.positions, scene.handles);
  const parts = partsSpec ? volumeParts(solver, mesh, partsSpec) : null;

  const started = new Timer();
  const deformer = createDeformer(solver, mesh, cage, { float32: !!flags.float32, memoryBudgetMB, ...subspace });
  try {
    const solverOptions = { ...scene.solver, ...options };
    if (!cage && subspace.basis === 'cage' && solverOptions.method === undefined) solverOptions.method = 'full';
    deformer.setOptions(solverOptions);
    if (parts) deformer.setVolumeParts(parts);
    if (scene.skeleton) deformer.setSkeleton(scene.skeleton);
    deformer.setHandles(groups);
    deformer.setTargets(targets);
    if (lines.some(Boolean)) deformer.setHandleLines(lines);
    const { result, cutShort } = await solveInterruptibly(deformer, {
      maxIterations: deformer.options().maxIterations,
      timeLimitMs,
      onProgress: flags.quiet ? undefined : (count, ms) => process.stderr.write(
        `deform: ${count} iterations in ${(ms / 1000).toFixed(0)} s (Ctrl-C stops and writes the result so far)\n`),
    });
    const positions = deformer.positions();
    const report = makeReport(deformer, result, lines, started.ms());
    report.wasmBuild = solver.build;
    report.threads = solver.threads();
    report.cutShort = cutShort;
    report.warnings = [...(model.gltf?.warnings ?? []), ...(cageIgnored ? [GENERATE_CAGE_IGNORED] : []), ...resultWarnings(deformer, !!cage && subspace.basis === 'cage'), ...reducedWarnings(report), ...lineWarnings(report),
      ...boneWarnings(report, subspace.basis)];

    const from = basename(scenePath);
    if (flags.out) {
      const comment = `deformed by subspace-deform from ${from}`;
      writeFileBytes(flags.out, await writeModel(solver, model, positions, flags.out, { solverOfFile: deformer.layout().solverOfFile, comment }));
    }
    if (flags['cage-out']) {
      const positions = deformer.cagePositions();
      const comment = `cage deformed by subspace-deform from ${from}`;
      writeFileBytes(flags['cage-out'], await writeModel(solver, { mesh: { positions, indices: cage.indices } }, positions, flags['cage-out'], { comment }));
    }
    if (flags.report) writeFileBytes(flags.report, `${JSON.stringify(report, null, 2)}\n`);
    if (!flags.quiet) printSummary(scenePath, report);
    return cutShort?.by === 'SIGINT' ? 130 : 0;
  } finally {
    deformer.dispose();
  }
}

// Deformer.create with the advice for a cage split at seams (cage_seams.mjs) when it refuses the cage.
function createDeformer(solver, mesh, cage, options) {
  try {
    return Deformer.create(solver, mesh, cage, options);
  } catch (error) {
    throw cageSeamError(error, cage);
  }
}

// "a, b or c"
function alternatives(list) {
  return `${list.slice(0, -1).join(', ')} or ${list.at(-1)}`;
}

// The scene's subspace with --basis / --modes / --coordinates / --resolution applied: { basis, modes?,
// coordinates?, pmvcResolution?, harmonicResolution? } as Deformer.create takes them.
function subspaceOverride(sceneSubspace, flags) {
  if (flags.basis !== undefined && !BASES.includes(flags.basis)) throw new UsageError(`--basis must be ${alternatives(BASES)} (got '${flags.basis}')`);
  const basis = flags.basis ?? (flags.modes !== undefined ? 'spectral' : sceneSubspace.basis);
  if (basis === 'cage') {
    if (flags.modes !== undefined) throw new UsageError('--modes is for --basis spectral');
    const { coordinates, pmvcResolution, harmonicResolution } = sceneSubspace;
    return { basis, ...coordinatesChoice(flags, { coordinates, pmvcResolution, harmonicResolution }) };
  }
  if (flags.coordinates !== undefined || flags.resolution !== undefined) {
    throw new UsageError('--coordinates and --resolution are for the cage basis');
  }
  const modes = flags.modes !== undefined ? numberFlag(flags.modes, '--modes', { integer: true, min: 1, max: 100000 }) : sceneSubspace.modes;
  if (modes === undefined) throw new UsageError('--basis spectral needs --modes K (or "subspace": { "modes": K } in the scene)');
  return { basis, modes };
}

function overrides(flags) {
  const out = {};
  if (flags.method !== undefined) {
    if (!METHODS.includes(flags.method)) throw new UsageError(`--method must be ${alternatives(METHODS)} (got '${flags.method}')`);
    out.method = flags.method;
  }
  if (flags.jacobian !== undefined) {
    if (!JACOBIANS.includes(flags.jacobian)) throw new UsageError(`--jacobian must be ${alternatives(JACOBIANS)} (got '${flags.jacobian}')`);
    out.jacobian = flags.jacobian;
  }
  for (const name of ['weighting', 'integration']) {
    if (flags[name] === undefined) continue;
    const { choices } = optionSchema(name);
    if (!choices.includes(flags[name])) throw new UsageError(`--${name} must be ${alternatives(choices)} (got '${flags[name]}')`);
    out[name] = flags[name];
  }
  if (flags['max-iterations'] !== undefined) {
    const n = Number(flags['max-iterations']);
    const option = optionSchema('maxIterations');
    if (!optionAllows(option, n)) throw new UsageError(`--max-iterations must be ${option.expects} (got ${describeValue(flags['max-iterations'])})`);
    out.maxIterations = n;
  }
  return out;
}

// The warnings with codes the report and the summary show (the app shows the same): a poor cage
// (cage_quality's codes), then the result's (folded triangles, a deformed cage that crosses itself).
function resultWarnings(deformer, hasCage) {
  const warnings = [];
  if (hasCage) {
    const q = deformer.cageQuality();
    q.warnings.forEach((message, k) => warnings.push({ severity: 'warning', code: q.warningCodes[k], message: `poor cage: ${message}` }));
  }
  return [...warnings, ...deformer.resultWarnings()];
}

function makeReport(deformer, result, lines, totalMs) {
  // Per group, its vertices' largest distance from their targets, or from their lines for a group with "along" or
  // "from" (its depth is free).
  const handleDistances = Array.from(deformer.handleDistances());
  const handleMaxError = Math.max(0, ...handleDistances);
  const last = result.iterations.at(-1);
  const options = deformer.options();
  const parts = deformer.volumeParts();
  const rest = parts.length ? deformer.restPartVolumes() : null;
  return {
    method: options.method,
    jacobian: options.jacobian,
    volumeConstraint: options.volume,
    weighting: options.weighting,
    integration: options.method === 'subspace' ? options.integration : 'full',
    basis: deformer.basis,
    basisSize: deformer.basisSize,
    coordinates: deformer.coordinatesReport(),
    volumePartCount: parts.length ? Math.max(...parts) + 1 : 0,
    ...(rest ? {
      restPartVolumes: Array.from(rest),
      partVolumeChange: Array.from(deformer.partVolumes(), (v, k) => (v - rest[k]) / Math.abs(rest[k])),
    } : {}),
    vertexCount: deformer.vertexCount,
    layout: layoutSummary(deformer.layout()),
    handleVertexCount: deformer.handleCount,
    restVolume: deformer.restVolume,
    converged: result.converged,
    stop: result.stop,
    stopReason: result.stopReason,
    iterationCount: result.iterations.length,
    energy: last ? last.energy : 0,
    volumeRelError: last ? last.volumeRelError : 0,
    handleMaxError,
    handleDistances,
    handleLines: lines,
    bindMs: deformer.bindMs,
    precomputeMs: deformer.precomputeMs,
    solveMs: result.iterations.reduce((sum, it) => sum + it.ms, 0),
    totalMs,
    products: result.iterations.reduce((sum, it) => sum + it.products, 0),
    fallbackVertices: deformer.fallbackCount,
    ...(options.method === 'subspace' && options.integration === 'reduced' ? { reducedIntegration: reducedReport(deformer) } : {}),
    ...skeletonReport(deformer),
    iterations: result.iterations,
  };
}

// The layout's counts for the report (without the per-vertex map).
function layoutSummary(layout) {
  const counts = { ...layout };
  delete counts.solverOfFile;
  return counts;
}

// The reduced integration's samples and fit, and the energy the solve reached summed over every vertex.
function reducedReport(deformer) {
  const { rule, samples, candidates, testError, reliable, ms } = deformer.reducedIntegration();
  return { rule, samples, candidates, testError, reliable, fitMs: ms, fullEnergy: deformer.fullEnergy() };
}

// A reduced solve whose rule misses what the full energy sees may converge to another shape: say so.
function reducedWarnings(report) {
  const reduced = report.reducedIntegration;
  if (!reduced || reduced.reliable) return [];
  return [{
    severity: 'warning', code: 'reduced_integration_inaccurate',
    message: `the reduced integration's rule misses part of the energy (error ${reduced.testError.toPrecision(3)} on ` +
      'held-out poses, above 0.25): this shape may differ from the full solve\'s; run with --integration full',
  }];
}

// ARAP pins every handle vertex to its target: a scene's "along"/"from" does not apply to it (the app's views say the same).
function lineWarnings(report) {
  return handleLineWarnings(report.method, report.handleLines);
}

// The skeleton's deformed joints and, per bone, its length and straightness errors (relative to its rest length)
// and its multiplier, and whether the method kept it (ARAP does not: its bones say they held nothing).
function skeletonReport(deformer) {
  const report = deformer.skeletonReport();
  if (!report) return {};
  const joints = Array.from({ length: report.joints.length / 3 }, (_, j) => Array.from(report.joints.subarray(3 * j, 3 * j + 3)));
  return { skeleton: { joints, bones: report.bones, kept: report.kept } };
}

// ARAP does not keep bones (in the words of the app's ARAP view: skeleton.js skeletonWarnings); a space too coarse to
// hold a bone's middle beside the other constraints keeps it only partly straight, and the remedy depends on the space
// (a finer cage, more modes; in the full space, bones along each other).
function boneWarnings(report, basis) {
  if (!report.skeleton) return [];
  const ignored = skeletonWarnings(report.method, report.skeleton);
  if (ignored.length || !report.skeleton.kept) return ignored;
  const loose = report.skeleton.bones.flatMap((b, k) => (b.straightHard ? [] : [k]));
  if (!loose.length) return [];
  const why = {
    full: ['the full space', 'they lie along other bones', 'separate the bones that overlap'],
    cage: ['the subspace', 'too few cage vertices around them', 'use a finer cage or the full space'],
    spectral: ['the subspace', 'too few modes', 'use more modes or the full space'],
  }[report.method === 'full' ? 'full' : basis] ?? ['the subspace', 'the subspace is too coarse around them', 'use the full space'];
  return [{
    severity: 'warning', code: 'bones_not_held_straight',
    message: `${why[0]} cannot hold bone${loose.length > 1 ? 's' : ''} ${loose.join(', ')} straight exactly beside the other ` +
      `constraints (${why[1]}): their lengths are kept, their straightness only in part; ${why[2]}`,
  }];
}

// How the solve ended, said plainly: an iteration cap or a time limit is not a convergence.
function outcome(r) {
  if (r.cutShort) return `NOT converged (stopped by ${r.cutShort.by === 'SIGINT' ? 'Ctrl-C' : '--time-limit'})`;
  if (r.converged) return `converged (${r.stopReason.replace(/^converged: /, '')})`;
  if (r.stop === 'max_iterations' || r.stop === 'iteration_limit') return 'NOT converged (stopped at the iteration limit)';
  return `NOT converged (${r.stopReason})`;
}

function printSummary(scenePath, r) {
  const g = (x) => Number(x).toPrecision(4);
  const coordinates = r.coordinates ? `, ${r.coordinates.coordinates} coordinates` : '';
  const subspace = r.method === 'subspace' ? ` (${r.basis} basis${coordinates}, ${r.basisSize} columns)` : '';
  // ARAP keeps no volume (its volume error is reported all the same) and has no Gauss-Newton Jacobian.
  const volume = !r.volumeConstraint || r.method === 'arap' ? ''
    : r.volumePartCount ? ` with the volume of ${r.volumePartCount} part${r.volumePartCount === 1 ? '' : 's'}` : ' with volume';
  const method = r.method === 'arap' ? 'arap (volume not kept)' : `${r.method}/${r.jacobian}`;
  console.log(`${scenePath}: ${method}${subspace}${volume}, ${r.vertexCount} vertices, ${r.handleVertexCount} handle vertices`);
  console.log(`  ${outcome(r)} after ${r.iterationCount} iterations, ${duration(r.solveMs)} (bind ${duration(r.bindMs)})`);
  console.log(`  energy ${g(r.energy)}, volume error ${g(r.volumeRelError)}, handle max error ${g(r.handleMaxError)}`);
  if (r.partVolumeChange) console.log(`  part volume changes ${r.partVolumeChange.map(g).join(', ')}`);
  if (r.skeleton) {
    const worst = (key) => Math.max(...r.skeleton.bones.map((b) => Math.abs(b[key])));
    console.log(`  ${r.skeleton.bones.length} bones: length error ${g(worst('lengthError'))}, straightness error ${g(worst('straightnessError'))} (of their lengths)`);
  }
  for (const w of r.warnings) console.log(`  warning (${w.code}): ${w.message}`);
  const reduced = r.reducedIntegration;
  if (reduced) {
    const rule = reduced.rule === 'clusters' ? `${reduced.samples} rotation clusters` : `every vertex (${reduced.samples})`;
    const finishing = r.iterations.filter((it) => it.finishing).length;
    console.log(`  reduced integration: ${rule} (made in ${duration(reduced.fitMs)}, error on held-out poses ` +
      `${g(reduced.testError)}); ${finishing} finishing iterations on every vertex; energy over every vertex ` +
      `${g(reduced.fullEnergy)}`);
  }
}
