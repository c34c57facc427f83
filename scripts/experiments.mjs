// Reproduces the report's experiments (section 3, figures 3-5) headless in Node through the wasm Deformer
// (results and discussion: docs/experiments/README.md). For each scene it runs the subspace solve (fast and exact), the full space and ARAP from the
// rest pose, records merit per iteration and cumulative ms, measures every final shape with the same
// yardsticks (the energy of docs/method.md section 5, the ARAP energy, volume change, handle error), and writes
//   docs/experiments/results.json, docs/experiments/*.svg (plots), docs/experiments/<scene>.json (scene files)
// The README beside them discusses the results (written by hand from results.json).
// Beyond the report (its future work): on every scene the cage-free spectral subspace for several k and the
// condition number of the step's matrix per basis (experiments/subspaces.mjs), and a neck pull with one global
// volume against the volume of each part (experiments/volume_parts.mjs).
//
//   npm run experiments -- [--quick] [--builtin] [--out DIR] [--only id,...] [--spectral-cost]
//                          [--weighting area|uniform] [--integration full|reduced]
//   --quick          smaller iteration caps and time budgets (about a minute)
//   --builtin        use the built-in procedural models even when ../shared/data is present
//   --only           run only these scenes (ids, neck_pull included); results.json then holds only them; an
//                    unknown id is refused (exit 2, nothing written)
//   --spectral-cost  also time the spectral basis in wasm at n = 5k, 20k, 50k and k = 50, 100, 200 (minutes)
//   --weighting      the energy's weighting for every series (default area; uniform is the report's formulation)
//   --integration    the subspace series' integration (default full; reduced samples the Laplacian term)
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { basename, dirname, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import os from 'node:os';
import { CommandLineError, parseCommandLine } from './lib/command_line.mjs';
import { requireBuild } from './lib/require_build.mjs';

// The library needs the wasm build: without one, one line says how to make it (lib/require_build.mjs).
requireBuild('experiments');
const { Deformer, handleTargets, loadSolver, makeExample, parseScene, readMesh, wasmDir } = await import('subspace-deform');
const { SCENES, bounds } = await import('./experiments/scenes.mjs');
const { runSeries, SERIES } = await import('./experiments/series.mjs');
const { compareSubspaces } = await import('./experiments/subspaces.mjs');
const { NECK_PULL, runVolumeParts } = await import('./experiments/volume_parts.mjs');
const { linePlot } = await import('./experiments/svg_plot.mjs');
const { renderViews } = await import('./experiments/render.mjs');
const { Timer } = await import('./lib/timer.mjs'); // with the app's time format, which imports the library

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const sharedData = resolve(root, '../shared/data');

const USAGE = 'usage: node scripts/experiments.mjs [--quick] [--builtin] [--out DIR] [--only id,...] [--spectral-cost] ' +
  '[--weighting area|uniform] [--integration full|reduced]';
const FLAGS = {
  quick: { type: 'boolean' }, builtin: { type: 'boolean' }, out: { type: 'string' }, only: { type: 'string' },
  'spectral-cost': { type: 'boolean' }, weighting: { type: 'string' }, integration: { type: 'string' },
  help: { type: 'boolean', short: 'h' },
};

function parseArgs(argv) {
  const usage = (message) => {
    console.error(`experiments: ${message}`);
    process.exit(2);
  };
  let parsed;
  try {
    parsed = parseCommandLine(argv, FLAGS);
  } catch (error) {
    if (!(error instanceof CommandLineError)) throw error;
    usage(error.kind === 'unknown' ? `unknown argument '${error.flag}'` : error.message);
  }
  const { positionals, flags } = parsed;
  if (flags.help) {
    console.log(USAGE);
    process.exit(0);
  }
  if (positionals.length) usage(`unknown argument '${positionals[0]}'`);
  const weighting = flags.weighting ?? 'area', integration = flags.integration ?? 'full';
  if (!['area', 'uniform'].includes(weighting)) usage(`--weighting must be area or uniform (got '${weighting}')`);
  if (!['full', 'reduced'].includes(integration)) usage(`--integration must be full or reduced (got '${integration}')`);
  // A typo in --only used to run no scene and still write results.json, replacing the committed results with an
  // empty run: every id must name a scene.
  const known = [...SCENES.map((sc) => sc.id), NECK_PULL.id];
  const unknown = flags.only?.split(',').find((id) => !known.includes(id));
  if (unknown !== undefined) usage(`--only: unknown scene '${unknown}' (known: ${known.join(', ')})`);
  return {
    solverOptions: { weighting, integration },
    quick: !!flags.quick, builtin: !!flags.builtin, out: resolve(flags.out ?? resolve(root, 'docs/experiments')),
    only: flags.only === undefined ? null : new Set(flags.only.split(',')), spectralCost: !!flags['spectral-cost'],
  };
}

// Loads the scene's real model pair from ../shared/data, or the built-in stand-in.
function loadModel(solver, scene, args) {
  const { mesh: meshFile, cage: cageFile, name } = scene.model ?? {};
  const meshPath = scene.model && resolve(sharedData, meshFile), cagePath = scene.model && resolve(sharedData, cageFile);
  if (scene.model && !args.builtin && existsSync(meshPath) && existsSync(cagePath)) {
    return {
      real: true, name, meshPath, cagePath,
      mesh: readMesh(solver, readFileSync(meshPath), meshFile),
      cage: readMesh(solver, readFileSync(cagePath), cageFile),
    };
  }
  const why = !scene.model ? null : args.builtin ? '--builtin given' : `${meshPath} or ${cagePath} is absent`;
  const ex = makeExample(solver, scene.fallback.example);
  // Scene files name built-in models by "example" (no mesh files needed).
  return { real: false, name: ex.name, why, example: ex.name, mesh: ex.mesh, cage: ex.cage };
}

function plotScene(out, scene, result) {
  const usable = result.series.filter((s) => s.iterations.length > 0);
  const gn = usable.filter((s) => !s.method.startsWith('arap'));
  const files = [];
  const write = (name, spec) => {
    writeFileSync(resolve(out, name), linePlot(spec));
    files.push(name);
  };
  const model = `${result.model.name}, n = ${result.n}, m = ${result.m}`;
  // Merit per iteration and per ms for the Gauss-Newton methods (the same energy).
  write(`${scene.id}_merit_iterations.svg`, {
    title: `${scene.id}: merit per iteration (${model})`,
    xLabel: 'iteration', yLabel: 'merit 1/2|f|^2 + lambda g', logY: true,
    series: gn.map((s) => ({ name: s.label, x: s.iterations.map((it) => it.iteration), y: s.iterations.map((it) => it.merit), dash: s.method.includes('exact') })),
  });
  write(`${scene.id}_merit_ms.svg`, {
    title: `${scene.id}: merit per wall-clock ms (wasm, ${model})`,
    xLabel: 'cumulative ms (log)', yLabel: 'merit 1/2|f|^2 + lambda g', logY: true, logX: true,
    series: gn.map((s) => ({ name: s.label, x: s.iterations.map((it) => it.cumulativeMs), y: s.iterations.map((it) => it.merit), dash: s.method.includes('exact') })),
  });
  // Every method measured by the same energy 1/2|f|^2 (ARAP's iterates evaluated at sampled iterations).
  write(`${scene.id}_energy_all.svg`, {
    title: `${scene.id}: energy 1/2|f|^2 of every method (${model})`,
    xLabel: 'iteration (log)', yLabel: 'energy 1/2|f|^2 (docs/method.md)', logY: true, logX: true,
    series: usable.map((s) => ({
      name: s.label,
      x: s.energyTrace.map((e) => e.iteration),
      y: s.energyTrace.map((e) => e.energy),
      dash: s.method.includes('exact') || s.method.includes('sliced'),
    })),
  });
  return files;
}

function writeSceneFile(out, scene, model, handles, extra = {}) {
  // Real models by their file names: a scene names files only in its own folder and below (docs/scene-format.md),
  // so the models are linked or copied beside it to run it; they stay out of the repository (.gitignore).
  const mesh = model.meshPath && basename(model.meshPath), cage = model.cagePath && basename(model.cagePath);
  const file = {
    name: scene.id,
    description: `${scene.title}. ${model.real ? `The mesh and cage come from ../shared/data and are NOT shipped with the project (see ../shared/data/SOURCES.md for their licences). Link or copy ${mesh} and ${cage} beside this file first (docs/experiments/README.md), then run` : `Built-in example '${model.example}' (no files needed). Run`}: node scripts/deform.mjs deform docs/experiments/${scene.id}.json [--method full|arap] [--jacobian exact]`,
    ...(model.example ? { example: model.example } : { mesh, cage }),
    handles: handles.map((h) => {
      const out = { vertices: h.vertices };
      if (h.translate) out.translate = h.translate.map((x) => +x.toPrecision(8));
      if (h.rotate) out.rotate = { ...h.rotate, center: h.rotate.center.map((x) => +x.toPrecision(8)) };
      return out;
    }),
    solver: { method: 'subspace', jacobian: 'fast', volume: true, maxIterations: 100, positionWeight: 1.0 },
    ...extra,
  };
  parseScene(file);  // the file must be valid for the CLI and the app
  const name = `${scene.id}.json`;
  // Number arrays on one line each, so the handle lists stay readable.
  const text = JSON.stringify(file, null, 2).replace(/\[\s*(-?[\d.e+-]+(?:,\s*-?[\d.e+-]+)*)\s*\]/g,
    (_, inner) => `[${inner.split(/,\s*/).join(', ')}]`);
  writeFileSync(resolve(out, name), text + '\n');
  return name;
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  mkdirSync(args.out, { recursive: true });
  const solver = await loadSolver({ bench: true });
  if (typeof solver.benchEvaluateEnergy !== 'function') {
    console.error(`experiments: ${wasmDir()} lacks the benchEvaluateEnergy binding (cpp/tools/wasm/bench_bindings.cpp): rebuild with "bash scripts/build.sh --wasm"`);
    process.exit(1);
  }
  const started = new Timer();
  const results = {
    date: new Date().toISOString(),
    quick: args.quick,
    solverOptions: args.solverOptions,
    machine: { nproc: os.availableParallelism?.() ?? os.cpus().length, cpu: os.cpus()[0]?.model ?? 'unknown', loadBefore: os.loadavg() },
    notes: [],
    scenes: [],
  };
  for (const scene of SCENES.filter((sc) => !args.only || args.only.has(sc.id))) {
    const { model, handles, query, context, b } = prepare(solver, scene, args, results);
    const { d } = context;
    const series = [];
    for (const kind of scene.series) {
      const sceneTimer = new Timer();
      let s;
      try {
        s = runSeries(context, kind);
      } catch (error) {
        // A method may refuse a scene (e.g. a singular exact normal matrix): record why and go on.
        console.warn(`${scene.id} [${model.name}] ${SERIES[kind].label}: failed: ${error.message}`);
        results.notes.push(`${scene.id}: ${SERIES[kind].label} failed: ${error.message}`);
        continue;
      }
      series.push(s);
      console.log(`${scene.id} [${model.name}] ${SERIES[kind].label}: ${s.iterations.length} iterations, ` +
        `energy ${s.final.energy.toExponential(3)}, volume ${s.final.volumeChangePercent.toFixed(3)}%, ` +
        `handle error ${s.final.handleMaxErrorRelative.toExponential(2)} D, ${s.stopReason} (${sceneTimer.seconds().toFixed(1)} s)`);
    }
    const result = {
      id: scene.id, figure: scene.figure, title: scene.title, query,
      model: model.example
        ? { name: model.name, real: false, example: model.example }
        : { name: model.name, real: true, mesh: relative(root, model.meshPath), cage: relative(root, model.cagePath) },
      n: model.mesh.positions.length / 3, m: model.cage.positions.length / 3,
      bindMs: d.bindMs, diagonal: b.diagonal, restVolume: d.restVolume,
      handleVertexCount: context.handleVertices.length,
      series,
    };
    result.sceneFile = writeSceneFile(args.out, scene, model, handles);
    result.plots = plotScene(args.out, scene, result);
    result.images = renderViews(args.out, scene.id, model.mesh, series, context, { yaw: model.real ? scene.view?.yaw ?? 0 : 0 });
    result.subspaces = compareSubspaces(context, model, scene, series, args.out, console.log);
    results.scenes.push(result);
    d.dispose();
  }
  if (!args.only || args.only.has(NECK_PULL.id)) results.volumeParts = neckPull(solver, args, results);
  if (args.spectralCost) results.spectralCost = spectralCost(solver);
  results.seconds = started.seconds();
  results.machine.loadAfter = os.loadavg();
  // Per-iteration records as columns ({ iteration: [...], merit: [...], ... }), number arrays on one line.
  for (const scene of results.scenes) {
    for (const s of [...scene.series, ...scene.subspaces.series]) s.iterations = columns(s.iterations);
  }
  for (const s of results.volumeParts?.series ?? []) s.iterations = columns(s.iterations);
  const text = JSON.stringify(results, roundReplacer, 1).replace(/\[\s*(-?[\d.e+-]+(?:,\s*-?[\d.e+-]+)*)\s*\]/g,
    (_, inner) => `[${inner.split(/,\s*/).join(',')}]`);
  writeFileSync(resolve(args.out, 'results.json'), text + '\n');
  console.log(`wrote ${relative(process.cwd(), resolve(args.out, 'results.json'))} and plots in ${results.seconds.toFixed(0)} s`);
}

// A scene's model, handles and the context its series run in (a cage session with the handles set).
function prepare(solver, scene, args, results) {
  const model = loadModel(solver, scene, args);
  if (!model.real && model.why) {
    const note = `${scene.id}: real model ${scene.model.name} not used (${model.why}); built-in '${model.name}' instead`;
    console.warn(`experiments: ${note}`);
    results.notes.push(note);
  }
  const { handles, query, parts } = scene.build(model.mesh.positions, model.real);
  const parsed = parseScene({ mesh: 'x', handles });
  const { groups, targets } = handleTargets(model.mesh.positions, parsed.handles);
  const d = Deformer.create(solver, model.mesh, model.cage);
  const b = bounds(model.mesh.positions);
  const context = {
    solver, d, groups, targets, rest: model.mesh.positions, indices: model.mesh.indices,
    diagonal: b.diagonal, quick: args.quick, solverOptions: args.solverOptions,
    handleVertices: groups.flat(),
  };
  d.setHandles(groups);
  return { model, handles, query, parts, context, b };
}

// Global volume against volume per part (experiments/volume_parts.mjs), with its scene file.
function neckPull(solver, args, results) {
  const { model, handles, query, parts, context } = prepare(solver, NECK_PULL, args, results);
  context.d.dispose();
  const run = runVolumeParts(context, model, parts, args.out, console.log);
  const scene = { ...NECK_PULL, series: [] };
  const sceneFile = writeSceneFile(args.out, scene, model, handles, { volumeParts: { auto: parts } });
  return {
    id: NECK_PULL.id, title: NECK_PULL.title, query, sceneFile,
    model: model.example ? { name: model.name, real: false, example: model.example } : { name: model.name, real: true },
    n: model.mesh.positions.length / 3, m: model.cage.positions.length / 3, ...run,
  };
}

// The spectral basis' cost inside wasm on the benchmark capsules (docs/benchmarks.md has the native table).
function spectralCost(solver) {
  const rows = [];
  for (const n of [5000, 20000, 50000]) {
    for (const modes of [50, 100, 200]) {
      const row = solver.benchSpectralBasis(n, modes);
      console.log(`spectral basis in wasm: n = ${row.n}, k = ${modes}: ${row.ms.toFixed(0)} ms (${row.solves} solves), load ${os.loadavg()[0].toFixed(1)}`);
      rows.push({ ...row, load: os.loadavg()[0] });
    }
  }
  return rows;
}

function columns(rows) {
  const out = {};
  for (const key of Object.keys(rows[0] ?? {})) out[key] = rows.map((r) => r[key]);
  return out;
}

// Keeps results.json readable: 6 significant digits; positions are not stored.
function roundReplacer(key, value) {
  if (key === 'positions') return undefined;
  return typeof value === 'number' && !Number.isInteger(value) ? +value.toPrecision(6) : value;
}

main().catch((error) => {
  console.error(`experiments: ${error.stack ?? error.message}`);
  process.exit(1);
});
