#!/usr/bin/env node
// Thread scaling on the real models (docs/benchmarks.md, "Threads on the real models"): each model of
// ../shared/data in its own cage, in the drag scene of cpp/tools/bench_models.cpp, with each thread count: the bind,
// the converged solve from rest and a drag of F frames (one step() each, as the app's worker does), with full and
// reduced integration, in wasm (the threaded Node build, in this process) and natively (bench_models --threads).
// The threads' rules promise the same bits at every thread count; this checks it on real models: the same
// iterations, products and merits in wasm, the same shape hashes natively. It exits 1 when a count differs.
//
//   node scripts/bench/model_threads.mjs [--models boy,handbones,cow] [--threads 1,2,4,8,16] [--frames 10]
//        [--data DIR] [--native-bin PATH] [--no-wasm] [--no-native] [--json FILE]
// The default thread counts are 1, 2, 4, 8 and 16 up to the machine's cores.
import { execFileSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Deformer, loadSolver, readMesh } from 'subspace-deform';
import { MODELS, availableModels, dragHandles } from './models.mjs';
import { defaultThreadCounts } from './scaling.mjs';
import { namesOption, numberOption, readScriptOptions } from '../lib/script_options.mjs';

const HELP = `usage: node scripts/bench/model_threads.mjs [--models boy,handbones,cow] [--threads 1,2,4,8,16] [--frames 10]
       [--data DIR] [--native-bin PATH] [--no-wasm] [--no-native] [--json FILE]
  models: ${MODELS.join(', ')} (those in DIR, default ../shared/data)`;
const root = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..');
// Unknown flags used to be ignored, and a misspelt model measured nothing with exit 0.
const { flags } = readScriptOptions('model_threads', process.argv.slice(2), {
  models: 'string', threads: 'string', frames: 'string', data: 'string', 'native-bin': 'string', 'no-wasm': 'boolean',
  'no-native': 'boolean', json: 'string',
}, HELP);
const names = namesOption('model_threads', flags.models ?? 'boy,handbones,cow', '--models', MODELS);
const threadCounts = (flags.threads ?? defaultThreadCounts(os.availableParallelism()).join(','))
  .split(',').map((t) => numberOption('model_threads', t, '--threads', { integer: true, min: 1, max: 1024 }));
const frames = numberOption('model_threads', flags.frames ?? '10', '--frames', { integer: true, min: 1 });
const dataDir = resolve(flags.data ?? join(root, '..', 'shared', 'data'));
const nativeBin = flags['no-native'] ? null : resolve(flags['native-bin'] ?? join(root, 'build', 'native', 'bench_models'));
const runWasm = !flags['no-wasm'];
const jsonPath = flags.json ?? '';

/** A short SHA-1 of bytes or text: equal inputs give equal digests. */
const digest = (data) => createHash('sha1').update(data).digest('hex').slice(0, 16);

const median = (values) => {
  const s = [...values].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};

/**
 * The drag of tools/drag_scene.h, from models.mjs' handles (the fixed end; the moved end's pull and turn):
 * groups [fixed end, moved end] and targets(t) at a fraction t of the pull.
 */
function dragScene(mesh) {
  const positions = mesh.positions;
  const [{ vertices: fixed }, { vertices: moved, translate, rotate }] = dragHandles(mesh);
  const turn = rotate.axis.indexOf(1);
  const a = (turn + 1) % 3, b = (turn + 2) % 3; // the plane of the turn, right-handed about its axis
  const targets = (t) => {
    const out = new Float64Array(3 * (fixed.length + moved.length));
    fixed.forEach((v, k) => out.set(positions.subarray(3 * v, 3 * v + 3), 3 * k));
    const c = Math.cos(t * rotate.angle), s = Math.sin(t * rotate.angle);
    moved.forEach((v, k) => {
      const p = [0, 1, 2].map((d) => positions[3 * v + d] - rotate.center[d]);
      const q = [...p];
      q[a] = c * p[a] - s * p[b];
      q[b] = s * p[a] + c * p[b];
      const row = 3 * (fixed.length + k);
      for (let d = 0; d < 3; ++d) out[row + d] = rotate.center[d] + q[d] + t * translate[d];
    });
    return out;
  };
  return { groups: [fixed, moved], targets };
}

/** One model at one thread count in wasm: bind, then per integration the converged solve and the drag. */
function wasmRun(solver, mesh, cage, threads) {
  solver.setThreads(threads);
  let t0 = performance.now();
  const d = Deformer.create(solver, mesh, cage);
  const bindMs = performance.now() - t0;
  try {
    const scene = dragScene(mesh);
    d.setHandles(scene.groups);
    const out = { bindMs };
    for (const integration of ['full', 'reduced']) {
      d.setOptions({ integration });
      d.reset();
      d.setTargets(scene.targets(1));
      t0 = performance.now();
      const r = d.solve();
      const solveMs = performance.now() - t0;
      const frameMs = [];
      for (let f = 1; f <= frames; ++f) {
        d.setTargets(scene.targets(1 + (0.25 * f) / frames));
        t0 = performance.now();
        d.step(1);
        frameMs.push(performance.now() - t0);
      }
      // What the threads must not change: the solve's products and merits, and the dragged shape.
      const trace = JSON.stringify(r.iterations.map((it) => [it.products, it.merit]));
      const check = `${digest(new Uint8Array(d.positions().buffer))}/${digest(trace)}`;
      out[integration] = { iterations: r.iterations.length, converged: r.converged, stop: r.stop, solveMs,
        msPerIteration: median(r.iterations.map((it) => it.ms)), frameMs: median(frameMs), check };
    }
    return out;
  } finally {
    d.dispose();
  }
}

/** One model at one thread count natively: bench_models' JSON lines. */
function nativeRun(meshPath, cagePath, threads) {
  const text = execFileSync(nativeBin, [meshPath, cagePath, '--integration', 'both', '--frames', String(frames), '--threads', String(threads)],
    { encoding: 'utf8', maxBuffer: 1 << 24 });
  const lines = text.trim().split('\n').map((line) => JSON.parse(line));
  const out = { bindMs: lines.find((l) => 'bindMs' in l).bindMs };
  for (const l of lines.filter((x) => x.integration)) out[l.integration] = { ...l, check: `${l.shapeHash}/${l.dragHash}` };
  return out;
}

const fixed = (v, digits = 1) => (Number.isFinite(v) ? v.toFixed(digits) : '-');

const models = availableModels(dataDir, names);
if (!models.length) {
  // Asked to measure and measuring nothing is a failure, not a success.
  console.error(`model_threads: none of ${names.join(', ')} is in ${dataDir}: nothing to measure`);
  process.exit(1);
}
if (nativeBin && !existsSync(nativeBin)) throw new Error(`${nativeBin} is missing: bash scripts/build.sh --native (or --no-native)`);
const solver = runWasm ? await loadSolver({ threads: Math.max(...threadCounts) }) : null;
const results = [];
let differ = false;
console.log(`threads ${threadCounts.join(', ')} on ${os.availableParallelism()} cores (${os.cpus()[0]?.model}), load ${os.loadavg()[0].toFixed(2)}, ${frames} drag frames`);
console.log('| model (n x m) | build | integration | threads | bind ms | solve ms (iterations) | ms / iteration | drag frame ms | same bits |');
console.log('|---|---|---|---|---|---|---|---|---|');
for (const name of models) {
  const meshPath = join(dataDir, `${name}.obj`), cagePath = join(dataDir, `${name}_cage.obj`);
  const builds = [];
  if (solver) {
    const mesh = readMesh(solver, readFileSync(meshPath), `${name}.obj`), cage = readMesh(solver, readFileSync(cagePath), `${name}_cage.obj`);
    builds.push(['wasm', (t) => wasmRun(solver, mesh, cage, t)]);
  }
  if (nativeBin) builds.push(['native', (t) => nativeRun(meshPath, cagePath, t)]);
  for (const [build, run] of builds) {
    const runs = threadCounts.map((threads) => ({ threads, ...run(threads) }));
    for (const integration of ['full', 'reduced']) {
      const first = runs[0][integration].check;
      for (const r of runs) {
        const x = r[integration], same = x.check === first;
        differ ||= !same;
        const size = x.n ? `${x.n} x ${x.m}` : '';
        console.log(`| ${name}${size ? ` (${size})` : ''} | ${build} | ${integration} | ${r.threads} | ${fixed(r.bindMs, 0)} | ${fixed(x.solveMs, 0)} (${x.iterations}${x.converged ? '' : `, ${x.stop}`}) ` +
          `| ${fixed(x.msPerIteration)} | ${fixed(x.frameMs)} | ${same ? 'yes' : `NO (${x.check} vs ${first})`} |`);
        results.push({ model: name, build, integration, threads: r.threads, bindMs: r.bindMs, solveMs: x.solveMs, iterations: x.iterations,
          msPerIteration: x.msPerIteration, frameMs: x.frameMs, check: x.check });
      }
    }
  }
}
if (jsonPath) writeFileSync(jsonPath, JSON.stringify({ cores: os.availableParallelism(), cpu: os.cpus()[0]?.model, threadCounts, frames, results }, null, 1));
if (differ) {
  console.log('model_threads: some thread counts gave other bits (NO above): the threads\' rules are broken');
  process.exit(1);
}
