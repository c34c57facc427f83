#!/usr/bin/env node
// Wasm benchmark of automatic cage generation (docs/cage.md): a 25k-vertex procedural capsule (the same as
// cpp/tools/bench_cage.cpp) and the npm `bunny` (1839 vertices, split twice at edge midpoints: 29k) to
// a K-vertex cage. Usage: node scripts/bench/cage.mjs [K=200]. SD_WASM_DIR selects the build.
import bunny from 'bunny';
import { CAGE_LIMITS, generateCage, loadSolver, meshFromCells } from 'subspace-deform';
import { Timer } from '../lib/timer.mjs';
import { numberOption, readScriptOptions } from '../lib/script_options.mjs';

// Splits every triangle into four at its edge midpoints (shared midpoints welded): 4x the faces.
function subdivide(mesh) {
  const positions = Array.from(mesh.positions);
  const midpoint = new Map();
  const mid = (a, b) => {
    const key = a < b ? `${a},${b}` : `${b},${a}`;
    let id = midpoint.get(key);
    if (id === undefined) {
      id = positions.length / 3;
      for (let k = 0; k < 3; ++k) positions.push(0.5 * (positions[3 * a + k] + positions[3 * b + k]));
      midpoint.set(key, id);
    }
    return id;
  };
  const indices = [];
  for (let f = 0; f < mesh.indices.length; f += 3) {
    const [a, b, c] = mesh.indices.slice(f, f + 3);
    const ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
    indices.push(a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca);
  }
  return { positions: new Float64Array(positions), indices: new Uint32Array(indices) };
}

// The capsule of cpp/tools/bench_cage.cpp (make_capsule(3.0, 0.6, 30, 60, 208) is not bound to JS):
// rings of `segments` vertices between two poles, 24754 vertices.
function capsule() {
  const length = 3.0, radius = 0.6, rings = 30, cylinder = 60, segments = 208;
  const positions = [];
  const ring = [];
  const addRing = (x, r) => {
    const start = positions.length / 3;
    for (let s = 0; s < segments; ++s) {
      const t = (2 * Math.PI * s) / segments;
      positions.push(x, r * Math.cos(t), r * Math.sin(t));
    }
    ring.push(start);
  };
  positions.push(-length / 2 - radius, 0, 0);  // pole 0
  for (let i = 1; i <= rings; ++i) {
    const a = (Math.PI / 2) * (1 - i / rings);
    addRing(-length / 2 - radius * Math.sin(a), radius * Math.cos(a));
  }
  for (let i = 1; i < cylinder; ++i) addRing(-length / 2 + (length * i) / cylinder, radius);
  for (let i = 0; i < rings; ++i) {
    const a = (Math.PI / 2) * (i / rings);
    addRing(length / 2 + radius * Math.sin(a), radius * Math.cos(a));
  }
  const pole1 = positions.length / 3;
  positions.push(length / 2 + radius, 0, 0);
  const indices = [];
  for (let s = 0; s < segments; ++s) indices.push(0, ring[0] + ((s + 1) % segments), ring[0] + s);
  for (let r = 0; r + 1 < ring.length; ++r)
    for (let s = 0; s < segments; ++s) {
      const a = ring[r] + s, b = ring[r] + ((s + 1) % segments), c = ring[r + 1] + ((s + 1) % segments), d = ring[r + 1] + s;
      indices.push(a, b, c, a, c, d);
    }
  const last = ring[ring.length - 1];
  for (let s = 0; s < segments; ++s) indices.push(pole1, last + s, last + ((s + 1) % segments));
  return { positions: new Float64Array(positions), indices: new Uint32Array(indices) };
}

// A word for K died in generateCage with an uncaught InputError's stack.
const { positionals } = readScriptOptions('bench/cage', process.argv.slice(2), {}, 'usage: node scripts/bench/cage.mjs [K=200]', { maxPositionals: 1 });
const K = numberOption('bench/cage', positionals[0] ?? '200', 'K', { integer: true, ...CAGE_LIMITS.vertices });
const solver = await loadSolver();
const cases = [
  ['capsule', capsule()],
  ['bunny (subdivided twice)', subdivide(subdivide(meshFromCells(bunny)))],
];
for (const [name, mesh] of cases) {
  const timer = new Timer();
  const cpu0 = process.cpuUsage();
  const cage = generateCage(solver, mesh, { vertices: K });
  const ms = timer.ms();
  const cpuMs = process.cpuUsage(cpu0).user / 1e3;  // the machine may be shared: CPU time is the steadier number
  console.log(`${name}: ${mesh.positions.length / 3} vertices -> cage ${cage.positions.length / 3} vertices, ` +
    `volume ratio ${cage.volumeRatio.toFixed(3)}, clearance ${cage.minClearance.toPrecision(3)}, ` +
    `${cage.attempts} attempt(s), ${ms.toFixed(0)} ms wall, ${cpuMs.toFixed(0)} ms CPU`);
}
