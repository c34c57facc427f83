// The long fuzzing runs of fast-check properties (scripts/fuzz_scene.mjs, scripts/fuzz_gltf.mjs): fresh random
// seeds for a bounded time, the first failure printed with its seed, path and shrunk input (exit 1), else
// how many inputs found nothing.
import fc from 'fast-check';
import { Timer } from './timer.mjs';

/** The --seconds argument (default 60), or exit 2 with the usage. */
export function fuzzSeconds(script) {
  const at = process.argv.indexOf('--seconds');
  const seconds = at >= 0 ? Number(process.argv[at + 1]) : 60;
  if (!(seconds > 0)) {
    console.error(`usage: node scripts/${script}.mjs [--seconds S]`);
    process.exit(2);
  }
  return seconds;
}

/**
 * Checks `property` (a fast-check property or async property) with fresh seeds, `numRuns` inputs per seed,
 * until `seconds` have passed.
 */
export async function fuzzFor(name, property, seconds, numRuns) {
  const started = new Timer();
  let runs = 0;
  while (started.seconds() < seconds) {
    const seed = Math.floor(Math.random() * 2 ** 31);
    const details = await fc.check(property, { seed, numRuns });
    runs += details.numRuns;
    if (details.failed) {
      console.error(`${name}: finding after ${runs} inputs (seed ${seed}, path ${details.counterexamplePath}):`);
      console.error(fc.stringify(details.counterexample[0]));
      console.error(String(details.errorInstance?.message ?? details.error));
      process.exit(1);
    }
  }
  console.log(`${name}: ${runs} inputs in ${started.seconds().toFixed(0)} s, no finding`);
}
