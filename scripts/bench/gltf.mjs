#!/usr/bin/env node
// Wasm benchmark of the glTF path (docs/library.md#vertex-layout) on a large model as exporters write it:
// the mesh (an OBJ/OFF/PLY/STL file; default: the largest in ../shared/data, else a 25k-vertex procedural
// ellipsoid) is written as a .glb whose every face has its own three corners (a non-indexed, flat-shaded
// export: 3 x the vertices), then read back (readModel: glTF-Transform and the checks before allocating),
// checked (checkMesh: the layout welds the corners and checks the solver mesh), bound without a cage
// (Deformer.create in the full space: layout, Laplacian, volume parts), solved for a small pull in the subspace
// of its bounding box as cage and written back in its own layout (writeModel); the solve is compared with the
// same solve on the indexed mesh. Prints the counts and the median of 3 runs of each step.
// Usage: node scripts/bench/gltf.mjs [mesh file]. SD_WASM_BUILD=single selects the single-threaded build.
import { existsSync, readdirSync, readFileSync, statSync } from 'node:fs';
import { basename, join } from 'node:path';
import { Document, WebIO } from '@gltf-transform/core';
import { Deformer, checkMesh, loadSolver, readMesh, readModel, writeModel } from 'subspace-deform';
import { Timer } from '../lib/timer.mjs';

const sharedData = new URL('../../../shared/data/', import.meta.url).pathname;

function largestSharedMesh() {
  if (!existsSync(sharedData)) return null;
  const files = readdirSync(sharedData).filter((f) => /\.(obj|off|ply|stl)$/i.test(f)).map((f) => join(sharedData, f));
  return files.sort((a, b) => statSync(b).size - statSync(a).size)[0] ?? null;
}

// An ellipsoid of rings x segments quads between two poles (closed, indexed).
function ellipsoid(rings = 120, segments = 208) {
  const positions = [0, -1, 0];
  for (let r = 1; r < rings; ++r) {
    const theta = (Math.PI * r) / rings;
    for (let s = 0; s < segments; ++s) {
      const phi = (2 * Math.PI * s) / segments;
      positions.push(0.6 * Math.sin(theta) * Math.cos(phi), -Math.cos(theta), 0.4 * Math.sin(theta) * Math.sin(phi));
    }
  }
  positions.push(0, 1, 0);
  const top = positions.length / 3 - 1, at = (r, s) => 1 + (r - 1) * segments + (s % segments);
  const indices = [];
  for (let s = 0; s < segments; ++s) {
    indices.push(0, at(1, s), at(1, s + 1), top, at(rings - 1, s + 1), at(rings - 1, s));
    for (let r = 1; r < rings - 1; ++r) indices.push(at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s), at(r + 1, s + 1), at(r, s + 1));
  }
  return { positions: new Float64Array(positions), indices: new Uint32Array(indices) };
}

// A .glb of the mesh with every face's corners their own vertices (float32 positions, no index).
async function perCornerGlb(mesh) {
  const corners = new Float32Array(3 * mesh.indices.length);
  mesh.indices.forEach((v, c) => corners.set(mesh.positions.subarray(3 * v, 3 * v + 3), 3 * c));
  const document = new Document();
  const buffer = document.createBuffer();
  const position = document.createAccessor().setType('VEC3').setArray(corners).setBuffer(buffer);
  const primitive = document.createPrimitive().setAttribute('POSITION', position);
  document.createScene().addChild(document.createNode('model').setMesh(document.createMesh('model').addPrimitive(primitive)));
  return new WebIO().writeBinary(document);
}

// The bounding box grown by a tenth of its diagonal on every side: an 8-vertex cage.
function boxAround(positions) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  positions.forEach((x, i) => {
    lo[i % 3] = Math.min(lo[i % 3], x);
    hi[i % 3] = Math.max(hi[i % 3], x);
  });
  const margin = 0.1 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const corner = (k) => [0, 1, 2].map((a) => ((k >> a) & 1 ? hi[a] + margin : lo[a] - margin));
  const cage = { positions: new Float64Array(Array.from({ length: 8 }, (_, k) => corner(k)).flat()) };
  // Corner k has x = bit 0, y = bit 1, z = bit 2; two outward triangles per side.
  cage.indices = new Uint32Array([0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2,
    1, 3, 7, 1, 7, 5]);
  return cage;
}

async function median(run) {
  const times = [];
  let value;
  for (let k = 0; k < 3; ++k) {
    const timer = new Timer();
    value = await run();
    times.push(timer.ms());
  }
  return { ms: times.sort((a, b) => a - b)[1], value };
}

const solver = await loadSolver();
const path = process.argv[2] ?? largestSharedMesh();
const source = path ? readMesh(solver, readFileSync(path), basename(path)) : ellipsoid();
const name = path ? basename(path) : 'ellipsoid';
const glb = await perCornerGlb(source);
const read = await median(() => readModel(solver, glb, `${name}.glb`));
const { mesh } = read.value;
const check = await median(() => checkMesh(solver, mesh));
const { layout } = check.value.summary;
const bind = await median(() => {
  const d = Deformer.create(solver, mesh, null);
  d.dispose();
});
// A pull of the top tenth along x by 5% of the height, the bottom tenth fixed, in the full space.
const ys = Array.from({ length: mesh.positions.length / 3 }, (_, i) => mesh.positions[3 * i + 1]);
const lo = ys.reduce((a, b) => Math.min(a, b)), hi = ys.reduce((a, b) => Math.max(a, b)), span = hi - lo;
const bottom = [], top = [];
const seen = new Set();
ys.forEach((y, i) => {
  const point = `${mesh.positions[3 * i]},${y},${mesh.positions[3 * i + 2]}`;
  if (seen.has(point)) return;  // one file vertex per welded point: a point in two groups is refused
  seen.add(point);
  if (y < lo + 0.1 * span) bottom.push(i);
  else if (y > hi - 0.1 * span) top.push(i);
});
const d = Deformer.create(solver, mesh, boxAround(mesh.positions));
d.setOptions({ method: 'subspace' });
d.setHandles([bottom, top]);
const targetsOf = (fixed, moved) => Float64Array.from([...fixed, ...moved].flatMap((v, r) => [0, 1, 2].map((a) => mesh.positions[3 * v + a] + (r >= fixed.length && a === 0 ? 0.05 * span : 0))));
d.setTargets(targetsOf(bottom, top));
const solveTimer = new Timer();
const result = d.solve();
const solveMs = solveTimer.ms();
const rest = d.restPartVolumes(), now = d.partVolumes();
const worstVolume = Math.max(...rest.map((v, k) => Math.abs(now[k] - v) / Math.abs(v)));
const write = await median(() => writeModel(solver, read.value, d.positions(), `${name}-deformed.glb`, { solverOfFile: d.layout().solverOfFile }));
// The same solve on the indexed mesh as read (its corners are the .glb's vertices: corner c is vertex
// indices[c]), with the same targets: how far the seam-split file's result is from it, over the diagonal
// (float32 positions in the .glb against the file's own, and the solver's vertex order).
const indexed = Deformer.create(solver, source, boxAround(mesh.positions));
indexed.setOptions({ method: 'subspace' });
indexed.setHandles([bottom.map((c) => source.indices[c]), top.map((c) => source.indices[c])]);
indexed.setTargets(targetsOf(bottom, top));
indexed.solve();
const X = d.positions(), Y = indexed.positions();
let gap = 0;
for (let c = 0; c < mesh.indices.length; ++c) {
  for (let a = 0; a < 3; ++a) gap = Math.max(gap, Math.abs(X[3 * c + a] - Y[3 * source.indices[c] + a]));
}
const diagonal = Math.hypot(...[0, 1, 2].map((a) => {
  const xs = Array.from({ length: mesh.positions.length / 3 }, (_, i) => mesh.positions[3 * i + a]);
  return xs.reduce((p, q) => Math.max(p, q)) - xs.reduce((p, q) => Math.min(p, q));
}));
indexed.dispose();
d.dispose();

console.log(`${name} as a per-corner .glb: ${(glb.byteLength / 2 ** 20).toFixed(1)} MiB, ${layout.fileVertices} file vertices, ` +
  `${mesh.indices.length / 3} triangles -> ${layout.solverVertices} solver vertices (welded ${layout.welded})`);
console.log(`  readModel ${read.ms.toFixed(0)} ms, checkMesh ${check.ms.toFixed(0)} ms, Deformer.create (full space) ${bind.ms.toFixed(0)} ms, ` +
  `writeModel ${write.ms.toFixed(0)} ms (${(write.value.byteLength / 2 ** 20).toFixed(1)} MiB)`);
console.log(`  solve (subspace of an 8-vertex box cage, ${result.iterations.length} iterations, ${result.stopReason}) ${solveMs.toFixed(0)} ms, ` +
  `worst part volume change ${worstVolume.toExponential(2)}`);
console.log(`  the same solve on the indexed mesh: max difference ${(gap / diagonal).toExponential(2)} of the diagonal`);
