// Wasm benchmark of the mean value coordinates binding, the same cases as cpp/tools/bench_mvc.cpp:
// the vertices of a capsule inside a 7 x 7 subdivided box cage (296 vertices, 588 triangles).
//   node scripts/bench/mvc.mjs [n ...] [--float32]      (SD_WASM_DIR=build/mvc-wasm to use another build)
// Prints wall and CPU time (the machine may be shared) and point-triangle evaluations per second.
import { computeWeights, loadSolver } from 'subspace-deform';
import { boxCage, capsulePoints } from './binding_case.mjs';
import { numberOption, readScriptOptions } from '../lib/script_options.mjs';

// A word for a size used to run n = 2, and an unknown flag was ignored.
const { positionals, flags } = readScriptOptions('bench/mvc', process.argv.slice(2), { float32: 'boolean' },
  'usage: node scripts/bench/mvc.mjs [n ...] [--float32]', { maxPositionals: Infinity });
const float32 = !!flags.float32;
const sizes = positionals.map((n) => numberOption('bench/mvc', n, 'a size', { integer: true, min: 1 }));
if (sizes.length === 0) sizes.push(5000, 20000, 50000);

const solver = await loadSolver();

const cage = boxCage();

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
