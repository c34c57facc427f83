// Wasm benchmark of binding each cage coordinate type (docs/benchmarks.md, "Cage coordinates"): mean value,
// positive mean value and harmonic coordinates of about n capsule vertices in the 296-vertex box cage of
// mvc.mjs, and in the same capsule and cage bent into a U (a concave cage: what positive mean value
// coordinates sample, and where mean value weights go negative). Prints each binding's wall time, its ratio
// to mean value coordinates', the smallest weight and the work counts that do not depend on load (rays per
// vertex; harmonic grid unknowns, factor entries, factor and solve times), and the CPU time of the process (all
// threads) beside the wall time: on a shared machine the wall time varies with the load, the CPU time less.
//   node scripts/bench/coordinates.mjs [n ...] [--case box|bent] [--repeat R] [--pmvc-resolution N]
//        [--harmonic-resolution N] [--json FILE]   (SD_WASM_BUILD=single: the single-threaded build)
import { writeFileSync } from 'node:fs';
import { COORDINATES, computeWeights, loadSolver } from 'subspace-deform';
import { boxCage, capsulePoints } from './binding_case.mjs';
import { namesOption, numberOption, readScriptOptions } from '../lib/script_options.mjs';

const HELP = `usage: node scripts/bench/coordinates.mjs [n ...] [--case box|bent] [--repeat R] [--pmvc-resolution N]
       [--harmonic-resolution N] [--json FILE]`;
const FLAGS = { case: 'string', repeat: 'string', 'pmvc-resolution': 'string', 'harmonic-resolution': 'string', json: 'string' };
const { positionals, flags } = readScriptOptions('bench/coordinates', process.argv.slice(2), FLAGS, HELP, { maxPositionals: Infinity });
const sizes = positionals.map((n) => numberOption('bench/coordinates', n, 'a size', { integer: true, min: 1 }));
if (sizes.length === 0) sizes.push(50000);
// Any other --case ran the box case under that label.
const cases = flags.case !== undefined ? namesOption('bench/coordinates', flags.case, '--case', ['box', 'bent']) : ['box', 'bent'];
const repeat = numberOption('bench/coordinates', flags.repeat ?? '1', '--repeat', { integer: true, min: 1 });
const resolutions = { pmvc: flags['pmvc-resolution'], harmonic: flags['harmonic-resolution'] };

const solver = await loadSolver();
console.log(`wasm build: ${solver.build}, ${solver.threads()} thread(s)`);
const results = [];
for (const name of cases) {
  const cage = boxCage({ bent: name === 'bent' });
  for (const n of sizes) {
    const mesh = { positions: capsulePoints(n, { bent: name === 'bent' }) };
    let mvcMs = null;
    for (const coordinates of COORDINATES.types) {
      const options = { coordinates, memoryBudgetMB: 4000 };
      if (coordinates === 'pmvc' && resolutions.pmvc) options.pmvcResolution = Number(resolutions.pmvc);
      if (coordinates === 'harmonic' && resolutions.harmonic) options.harmonicResolution = Number(resolutions.harmonic);
      const times = [], cpus = [];
      let r;
      for (let k = 0; k < repeat; ++k) {
        const cpu0 = process.cpuUsage();
        r = computeWeights(solver, mesh, cage, options);
        const cpu = process.cpuUsage(cpu0);
        times.push(r.bindMs);
        cpus.push((cpu.user + cpu.system) / 1e3);
      }
      const median = (list) => list.sort((a, b) => a - b)[Math.floor(list.length / 2)];
      const ms = median(times), cpuMs = median(cpus);
      if (coordinates === 'mvc') mvcMs = { ms, cpuMs };
      const row = { case: name, n: r.rows, m: r.cols, coordinates, bindMs: ms, cpuMs, ratio: ms / mvcMs.ms, cpuRatio: cpuMs / mvcMs.cpuMs,
        minWeight: r.minWeight, threads: solver.threads(), build: solver.build };
      if (coordinates === 'pmvc') Object.assign(row, { raysPerVertex: r.rays / r.rows, hiddenFacesPerVertex: r.hiddenFaces / r.rows });
      if (coordinates === 'harmonic') {
        Object.assign(row, { resolution: r.resolution, unknowns: r.unknowns, factorNonzeros: r.factorNonzeros, factorMs: r.factorMs,
          solveMs: r.solveMs, gridMB: r.gridBytes / 1e6 });
      }
      results.push(row);
      const extra = coordinates === 'pmvc' ? `, ${row.raysPerVertex.toFixed(0)} rays/vertex behind ${row.hiddenFacesPerVertex.toFixed(1)} triangles`
        : coordinates === 'harmonic' ? `, resolution ${r.resolution}, ${r.unknowns} unknowns, factor ${(r.factorNonzeros / 1e6).toFixed(2)} M entries ${r.factorMs.toFixed(0)} ms, solves ${r.solveMs.toFixed(0)} ms, grid+factor ${(r.gridBytes / 1e6).toFixed(0)} MB`
          : '';
      console.log(`${name} n=${r.rows} m=${r.cols} ${coordinates.padEnd(8)} bind ${ms.toFixed(0).padStart(6)} ms wall (${row.ratio.toFixed(2)}x mvc), ` +
        `${cpuMs.toFixed(0)} ms cpu (${row.cpuRatio.toFixed(2)}x), min weight ${r.minWeight.toPrecision(3)}${extra}`);
    }
  }
}
if (flags.json) writeFileSync(flags.json, `${JSON.stringify(results, null, 2)}\n`);
