// Long fuzzing run of the scene parser (run by scripts/fuzz.sh): the property of
// tests/fuzz/scene_property.mjs with fresh random seeds for a bounded time.
//   node scripts/fuzz_scene.mjs [--seconds 60]
// A failure prints the seed, the path and the shrunk input; keep that input as
// tests/data/fuzz-regressions/scenes/<name>.json (tests/js/scene_fuzz.test.js replays it) and fix the parser.
import fc from 'fast-check';
import { checkScene, sceneInput } from '../tests/fuzz/scene_property.mjs';
import { Timer } from './lib/timer.mjs';

const at = process.argv.indexOf('--seconds');
const seconds = at >= 0 ? Number(process.argv[at + 1]) : 60;
if (!(seconds > 0)) {
  console.error('usage: node scripts/fuzz_scene.mjs [--seconds S]');
  process.exit(2);
}
const started = new Timer();
let runs = 0;
while (started.seconds() < seconds) {
  const seed = Math.floor(Math.random() * 2 ** 31);
  const details = fc.check(fc.property(sceneInput, checkScene), { seed, numRuns: 2000 });
  runs += details.numRuns;
  if (details.failed) {
    console.error(`fuzz_scene: finding after ${runs} inputs (seed ${seed}, path ${details.counterexamplePath}):`);
    console.error(JSON.stringify(details.counterexample[0]));
    console.error(String(details.errorInstance?.message ?? details.error));
    process.exit(1);
  }
}
console.log(`fuzz_scene: ${runs} inputs in ${started.seconds().toFixed(0)} s, no finding`);
