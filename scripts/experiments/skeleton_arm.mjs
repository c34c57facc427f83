// A figure posed by its skeleton (docs/experiments/skeleton.md; docs/method.md section 5.4): issue 30's arm, the
// built-in bar (a capsule of length 5 in its 28-vertex cage), its left end held and its right end folded down by
// (-1.2, -2.2, 0), solved without and with bones at x = -2, 0, 2 in every Gauss-Newton method and integration.
// Then the soft straightness term (option straightnessWeight) at five weights on the bar and the bar-fine.
// Writes docs/experiments/skeleton_arm.json and the pictures (or --out DIR) and prints the tables of skeleton.md.
//   node scripts/experiments/skeleton_arm.mjs [--out DIR]
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Deformer, loadNodeSolver, makeExample } from 'subspace-deform';
import { Timer } from '../lib/timer.mjs';
import { renderViews } from './render.mjs';
import { readScriptOptions } from '../lib/script_options.mjs';

const ARM = { joints: [[-2, 0, 0], [0, 0, 0], [2, 0, 0]], bones: [[0, 1], [1, 2]] };
const FOLD = [-1.2, -2.2, 0];
const CASES = [
  { label: 'subspace, fast', options: {} },
  { label: 'subspace, exact', options: { jacobian: 'exact' } },
  { label: 'subspace, reduced', options: { integration: 'reduced' } },
  { label: 'full space, fast', options: { method: 'full' } },
];
// (The full space's exact mode is left out: with the skeleton's 20 constraints its iteration takes 1.7 s here.)
const MAX_ITERATIONS = 100;

// The bar's end caps (|x| > 2.2) and targets that hold the left one and fold the right one.
function arm(mesh) {
  const left = [], right = [];
  for (let i = 0; i < mesh.positions.length / 3; ++i) {
    if (mesh.positions[3 * i] < -2.2) left.push(i);
    if (mesh.positions[3 * i] > 2.2) right.push(i);
  }
  const targets = new Float64Array(3 * (left.length + right.length));
  [...left, ...right].forEach((v, row) => {
    for (let a = 0; a < 3; ++a) targets[3 * row + a] = mesh.positions[3 * v + a] + (row >= left.length ? FOLD[a] : 0);
  });
  return { groups: [left, right], targets };
}

// One solve from rest; the skeleton's report measures the same points with and without bones.
function run(solver, bar, options, bones) {
  const d = Deformer.create(solver, bar.mesh, bar.cage);
  try {
    const { groups, targets } = arm(bar.mesh);
    d.setOptions({ maxIterations: MAX_ITERATIONS, ...options });
    if (bones) d.setSkeleton(ARM);
    d.setHandles(groups);
    d.setTargets(targets);
    const timer = new Timer();
    const result = d.solve();
    const ms = timer.ms();
    if (!bones) d.setSkeleton(ARM); // only to measure the same points on the shape solved without it
    const report = d.skeletonReport();
    const last = result.iterations.at(-1);
    return {
      positions: d.positions(), bones, stop: result.stop, iterations: result.iterations.length, ms,
      msPerIteration: ms / Math.max(1, result.iterations.length),
      folded: d.resultWarnings().filter((w) => w.code === 'folded_triangles').length > 0,
      energy: last.energy, laplacianEnergy: last.laplacianEnergy, volumeRelError: last.volumeRelError,
      lengthError: Math.max(...report.bones.map((b) => Math.abs(b.lengthError))),
      straightnessError: Math.max(...report.bones.map((b) => b.straightnessError)),
      hand: Array.from(report.joints.subarray(6, 9)),
    };
  } finally {
    d.dispose();
  }
}

// A drag as the app makes it (on the bar or the bar-fine: the same capsule, so the same handles and bones): the fold
// reached over 60 frames, one iteration per frame, from rest. Returns the
// median ms per frame (after 5 warm-up frames) and the worst length error of any frame.
function drag(solver, bar, bones, example) {
  const d = Deformer.create(solver, bar.mesh, bar.cage);
  try {
    const { groups, targets } = arm(bar.mesh);
    if (bones) d.setSkeleton(ARM);
    d.setHandles(groups);
    const rest = Float64Array.from(targets);
    const moved = groups[0].length;
    for (let r = moved; r < targets.length / 3; ++r) for (let a = 0; a < 3; ++a) rest[3 * r + a] -= FOLD[a];
    const times = [];
    let worst = 0;
    for (let frame = 1; frame <= 60; ++frame) {
      const f = frame / 60;
      d.setTargets(rest.map((x, i) => x + f * (targets[i] - x)));
      const timer = new Timer();
      d.step(1);
      times.push(timer.ms());
      if (bones) worst = Math.max(worst, ...d.skeletonReport().bones.map((b) => Math.abs(b.lengthError)));
    }
    const sorted = times.slice(5).sort((a, b) => a - b);
    return { example, vertices: bar.mesh.positions.length / 3, bones, msPerFrame: sorted[Math.floor(sorted.length / 2)], worstLengthError: worst };
  } finally {
    d.dispose();
  }
}

// The arm with bones solved from rest at each weight of the straightness term (subspace, fast): how straight, and
// what the Laplacian term pays for it.
const WEIGHTS = [0, 1, 3, 10, 30];
function sweep(solver, bar, example) {
  return WEIGHTS.map((straightnessWeight) => {
    const r = run(solver, bar, { straightnessWeight }, true);
    return { example, straightnessWeight, straightnessError: r.straightnessError, laplacianEnergy: r.laplacianEnergy,
      folded: r.folded, lengthError: r.lengthError, iterations: r.iterations, stop: r.stop, positions: r.positions };
  });
}

// --help and unknown flags used to run the whole experiment, and the default folder was ./docs/experiments of
// whatever folder it was started in: it is this repository's.
const { flags } = readScriptOptions('skeleton_arm', process.argv.slice(2), { out: 'string' },
  'usage: node scripts/experiments/skeleton_arm.mjs [--out DIR]   (default: docs/experiments of this repository)');
const out = flags.out ?? fileURLToPath(new URL('../../docs/experiments', import.meta.url));
mkdirSync(out, { recursive: true });
const solver = await loadNodeSolver();
const bar = makeExample(solver, 'bar');
const rows = [];
for (const c of CASES) for (const bones of [false, true]) rows.push({ label: c.label, options: c.options, ...run(solver, bar, c.options, bones) });
const fine = makeExample(solver, 'bar-fine'); // the same capsule, 43k vertices in a 52-vertex cage
const drags = [drag(solver, bar, false, 'bar'), drag(solver, bar, true, 'bar'), drag(solver, fine, false, 'bar-fine'),
  drag(solver, fine, true, 'bar-fine')];
const barWeights = sweep(solver, bar, 'bar');
renderViews(out, 'skeleton_arm_straightness', bar.mesh,
  barWeights.map((w) => ({ label: `straightnessWeight ${w.straightnessWeight}`, positions: w.positions })), arm(bar.mesh),
  { size: 220, pitch: 0 });
const weights = [...barWeights, ...sweep(solver, fine, 'bar-fine')].map(({ positions: _positions, ...w }) => w);
const shapes = rows.map((r) => ({ label: `${r.label}, ${r.bones ? 'bones' : 'no bones'}`, positions: r.positions }));
renderViews(out, 'skeleton_arm', bar.mesh, shapes, arm(bar.mesh), { size: 220, pitch: 0 });
const kept = rows.map(({ positions: _positions, ...r }) => r);
writeFileSync(join(out, 'skeleton_arm.json'), `${JSON.stringify({ skeleton: ARM, fold: FOLD, maxIterations: MAX_ITERATIONS, rows: kept, drags, weights }, null, 1)}\n`);
const g = (x) => Number(x).toPrecision(2);
console.log('| method | bones | length error | straightness error | volume error | energy | folded | iterations (stop) | ms per iteration |');
console.log('|---|---|---|---|---|---|---|---|---|');
for (const dr of drags) {
  console.log(`drag of the ${dr.example} (${dr.vertices} vertices; subspace, one iteration per frame), ${dr.bones ? 'bones' : 'no bones'}: ` +
    `${dr.msPerFrame.toFixed(1)} ms per frame` +
    (dr.bones ? `, worst length error of any frame ${g(dr.worstLengthError)}` : ''));
}
for (const r of rows) {
  console.log(`| ${r.label} | ${r.bones ? 'yes' : 'no'} | ${g(r.lengthError)} | ${g(r.straightnessError)} | ${g(Math.abs(r.volumeRelError))} | ` +
    `${Number(r.energy).toPrecision(4)} | ${r.folded ? 'yes' : 'no'} | ${r.iterations} (${r.stop}) | ${r.msPerIteration.toFixed(1)} |`);
}
console.log('| example | straightnessWeight | straightness error | Laplacian energy | folded | length error | iterations (stop) |');
console.log('|---|---|---|---|---|---|---|');
for (const w of weights) {
  console.log(`| ${w.example} | ${w.straightnessWeight} | ${g(w.straightnessError)} | ${Number(w.laplacianEnergy).toPrecision(3)} | ` +
    `${w.folded ? 'yes' : 'no'} | ${g(w.lengthError)} | ${w.iterations} (${w.stop}) |`);
}
