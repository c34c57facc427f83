// The real-model table of scripts/bench.mjs (docs/benchmarks.md, "Real models in their own cages"): each model
// of ../shared/data with its own cage, fixed within 5% of one end of its longest axis, the other end pulled
// sideways (the second-longest axis) by 8% of the diagonal and turned 20 degrees about the third axis (the scene of
// cpp/tools/bench_models.cpp). Solved to convergence with full and reduced integration: in wasm by the command-line
// tool (the threaded Node build, the library's default) on a scene file, natively by bench_models.
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { readMesh } from 'subspace-deform';

export const MODELS = ['handbones', 'gargoyle', 'moomoo', 'cow', 'spikybox', 'boy'];
const INTEGRATIONS = ['full', 'reduced'];
const cli = new URL('../deform.mjs', import.meta.url).pathname;

/** The models whose mesh and cage are in `dataDir` (none without ../shared/data). */
export function availableModels(dataDir, names = MODELS) {
  return names.filter((name) => existsSync(join(dataDir, `${name}.obj`)) && existsSync(join(dataDir, `${name}_cage.obj`)));
}

// The drag scene of bench_models as a scene file's handles: the fixed end, then the pulled and turned end.
export function dragHandles(mesh) {
  const p = mesh.positions, n = p.length / 3;
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < 3 * n; ++i) {
    lo[i % 3] = Math.min(lo[i % 3], p[i]);
    hi[i % 3] = Math.max(hi[i % 3], p[i]);
  }
  const extent = hi.map((h, a) => h - lo[a]);
  const axes = [0, 1, 2].sort((a, b) => extent[b] - extent[a]);
  const diagonal = Math.hypot(...extent);
  const fixed = [], moved = [];
  for (let i = 0; i < n; ++i) {
    const u = (p[3 * i + axes[0]] - lo[axes[0]]) / extent[axes[0]];
    if (u < 0.05) fixed.push(i);
    else if (u > 0.95) moved.push(i);
  }
  const centre = [0, 1, 2].map((a) => moved.reduce((s, i) => s + p[3 * i + a], 0) / moved.length);
  const unit = (a) => [0, 1, 2].map((k) => (k === a ? 1 : 0));
  return [
    { vertices: fixed },
    { vertices: moved, translate: unit(axes[1]).map((v) => 0.08 * diagonal * v),
      rotate: { axis: unit(axes[2]), angle: (20 * Math.PI) / 180, center: centre } },
  ];
}

const median = (values) => {
  const s = [...values].sort((a, b) => a - b);
  return s.length ? (s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2])) : NaN;
};

// One converged solve in wasm through the command-line tool: its report, summarised.
function runWasm(scenePath, integration, dir) {
  const report = join(dir, `report_${integration}.json`);
  const r = spawnSync(process.execPath, [cli, 'deform', scenePath, '--integration', integration, '--report', report, '--quiet'],
    { encoding: 'utf8', maxBuffer: 1 << 24 });
  if (r.status !== 0) throw new Error(`deform failed on ${scenePath}: ${r.stderr}`);
  const rep = JSON.parse(readFileSync(report, 'utf8'));
  return {
    iterations: rep.iterationCount, converged: rep.converged, stop: rep.stop, solveMs: rep.solveMs,
    msPerIteration: median(rep.iterations.map((it) => it.ms)),
    productsPerIteration: median(rep.iterations.map((it) => it.products)),
    passesPerIteration: median(rep.iterations.map((it) => it.passes)),
    fullEnergy: rep.reducedIntegration?.fullEnergy ?? rep.energy,
    reliable: rep.reducedIntegration?.reliable ?? true,
  };
}

// bench_models prints one JSON line per integration, then the largest distance between the two converged shapes over
// the diagonal (the reduced solve finished on every vertex: docs/method.md section 17.3), kept as `reducedVsFull`.
function runNative(bin, meshPath, cagePath) {
  const text = execFileSync(bin, [meshPath, cagePath, '--integration', 'both', '--frames', '5'], { encoding: 'utf8', maxBuffer: 1 << 24 });
  const lines = text.trim().split('\n').map((line) => JSON.parse(line));
  const byIntegration = Object.fromEntries(lines.filter((l) => l.integration).map((l) => [l.integration, l]));
  return { ...byIntegration, reducedVsFull: lines.find((l) => 'reducedVsFull' in l)?.reducedVsFull ?? NaN };
}

/**
 * Runs each available model in wasm and, when `nativeBin` is given, natively.
 * @returns {{ name: string, n: number, m: number, wasm: object, native: object|null }[]}
 */
export async function runModels({ solver, nativeBin, dataDir, names, log }) {
  const dir = mkdtempSync(join(tmpdir(), 'sd-bench-models-'));
  try {
    const rows = [];
    for (const name of availableModels(dataDir, names)) {
      const meshPath = join(dataDir, `${name}.obj`), cagePath = join(dataDir, `${name}_cage.obj`);
      const mesh = readMesh(solver, readFileSync(meshPath), `${name}.obj`);
      const scenePath = join(dir, `${name}.json`);
      // A scene names only files beside it (or below): the models are linked into its folder.
      symlinkSync(resolve(meshPath), join(dir, `${name}.obj`));
      symlinkSync(resolve(cagePath), join(dir, `${name}_cage.obj`));
      writeFileSync(scenePath, JSON.stringify({ mesh: `${name}.obj`, cage: `${name}_cage.obj`, handles: dragHandles(mesh) }));
      const wasm = Object.fromEntries(INTEGRATIONS.map((integration) => [integration, runWasm(scenePath, integration, dir)]));
      const native = nativeBin ? runNative(nativeBin, meshPath, cagePath) : null;
      const m = native?.full?.m ?? NaN;
      log(`models ${name}: full ${wasm.full.msPerIteration.toFixed(1)} ms/it, ${wasm.full.productsPerIteration} products/it (wasm)` +
        `${native ? `; ${native.full.msPerIteration.toFixed(1)} ms/it native` : ''}`);
      rows.push({ name, n: mesh.positions.length / 3, m, wasm, native });
    }
    return rows;
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

const fixed = (v, digits) => (Number.isFinite(v) ? v.toFixed(digits) : '-');

/** Markdown table: per model and integration, wasm and native side by side. */
export function formatModels(rows) {
  const lines = [
    '| model | n x m | integration | wasm: iterations, converged, solve ms | wasm ms/it | products/it | W passes/it | native: iterations, solve ms | native ms/it | reliable rule | reduced vs full shape (native) |',
    '|---|---|---|---|---|---|---|---|---|---|---|',
  ];
  for (const { name, n, m, wasm, native } of rows) {
    for (const integration of INTEGRATIONS) {
      const w = wasm[integration], nat = native?.[integration];
      lines.push(`| ${name} | ${n} x ${fixed(m, 0)} | ${integration} | ${w.iterations}, ${w.converged ? 'yes' : `no (${w.stop})`}, ${fixed(w.solveMs, 0)} ` +
        `| ${fixed(w.msPerIteration, 1)} | ${w.productsPerIteration} | ${w.passesPerIteration} ` +
        `| ${nat ? `${nat.iterations}, ${fixed(nat.solveMs, 0)}` : '-'} | ${fixed(nat?.msPerIteration, 1)} ` +
        `| ${integration === 'reduced' ? (w.reliable ? 'yes' : 'no') : ''} ` +
        `| ${integration === 'reduced' && Number.isFinite(native?.reducedVsFull) ? native.reducedVsFull.toExponential(1) : ''} |`);
    }
  }
  return lines.join('\n');
}
