// Markdown tables of docs/experiments/README.md from a results.json (so the README's numbers are the run's,
// not retyped): the report's tables per scene, the subspace comparison with the condition numbers, the neck
// pull's part volumes and the spectral basis' cost.
//   node scripts/experiments/tables.mjs [docs/experiments/results.json] > tables.md
import { readFileSync } from 'node:fs';

const NAMES = {
  'subspace-fast': 'subspace, fast', 'subspace-exact': 'subspace, exact', 'subspace-novolume': 'subspace, no volume constraint',
  'full-fast': 'full space, fast', 'full-exact': 'full space, exact', arap: 'ARAP, from rest', 'arap-sliced': 'ARAP, 10 slices',
};

const e = (x, digits = 3) => (x === undefined || x === null || !Number.isFinite(x) ? (x === Infinity ? 'inf' : '-') : Number(x).toExponential(digits - 1));
const g = (x) => (Math.abs(x) >= 0.01 && Math.abs(x) < 1000 ? Number(x.toPrecision(3)).toString() : e(x));
const percent = (x) => {
  const text = `${x > 0.0005 ? '+' : ''}${Math.abs(x) < 0.0005 ? '0.000' : x.toFixed(Math.abs(x) < 10 ? 3 : 1)}%`;
  return Math.abs(x) >= 1 ? `**${text}**` : text;
};
const stop = (s) => s.stopReason.replace(/^converged: /, '').replace(/^iteration cap (\d+)/, 'cap $1');
const ms = (s) => Math.round(s.iterations.ms.reduce((a, b) => a + b, 0));
const row = (cells) => `| ${cells.join(' | ')} |`;

function reportTable(scene) {
  const lines = [row([`${scene.id}${scene.model.real ? ` (${scene.model.name})` : ''}`, 'iterations', 'stop', 'ms', 'energy', 'ARAP energy', 'volume', 'handle error / D']),
    row(Array(8).fill('---'))];
  for (const s of scene.series) {
    lines.push(row([NAMES[s.method] ?? s.label, s.iterations.iteration.length, stop(s), ms(s), g(s.final.energy), g(s.final.arapEnergy),
      percent(s.final.volumeChangePercent), s.method.startsWith('arap') ? '0' : e(s.final.handleMaxErrorRelative, 2)]));
  }
  return lines.join('\n');
}

function kappa(c) {
  if (!c || c.error) return ['-', '-'];
  return [e(c.condition, 2), c.orthonormal ? e(c.orthonormal.condition, 2) : '-'];
}

function subspaceTable(scene) {
  const lines = [row([`${scene.id}: basis`, 'columns', 'iterations', 'stop', 'ms (bind)', 'energy', 'ARAP energy', 'handle error / D', 'kappa at rest', 'kappa, orthonormal basis']),
    row(Array(10).fill('---'))];
  const pick = (method) => scene.series.find((s) => s.method === method);
  const cage = pick('subspace-fast'), full = pick('full-fast');
  const c = scene.subspaces.conditioning;
  const line = (name, columns, s, bind, k) => lines.push(row([name, columns, s.iterations.iteration.length, stop(s),
    bind === null ? `${ms(s)}` : `${ms(s)} (${Math.round(bind)})`,
    g(s.final.energy), g(s.final.arapEnergy), e(s.final.handleMaxErrorRelative, 2), ...k]));
  if (cage) line('cage', scene.m, cage, scene.bindMs, kappa(c.cage));
  for (const s of scene.subspaces.series) line(`spectral, k = ${s.modes}`, s.modes + 4, s, s.bindMs, kappa(c.spectral[s.modes]));
  if (full) line('full space', scene.n, full, null, [e(c.full.condition, 2), '-']);
  return lines.join('\n');
}

function partsTable(v) {
  const K = v.restPartVolumes.length;
  const total = v.restPartVolumes.reduce((a, b) => a + b, 0);
  const lines = [row(['neck_pull', 'iterations', 'energy', 'handle error / D', 'largest part change', ...Array.from({ length: K }, (_, k) => `part ${k}`)]),
    row(Array(5 + K).fill('---')),
    row(['(share of the rest volume)', '', '', '', '', ...v.restPartVolumes.map((x) => `${((100 * x) / total).toFixed(1)}%`)])];
  for (const s of v.series) {
    const worst = Math.max(...s.final.partChangePercent.map(Math.abs)) / 100;
    lines.push(row([s.label, s.iterations.iteration.length, g(s.final.energy), e(s.final.handleMaxErrorRelative, 2), e(worst, 2),
      ...s.final.partChangePercent.map(percent)]));
  }
  return lines.join('\n');
}

function costTable(rows) {
  return [row(['n', 'k', 'wasm ms', 'Lanczos solves', 'memory MB', 'load']), row(Array(6).fill('---')),
    ...rows.map((r) => row([r.n, r.modes, Math.round(r.ms), r.solves, Math.round(r.memoryMB), r.load.toFixed(1)]))].join('\n');
}

const results = JSON.parse(readFileSync(process.argv[2] ?? new URL('../../docs/experiments/results.json', import.meta.url), 'utf8'));
console.log(`<!-- results.json of ${results.date}, load ${results.machine.loadBefore.map((x) => x.toFixed(1)).join(' ')} -> ${results.machine.loadAfter.map((x) => x.toFixed(1)).join(' ')} -->\n`);
for (const scene of results.scenes) console.log(`${reportTable(scene)}\n\n${subspaceTable(scene)}\n`);
if (results.volumeParts) console.log(`${partsTable(results.volumeParts)}\n`);
if (results.spectralCost) console.log(costTable(results.spectralCost));
