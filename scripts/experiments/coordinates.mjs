// Mean value, positive mean value and harmonic coordinates compared on concave cages (docs/experiments/
// coordinates.md; docs/method.md sections 2, 18 and 19): the shared armadillo and gargoyle with their cages
// (../shared/data, skipped with a note when absent) and the built-in C (a capsule bent into a C in its bent
// cage). Per model and coordinate type:
//   - binding: wasm time, W's memory and harmonic's grid and factor, the smallest weight, the share of weights
//     below -1e-3, rays per vertex (pmvc), the grid (harmonic);
//   - what is lost: linear precision max |W P0 - X0| / D, and smoothness along the C's centre line (second
//     differences of W at two spacings: they stay put for a smooth W and grow where W has a kink);
//   - how far a region moves when a far cage vertex moves: the cage vertex j whose mean value weights are the
//     most negative, and the region R where they are negative; moving p_j by d moves each mesh vertex by W_ij d,
//     so R's largest and mean |W_ij| (in units of |d|) and its mean W_ij (negative: R moves against d);
//   - the same drag solved with each (subspace, fast): energy, volume error, handle error, iterations, time,
//     and how far each final shape is from mean value coordinates' one;
//   - the step's conditioning at rest (the Gauss-Newton normal matrix in the subspace, raw and in an
//     orthonormal basis of the subspace).
// Writes coordinates.json, coordinates_<model>_shapes.png (rest and each type's drag) and
// coordinates_<model>_influence.png (cage vertex j's weight on the mesh per type, the app's colours) and prints
// the tables of coordinates.md.
//   node scripts/experiments/coordinates.mjs [--quick] [--out DIR]   (--quick: a coarser harmonic grid and pmvc sampling)
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import os from 'node:os';
import { Color } from 'three';
import { COORDINATES, Deformer, computeWeights, handleTargets, loadSolver, makeExample, parseSceneHandles, readMesh } from 'subspace-deform';
import { influenceColors, sharedScale } from '../../web/app/influence/influence_colors.js';
import { bounds, point, verticesBelow, verticesNear } from './scenes.mjs';
import { renderViews } from './render.mjs';
import { CommandLineError, parseCommandLine } from '../lib/command_line.mjs';
import { Timer } from '../lib/timer.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..');
const sharedData = resolve(root, '../shared/data');
const TYPES = COORDINATES.types;

// The models and their drags: handle regions by geometric queries, motions in units of the diagonal D.
const MODELS = [
  {
    id: 'c_bar', name: 'C (built-in c-bar)', example: 'c-bar', view: { yaw: 0, pitch: 0 },
    drag(p) {
      // The C opens towards +x; its two ends are the extremes of the angle about the bend's centre.
      const n = p.length / 3, angle = (v) => Math.atan2(p[3 * v + 1], -p[3 * v]);
      const order = [...Array(n).keys()].sort((a, b) => angle(a) - angle(b));
      const fixed = order.slice(0, 300), moved = order.slice(n - 300);
      return { handles: [{ vertices: fixed }, { vertices: moved, translate: [0.3, 0.9, 0] }],
        query: 'fixed: the lower end of the C (300 vertices); moved: the upper end (300 vertices) by (0.3, 0.9, 0), opening the C' };
    },
  },
  {
    id: 'armadillo', name: 'armadillo', mesh: 'armadillo.obj', cage: 'armadillo_cage.obj', view: { yaw: Math.PI, pitch: 0.25 },
    drag(p) {
      // The hands (the extremes in x) brought together across the body: the drag of two_handle_pull.
      const b = bounds(p), r = 0.025 * b.diagonal;
      const left = verticesNear(p, point(p, b.argLo[0]), r), right = verticesNear(p, point(p, b.argHi[0]), r);
      return { handles: [{ vertices: left }, { vertices: right, translate: [-0.3 * b.diagonal, 0, 0.045 * b.diagonal] }],
        query: `fixed: within 0.025 D of the lowest-x point (left hand, ${left.length} vertices); moved: within 0.025 D of the highest-x point (right hand, ${right.length} vertices) by 0.3 D towards -x` };
    },
  },
  {
    id: 'gargoyle', name: 'gargoyle', mesh: 'gargoyle.obj', cage: 'gargoyle_cage.obj', view: { yaw: Math.PI / 2, pitch: 0.25 },
    drag(p) {
      // The base fixed, the top pushed sideways.
      const b = bounds(p);
      const axis = b.size.indexOf(Math.max(...b.size));
      const base = verticesBelow(p, axis, b.lo[axis] + 0.08 * b.size[axis]);
      const top = [];
      for (let v = 0; v < p.length / 3; ++v) if (p[3 * v + axis] >= b.hi[axis] - 0.1 * b.size[axis]) top.push(v);
      const translate = [0, 0, 0];
      translate[(axis + 2) % 3] = 0.15 * b.diagonal;
      return { handles: [{ vertices: base }, { vertices: top, translate }],
        query: `fixed: the lowest 8% along the longest axis (${base.length} vertices); moved: the top 10% (${top.length} vertices) sideways by 0.15 D` };
    },
  },
];

function parseArgs(argv) {
  const usage = (message) => {
    console.error(`coordinates experiment: ${message} (use --quick, --out DIR)`);
    process.exit(2);
  };
  let parsed;
  try {
    parsed = parseCommandLine(argv, { quick: { type: 'boolean' }, out: { type: 'string' } });
  } catch (error) {
    if (!(error instanceof CommandLineError)) throw error;
    usage(error.kind === 'unknown' ? `unknown argument '${error.flag}'` : error.message);
  }
  const { positionals, flags } = parsed;
  if (positionals.length) usage(`unknown argument '${positionals[0]}'`);
  return { quick: !!flags.quick, out: resolve(flags.out ?? resolve(root, 'docs/experiments')) };
}

function loadModel(solver, spec) {
  if (spec.example) return { ...makeExample(solver, spec.example), real: false };
  const meshPath = resolve(sharedData, spec.mesh), cagePath = resolve(sharedData, spec.cage);
  if (!existsSync(meshPath) || !existsSync(cagePath)) return null;
  return { mesh: readMesh(solver, readFileSync(meshPath), spec.mesh), cage: readMesh(solver, readFileSync(cagePath), spec.cage), real: true };
}

// Each type's resolution: the defaults, or coarser with --quick.
const choice = (type, quick) => ({ coordinates: type, ...(quick && type === 'pmvc' ? { pmvcResolution: 12 } : {}),
  ...(quick && type === 'harmonic' ? { harmonicResolution: 32 } : {}) });

// max_i |sum_j W_ij p_j - x_i| / D.
function linearPrecision(W, rows, cols, cage, mesh, diagonal) {
  let worst = 0;
  for (let i = 0; i < rows; ++i) {
    const r = [0, 0, 0];
    for (let j = 0; j < cols; ++j) for (let a = 0; a < 3; ++a) r[a] += W[i * cols + j] * cage.positions[3 * j + a];
    worst = Math.max(worst, Math.hypot(r[0] - mesh.positions[3 * i], r[1] - mesh.positions[3 * i + 1], r[2] - mesh.positions[3 * i + 2]));
  }
  return worst / diagonal;
}

function bind(solver, model, type, quick, diagonal) {
  const r = computeWeights(solver, model.mesh, model.cage, { ...choice(type, quick), memoryBudgetMB: 3000 });
  let negative = 0;
  for (const w of r.weights) if (w < -1e-3) ++negative;
  return {
    W: r.weights, rows: r.rows, cols: r.cols,
    summary: {
      bindMs: r.bindMs, wMB: r.bytes / 1e6, extraMB: (r.gridBytes ?? 0) / 1e6, minWeight: r.minWeight,
      negativeShare: negative / r.weights.length, linearPrecision: linearPrecision(r.weights, r.rows, r.cols, model.cage, model.mesh, diagonal),
      ...(type === 'pmvc' ? { raysPerVertex: r.rays / r.rows, hiddenFacesPerVertex: r.hiddenFaces / r.rows } : {}),
      ...(type === 'harmonic' ? { resolution: r.resolution, unknowns: r.unknowns, factorMs: r.factorMs, solveMs: r.solveMs } : {}),
    },
  };
}

// Cage vertex j with the most negative mean value weight, and the region R where its weight is below -1e-3 x
// its largest: what moves the wrong way when p_j moves.
function farVertex(mvc) {
  let j = 0, lowest = Infinity;
  for (let k = 0; k < mvc.W.length; ++k) if (mvc.W[k] < lowest) { lowest = mvc.W[k]; j = k % mvc.cols; }
  const column = Float32Array.from({ length: mvc.rows }, (_, i) => mvc.W[i * mvc.cols + j]);
  const largest = Math.max(...column);
  const region = [];
  column.forEach((w, i) => { if (w < -1e-3 * largest) region.push(i); });
  return { vertex: j, region };
}

function regionMotion(bound, j, region) {
  let max = 0, sum = 0, signed = 0;
  for (const i of region) {
    const w = bound.W[i * bound.cols + j];
    max = Math.max(max, Math.abs(w));
    sum += Math.abs(w);
    signed += w;
  }
  return { maxMove: max, meanMove: sum / region.length, meanSigned: signed / region.length };
}

function solveDrag(solver, model, type, quick, groups, targets, diagonal) {
  const d = Deformer.create(solver, model.mesh, model.cage, { ...choice(type, quick), memoryBudgetMB: 3000 });
  try {
    d.setOptions({ method: 'subspace', jacobian: 'fast', maxIterations: 200 });
    d.setHandles(groups);
    d.setTargets(targets);
    const result = d.solve();
    const last = result.iterations.at(-1);
    const positions = d.positions();
    let handleError = 0, row = 0;
    for (const g of groups) for (const v of g) {
      handleError = Math.max(handleError, Math.hypot(...[0, 1, 2].map((a) => positions[3 * v + a] - targets[3 * row + a])));
      ++row;
    }
    return {
      positions,
      summary: { converged: result.converged, stop: result.stop, iterations: result.iterations.length, energy: last.energy,
        volumeRelError: last.volumeRelError, handleError: handleError / diagonal, solveMs: result.iterations.reduce((s, it) => s + it.ms, 0) },
    };
  } finally {
    d.dispose();
  }
}

function conditioning(solver, model, type, quick, handleVertices, targets) {
  try {
    const c = solver.benchStepConditioning(model.mesh.positions, model.mesh.indices, model.mesh.positions, handleVertices, targets, 1.0,
      { kind: 'cage', positions: model.cage.positions, indices: model.cage.indices, ...choice(type, quick) });
    return { raw: c.condition, orthonormal: c.orthonormal.condition };
  } catch (error) {
    return { error: error.message };
  }
}

// Second differences of W along the C's centre line (the bar's axis, bent like the mesh): their largest value
// over h^2, at spacing h and h / 4. A twice differentiable W gives about the same number at both; a kink in W
// gives 4 times more at h / 4 (it grows like 1 / h), a jump 16 times more.
function smoothness(solver, model, type, quick) {
  const radius = 5.4 / (1.5 * Math.PI);
  const line = (count) => {
    const p = new Float64Array(3 * count);
    for (let k = 0; k < count; ++k) {
      const x = -2.2 + (4.4 * k) / (count - 1), angle = x / radius;
      const bentX = radius * Math.sin(angle), bentY = radius - radius * Math.cos(angle);
      p.set([bentY - radius, -bentX, 0.1], 3 * k);  // the quarter turn of examples.cpp's c-bar
    }
    return p;
  };
  const measure = (count) => {
    const r = computeWeights(solver, { positions: line(count) }, model.cage, choice(type, quick));
    const h = 4.4 / (count - 1);
    let worst = 0;
    for (let k = 1; k + 1 < count; ++k) {
      for (let j = 0; j < r.cols; ++j) {
        const d2 = r.weights[(k - 1) * r.cols + j] - 2 * r.weights[k * r.cols + j] + r.weights[(k + 1) * r.cols + j];
        worst = Math.max(worst, Math.abs(d2) / (h * h));
      }
    }
    return worst;
  };
  const coarse = measure(201), fine = measure(801);
  return { coarse, fine, growth: fine / coarse };
}

// The app's influence colours (linear) as 0-255 sRGB per triangle (the mean of its vertices').
function faceColorsOf(values, scale, indices) {
  const { colors } = influenceColors(values, scale);
  const c = new Color();
  const faces = [];
  for (let f = 0; f < indices.length / 3; ++f) {
    let r = 0, g = 0, b = 0;
    for (let k = 0; k < 3; ++k) {
      const v = indices[3 * f + k];
      r += colors[3 * v] / 3; g += colors[3 * v + 1] / 3; b += colors[3 * v + 2] / 3;
    }
    c.setRGB(r, g, b).convertLinearToSRGB();
    faces.push([255 * c.r, 255 * c.g, 255 * c.b]);
  }
  return faces;
}

function runModel(solver, spec, args, log) {
  const model = loadModel(solver, spec);
  if (!model) return null;
  const b = bounds(model.mesh.positions);
  const { handles, query } = spec.drag(model.mesh.positions);
  const { groups, targets } = handleTargets(model.mesh.positions, parseSceneHandles(handles));
  const handleVertices = groups.flat();
  const bound = Object.fromEntries(TYPES.map((type) => [type, bind(solver, model, type, args.quick, b.diagonal)]));
  const far = farVertex(bound.mvc);
  const result = { id: spec.id, name: spec.name, real: model.real, n: bound.mvc.rows, m: bound.mvc.cols, diagonal: b.diagonal, query,
    farVertex: far.vertex, regionSize: far.region.length, types: {} };
  const shapes = [];
  for (const type of TYPES) {
    const drag = solveDrag(solver, model, type, args.quick, groups, targets, b.diagonal);
    shapes.push({ label: `${type}: drag`, positions: drag.positions });
    result.types[type] = {
      ...bound[type].summary,
      farVertex: regionMotion(bound[type], far.vertex, far.region),
      drag: drag.summary,
      conditioning: conditioning(solver, model, type, args.quick, handleVertices, targets),
      ...(spec.id === 'c_bar' ? { smoothness: smoothness(solver, model, type, args.quick) } : {}),
    };
    log(`${spec.id} ${type}: bind ${bound[type].summary.bindMs.toFixed(0)} ms, min weight ${bound[type].summary.minWeight.toPrecision(3)}, ` +
      `drag ${drag.summary.iterations} iterations energy ${drag.summary.energy.toExponential(3)}`);
  }
  for (const s of shapes) {
    let gap = 0;
    for (let i = 0; i < s.positions.length; i += 3) gap = Math.max(gap, Math.hypot(...[0, 1, 2].map((a) => s.positions[i + a] - shapes[0].positions[i + a])));
    result.types[s.label.split(':')[0]].drag.shapeGapToMvc = gap / b.diagonal;
  }
  const ctx = { groups, targets };
  result.shapesImage = renderViews(args.out, spec.id, model.mesh, shapes, ctx,
    { yaw: spec.view.yaw, pitch: spec.view.pitch, file: `coordinates_${spec.id}_shapes.png` }).file;
  // Cage vertex j's weight on the rest mesh, one panel per type, on one scale.
  const columns = TYPES.map((type) => Float32Array.from({ length: bound[type].rows }, (_, i) => bound[type].W[i * bound[type].cols + far.vertex]));
  const scale = sharedScale(columns.map((c) => ({ min: Math.min(...c), max: Math.max(...c) })));
  result.influenceImage = renderViews(args.out, spec.id, model.mesh, TYPES.map((type) => ({ label: type, positions: model.mesh.positions })),
    { groups: [[]], targets: new Float64Array(0) }, { yaw: spec.view.yaw, pitch: spec.view.pitch, file: `coordinates_${spec.id}_influence.png`,
      restLabel: 'rest', panelColors: [null, ...columns.map((c) => faceColorsOf(c, scale, model.mesh.indices))] }).file;
  result.influenceScale = scale;
  return result;
}

const fmt = (x, d = 3) => (Number.isFinite(x) ? Number(x.toPrecision(d)).toString() : String(x));

/** The tables of coordinates.md from the results. */
export function tables(results) {
  const out = [];
  const row = (cells) => out.push(`| ${cells.join(' | ')} |`);
  const head = (cells) => { row(cells); row(cells.map(() => '---')); };
  out.push('Binding and what it keeps:\n');
  head(['model (n, m)', 'coordinates', 'bind ms', 'W + extra MB', 'min weight', 'weights < -1e-3', 'linear precision / D', 'work']);
  for (const r of results.models) for (const t of TYPES) {
    const x = r.types[t];
    const work = t === 'pmvc' ? `${fmt(x.raysPerVertex, 3)} rays/vertex` : t === 'harmonic' ? `grid ${x.resolution}, ${x.unknowns} unknowns, factor ${fmt(x.factorMs, 3)} ms` : '';
    row([`${r.name} (${r.n}, ${r.m})`, t, fmt(x.bindMs, 3), `${fmt(x.wMB, 3)} + ${fmt(x.extraMB, 3)}`, fmt(x.minWeight), `${fmt(100 * x.negativeShare, 3)}%`, fmt(x.linearPrecision), work]);
  }
  out.push('\nMoving the far cage vertex j (whose mean value weights are the most negative) by d: the region R where its mean value weights are negative moves by |W_ij| |d| (mean W_ij < 0: against d):\n');
  head(['model', 'j', '|R|', 'coordinates', 'max |W_ij| on R', 'mean |W_ij| on R', 'mean W_ij on R']);
  for (const r of results.models) for (const t of TYPES) {
    const x = r.types[t].farVertex;
    row([r.name, r.farVertex, r.regionSize, t, fmt(x.maxMove), fmt(x.meanMove), fmt(x.meanSigned)]);
  }
  out.push('\nThe same drag solved with each (subspace, fast), and the step\'s conditioning at rest:\n');
  head(['model', 'coordinates', 'iterations', 'energy', 'volume error', 'handle error / D', 'shape vs mvc / D', 'solve ms', 'kappa (orthonormal)']);
  for (const r of results.models) for (const t of TYPES) {
    const x = r.types[t];
    row([r.name, t, x.drag.iterations, fmt(x.drag.energy, 4), fmt(x.drag.volumeRelError, 2), fmt(x.drag.handleError), fmt(x.drag.shapeGapToMvc),
      fmt(x.drag.solveMs, 3), x.conditioning.error ? x.conditioning.error : `${fmt(x.conditioning.raw)} (${fmt(x.conditioning.orthonormal)})`]);
  }
  const c = results.models.find((r) => r.id === 'c_bar');
  if (c) {
    out.push('\nSmoothness along the C\'s centre line: the largest second difference of W over h^2 at h and h / 4 (same for a smooth W; x4 for a kink, x16 for a jump):\n');
    head(['coordinates', 'h = 4.4 / 200', 'h = 4.4 / 800', 'growth']);
    for (const t of TYPES) row([t, fmt(c.types[t].smoothness.coarse), fmt(c.types[t].smoothness.fine), `${fmt(c.types[t].smoothness.growth)}x`]);
  }
  return out.join('\n');
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  mkdirSync(args.out, { recursive: true });
  const solver = await loadSolver({ bench: true });
  const timer = new Timer();
  const results = { date: new Date().toISOString(), quick: args.quick, wasm: { build: solver.build, threads: solver.threads() },
    machine: { nproc: os.availableParallelism?.() ?? os.cpus().length, loadBefore: os.loadavg() }, notes: [], models: [] };
  for (const spec of MODELS) {
    const r = runModel(solver, spec, args, console.log);
    if (r) results.models.push(r);
    else results.notes.push(`${spec.name}: ../shared/data/${spec.mesh} or ${spec.cage} is absent; skipped`);
  }
  results.seconds = timer.seconds();
  results.machine.loadAfter = os.loadavg();
  for (const note of results.notes) console.warn(`coordinates experiment: ${note}`);
  writeFileSync(resolve(args.out, 'coordinates.json'), `${JSON.stringify(results, (k, v) => (typeof v === 'number' ? Number(v.toPrecision(6)) : v), 1)}\n`);
  console.log(tables(results));
}

if (process.argv[1] === fileURLToPath(import.meta.url)) await main();
