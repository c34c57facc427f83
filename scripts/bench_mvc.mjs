// Wasm benchmark of the mean value coordinates binding, the same cases as cpp/tools/bench_mvc.cpp:
// the vertices of a capsule inside a 7 x 7 subdivided box cage (296 vertices, 588 triangles).
//   node scripts/bench_mvc.mjs [n ...] [--float32]      (SD_WASM_DIR=build/mvc-wasm to use another build)
// Prints wall and CPU time (the machine may be shared) and point-triangle evaluations per second.
import { computeWeights, loadSolver } from 'subspace-deform';

const args = process.argv.slice(2);
const float32 = args.includes('--float32');
const sizes = args.filter((a) => !a.startsWith('--')).map(Number);
if (sizes.length === 0) sizes.push(5000, 20000, 50000);

const solver = await loadSolver();

// Box cage [-1.7, 1.7] x [-0.7, 0.7]^2 and a capsule (length 2, radius 0.45) along x with about n vertices,
// built by the same procedural shapes as the native benchmark.
const cage = boxCage();

function boxCage() {
  // No binding of make_box is exposed; build the subdivided box here (same layout as make_box(3.4, 1.4, 1.4, 7)).
  const s = 7, half = [1.7, 0.7, 0.7];
  const positions = [], indices = [], ids = new Map();
  const vertex = (p) => {
    const key = p.map((x) => Math.round(x * 1e9)).join(',');
    if (!ids.has(key)) { ids.set(key, positions.length / 3); positions.push(...p); }
    return ids.get(key);
  };
  const face = (origin, u, v) => {
    const id = [];
    for (let j = 0; j <= s; ++j) for (let i = 0; i <= s; ++i) id.push(vertex([0, 1, 2].map((a) => origin[a] + (u[a] * i + v[a] * j) / s)));
    for (let j = 0; j < s; ++j) for (let i = 0; i < s; ++i) {
      const a = id[j * (s + 1) + i], b = id[j * (s + 1) + i + 1], c = id[(j + 1) * (s + 1) + i + 1], d = id[(j + 1) * (s + 1) + i];
      indices.push(a, b, c, a, c, d);
    }
  };
  const lo = half.map((h) => -h), d = half.map((h) => 2 * h);
  const ex = [d[0], 0, 0], ey = [0, d[1], 0], ez = [0, 0, d[2]];
  const add = (p, q) => p.map((x, k) => x + q[k]);
  face(lo, ey, ex); face(add(lo, ez), ex, ey); face(lo, ex, ez); face(add(lo, ey), ez, ex); face(lo, ez, ey); face(add(lo, ex), ey, ez);
  return { positions: new Float64Array(positions), indices: new Uint32Array(indices) };
}

// Capsule vertices (same parameters as capsule_points in bench_mvc.cpp).
function capsulePoints(n) {
  const segments = Math.max(8, Math.floor(Math.sqrt(n / 2)));
  const rings = Math.max(2, Math.floor(segments / 4));
  const cylinder = Math.max(1, Math.floor((n - 2) / segments) - 2 * rings + 1);
  const length = 2, radius = 0.45, profile = [];
  for (let k = 1; k <= rings; ++k) { const phi = (Math.PI / 2) * k / rings; profile.push([-length / 2 - radius * Math.cos(phi), radius * Math.sin(phi)]); }
  for (let k = 1; k < cylinder; ++k) profile.push([-length / 2 + length * k / cylinder, radius]);
  for (let k = rings; k >= 1; --k) { const phi = (Math.PI / 2) * k / rings; profile.push([length / 2 + radius * Math.cos(phi), radius * Math.sin(phi)]); }
  const out = [-length / 2 - radius, 0, 0];
  for (const [x, r] of profile) for (let s = 0; s < segments; ++s) { const t = 2 * Math.PI * s / segments; out.push(x, r * Math.cos(t), r * Math.sin(t)); }
  out.push(length / 2 + radius, 0, 0);
  return new Float64Array(out);
}

console.log(`cage: ${cage.positions.length / 3} vertices, ${cage.indices.length / 3} triangles; storage ${float32 ? 'float32' : 'float64'}`);
for (const n of sizes) {
  const points = capsulePoints(n);
  const cpu0 = process.cpuUsage();
  const result = computeWeights(solver, { positions: points }, cage, { float32, memoryBudgetMB: 4000 });
  const cpu = process.cpuUsage(cpu0);
  const cpuMs = (cpu.user + cpu.system) / 1e3;
  console.log(`n=${String(result.rows).padStart(6)} m=${result.cols}: bind ${result.bindMs.toFixed(1)} ms wall (${cpuMs.toFixed(1)} ms cpu for the call), ` +
    `${(result.evaluations / result.bindMs / 1e3).toFixed(1)} M evals/s wall (${(result.evaluations / cpuMs / 1e3).toFixed(1)} cpu), ` +
    `call ${result.ms.toFixed(1)} ms, min weight ${result.minWeight.toPrecision(3)}, W ${(result.bytes / 1e6).toFixed(1)} MB`);
}
