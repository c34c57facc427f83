// `deform <scene.json>`: solves a scene file (docs/scene-format.md) with the same wasm solver as the app and
// writes the deformed mesh, the deformed cage and a convergence report.
import { readFileSync, writeFileSync } from 'node:fs';
import { basename, dirname, resolve } from 'node:path';
import {
  Deformer, JACOBIANS, METHODS, describeValue, generateCage, handleTargets, loadExample, optionAllows, optionSchema,
  parseScene, readMesh, writeObj,
} from 'subspace-deform';
import { UsageError, loadCommandSolver, parseArgs, readInputFile } from '../lib/cli_support.mjs';

const HELP = `usage: node scripts/deform.mjs deform <scene.json> [options]

Solves a scene: the mesh (and cage) it names -- or a built-in "example", or a mesh with "generateCage" --
its handle groups moved by their translate/rotate, with the scene's solver options. Command-line options
override the scene.
  --method subspace|full|arap   deformation method (subspace needs a cage)
  --jacobian exact|fast         Gauss-Newton step: dense reference or matrix-free PCG
  --max-iterations N            iteration cap
  --float32                     store the weights W in single precision
  --out mesh.obj                write the deformed mesh
  --cage-out cage.obj           write the deformed cage (the rest cage for full/arap)
  --report report.json          write the convergence report: iterations[] (energy, volume, step, ms,
                                ...), volumeRelError, handleMaxError, converged, stop (why it stopped),
                                iterationCount, bindMs
  --quiet                       print nothing but errors
  --threads N                   solver threads (default: every core, or SD_THREADS)
Exit status: 0 solved (converged or not: see the report), 1 invalid input or failed run, 2 bad usage.`;

const FLAGS = {
  help: 'boolean', method: 'string', jacobian: 'string', 'max-iterations': 'string', float32: 'boolean',
  out: 'string', 'cage-out': 'string', report: 'string', quiet: 'boolean', threads: 'string',
};

// The scene's mesh and cage: files relative to the scene, a built-in example, or a generated cage.
async function sceneModel(solver, scene, base) {
  if (scene.example) return loadExample(solver, scene.example);
  const mesh = readMesh(solver, readInputFile(resolve(base, scene.mesh)), basename(scene.mesh));
  if (scene.generateCage) return { mesh, cage: generateCage(solver, mesh, { vertices: scene.generateCage.vertices }) };
  const cage = scene.cage ? readMesh(solver, readInputFile(resolve(base, scene.cage)), basename(scene.cage)) : null;
  return { mesh, cage };
}

export async function deformCommand(argv) {
  const { positionals, flags } = parseArgs(argv, FLAGS);
  if (flags.help) {
    console.log(HELP);
    return 0;
  }
  if (positionals.length !== 1) throw new UsageError(`deform takes exactly one scene file\n\n${HELP}`);
  const options = overrides(flags);
  const solverPromise = loadCommandSolver(flags);
  const scenePath = positionals[0];
  const scene = parseScene(new TextDecoder().decode(readInputFile(scenePath)));
  const base = dirname(resolve(scenePath));
  const solver = await solverPromise;
  const { mesh, cage } = await sceneModel(solver, scene, base);
  const { groups, targets } = handleTargets(mesh.positions, scene.handles);

  const started = performance.now();
  const deformer = Deformer.create(solver, mesh, cage, { float32: !!flags.float32 });
  try {
    const solverOptions = { ...scene.solver, ...options };
    if (!cage && solverOptions.method === undefined) solverOptions.method = 'full';
    deformer.setOptions(solverOptions);
    deformer.setHandles(groups);
    deformer.setTargets(targets);
    const result = deformer.solve();
    const positions = deformer.positions();
    const report = makeReport(deformer, result, positions, groups, targets, performance.now() - started);
    report.wasmBuild = solver.build;
    report.threads = solver.threads();

    if (flags.out) writeFileSync(flags.out, writeObj(solver, { positions, indices: mesh.indices }, `deformed by subspace-deform from ${basename(scenePath)}`));
    if (flags['cage-out']) {
      if (!cage) throw new Error('--cage-out: the scene has no cage');
      writeFileSync(flags['cage-out'], writeObj(solver, { positions: deformer.cagePositions(), indices: cage.indices }, `cage deformed by subspace-deform from ${basename(scenePath)}`));
    }
    if (flags.report) writeFileSync(flags.report, `${JSON.stringify(report, null, 2)}\n`);
    if (!flags.quiet) printSummary(scenePath, report);
    return 0;
  } finally {
    deformer.dispose();
  }
}

// "a, b or c"
function alternatives(list) {
  return `${list.slice(0, -1).join(', ')} or ${list.at(-1)}`;
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
  if (flags['max-iterations'] !== undefined) {
    const n = Number(flags['max-iterations']);
    const option = optionSchema('maxIterations');
    if (!optionAllows(option, n)) throw new UsageError(`--max-iterations must be ${option.expects} (got ${describeValue(flags['max-iterations'])})`);
    out.maxIterations = n;
  }
  return out;
}

function makeReport(deformer, result, positions, groups, targets, totalMs) {
  let handleMaxError = 0;
  let row = 0;
  for (const group of groups) {
    for (const v of group) {
      const d = Math.hypot(positions[3 * v] - targets[3 * row], positions[3 * v + 1] - targets[3 * row + 1], positions[3 * v + 2] - targets[3 * row + 2]);
      handleMaxError = Math.max(handleMaxError, d);
      ++row;
    }
  }
  const last = result.iterations.at(-1);
  const options = deformer.options();
  return {
    method: options.method,
    jacobian: options.jacobian,
    volumeConstraint: options.volume,
    vertexCount: deformer.vertexCount,
    handleVertexCount: deformer.handleCount,
    restVolume: deformer.restVolume,
    converged: result.converged,
    stop: result.stop,
    stopReason: result.stopReason,
    iterationCount: result.iterations.length,
    energy: last ? last.energy : 0,
    volumeRelError: last ? last.volumeRelError : 0,
    handleMaxError,
    bindMs: deformer.bindMs,
    precomputeMs: deformer.precomputeMs,
    solveMs: result.iterations.reduce((sum, it) => sum + it.ms, 0),
    totalMs,
    products: result.iterations.reduce((sum, it) => sum + it.products, 0),
    fallbackVertices: deformer.fallbackCount,
    iterations: result.iterations,
  };
}

function printSummary(scenePath, r) {
  const g = (x) => Number(x).toPrecision(4);
  console.log(`${scenePath}: ${r.method}/${r.jacobian}${r.volumeConstraint ? ' with volume' : ''}, ${r.vertexCount} vertices, ${r.handleVertexCount} handle vertices`);
  console.log(`  ${r.converged ? 'converged' : 'NOT converged'} (${r.stopReason}) after ${r.iterationCount} iterations, ${g(r.solveMs)} ms (bind ${g(r.bindMs)} ms)`);
  console.log(`  energy ${g(r.energy)}, volume error ${g(r.volumeRelError)}, handle max error ${g(r.handleMaxError)}`);
}
