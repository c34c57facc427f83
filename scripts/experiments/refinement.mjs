#!/usr/bin/env node
// The same bend at four mesh resolutions (docs/experiments/refinement.md): a capsule (length 4, radius 0.5) in
// the built-in bar's 28-vertex cage, the ends x < -2.3 fixed and x > 2.3 moved by (0, -1.2, 0), solved to
// convergence at about 4.7k, 19k, 76k and 307k vertices with each energy weighting. The cage, hence the
// subspace, is the same in every row: W is the same continuous function sampled more finely, so the shapes are
// compared as the cage maps them, through the coarsest mesh's W applied to each solve's deformed cage, and along
// the centre line (the images of points (x, 0, 0)).
//   node scripts/experiments/refinement.mjs [--scales 1,2,4,8] [--json docs/experiments/refinement.json]
import { writeFileSync } from 'node:fs';
import { Deformer, computeWeights, loadSolver, makeExample } from 'subspace-deform';
import { numberOption, readScriptOptions } from '../lib/script_options.mjs';
import { Timer } from '../lib/timer.mjs';

const CENTRE_X = [-1, -0.5, 0, 0.5, 1];

/** make_capsule of cpp/core/mesh/shapes.cpp: poles on the x axis, `rings` per hemisphere, closed, outward. */
export function capsule(length, radius, rings, cylinderRings, segments) {
  const profile = [];
  for (let k = 1; k <= rings; ++k) {
    const phi = (Math.PI / 2) * k / rings;
    profile.push([-length / 2 - radius * Math.cos(phi), radius * Math.sin(phi)]);
  }
  for (let k = 1; k < cylinderRings; ++k) profile.push([-length / 2 + (length * k) / cylinderRings, radius]);
  for (let k = rings; k >= 1; --k) {
    const phi = (Math.PI / 2) * k / rings;
    profile.push([length / 2 + radius * Math.cos(phi), radius * Math.sin(phi)]);
  }
  const positions = [-length / 2 - radius, 0, 0];
  for (const [x, r] of profile) {
    for (let s = 0; s < segments; ++s) positions.push(x, r * Math.cos((2 * Math.PI * s) / segments), r * Math.sin((2 * Math.PI * s) / segments));
  }
  const last = 1 + profile.length * segments;
  positions.push(length / 2 + radius, 0, 0);
  const id = (r, s) => 1 + r * segments + (s % segments);
  const indices = [];
  for (let s = 0; s < segments; ++s) indices.push(0, id(0, s + 1), id(0, s));
  for (let r = 0; r + 1 < profile.length; ++r) {
    for (let s = 0; s < segments; ++s) indices.push(id(r, s), id(r, s + 1), id(r + 1, s + 1), id(r, s), id(r + 1, s + 1), id(r + 1, s));
  }
  for (let s = 0; s < segments; ++s) indices.push(last, id(profile.length - 1, s), id(profile.length - 1, s + 1));
  return { positions: new Float64Array(positions), indices: new Uint32Array(indices) };
}

const capsuleAt = (scale) => capsule(4, 0.5, 10 * scale, 40 * scale, 80 * scale);

/** The bend solved on the capsule at `scale`; returns the deformed cage and the solve's numbers. */
function bend(solver, cage, scale, weighting) {
  const mesh = capsuleAt(scale);
  const deformer = Deformer.create(solver, mesh, cage);
  try {
    deformer.setOptions({ weighting });
    const fixed = [], moving = [];
    for (let i = 0; i < mesh.positions.length / 3; ++i) {
      if (mesh.positions[3 * i] < -2.3) fixed.push(i);
      if (mesh.positions[3 * i] > 2.3) moving.push(i);
    }
    deformer.setHandles([fixed, moving]);
    const targets = [];
    for (const v of fixed) targets.push(...mesh.positions.subarray(3 * v, 3 * v + 3));
    for (const v of moving) targets.push(mesh.positions[3 * v], mesh.positions[3 * v + 1] - 1.2, mesh.positions[3 * v + 2]);
    deformer.setTargets(new Float64Array(targets));
    const timer = new Timer();
    const result = deformer.solve();
    const last = result.iterations.at(-1);
    return {
      vertices: mesh.positions.length / 3, weighting, converged: result.converged, iterations: result.iterations.length,
      energy: last.energy, volumeRelError: last.volumeRelError, solveMs: timer.ms(), cage: deformer.cagePositions(),
    };
  } finally {
    deformer.dispose();
  }
}

/** X = W P for a cage's weights W (n x m, row-major) and deformed cage P. */
function apply(weights, cage) {
  const { weights: data, rows, cols } = weights;
  const out = new Float64Array(3 * rows);
  for (let i = 0; i < rows; ++i) {
    for (let j = 0; j < cols; ++j) for (let d = 0; d < 3; ++d) out[3 * i + d] += data[i * cols + j] * cage[3 * j + d];
  }
  return out;
}

function largestDistance(a, b) {
  let worst = 0;
  for (let i = 0; i < a.length; i += 3) worst = Math.max(worst, Math.hypot(a[i] - b[i], a[i + 1] - b[i + 1], a[i + 2] - b[i + 2]));
  return worst;
}

async function main() {
  // A word for a scale used to reach the mesh builder ("mesh has no faces"); scale 16 is about 1.2M vertices.
  const { flags } = readScriptOptions('refinement', process.argv.slice(2), { scales: 'string', json: 'string' },
    'usage: node scripts/experiments/refinement.mjs [--scales 1,2,4,8] [--json docs/experiments/refinement.json]');
  const scales = (flags.scales ?? '1,2,4,8').split(',').map((s) => numberOption('refinement', s, '--scales', { integer: true, min: 1, max: 16 }));
  const solver = await loadSolver();
  const cage = makeExample(solver, 'bar').cage;
  const coarse = capsuleAt(1);
  const diagonal = Math.hypot(5, 1, 1); // the coarse capsule's bounding box: 5 x 1 x 1
  const coarseW = computeWeights(solver, coarse, cage);
  const centreW = computeWeights(solver, { positions: new Float64Array(CENTRE_X.flatMap((x) => [x, 0, 0])) }, cage);
  const rows = [];
  for (const weighting of ['area', 'uniform']) {
    let previous = null;
    for (const scale of scales) {
      const r = bend(solver, cage, scale, weighting);
      const shape = apply(coarseW, r.cage);
      const centre = apply(centreW, r.cage);
      const row = { ...r, centreY: CENTRE_X.map((_, k) => centre[3 * k + 1]),
        differenceFromCoarser: previous ? largestDistance(shape, previous) / diagonal : null };
      delete row.cage;
      rows.push(row);
      previous = shape;
      console.log(`${weighting.padEnd(7)} ${String(row.vertices).padStart(7)}: centre line y ${row.centreY.map((y) => y.toFixed(3)).join(' / ')}, ` +
        `${row.differenceFromCoarser === null ? '' : `${row.differenceFromCoarser.toExponential(1)} of the diagonal from the coarser, `}` +
        `${row.iterations} iterations${row.converged ? '' : ' (NOT converged)'}, energy ${row.energy.toExponential(2)}, volume error ${row.volumeRelError.toExponential(1)}`);
    }
  }
  if (flags.json) writeFileSync(flags.json, JSON.stringify({ date: new Date().toISOString(), centreX: CENTRE_X, rows }, null, 2) + '\n');
}

main().catch((error) => {
  console.error(`refinement: ${error.message}`);
  process.exit(1);
});
