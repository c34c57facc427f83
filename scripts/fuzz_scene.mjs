// Long fuzzing run of the scene parser (run by scripts/fuzz.sh): the property of
// tests/fuzz/scene_property.mjs with fresh random seeds for a bounded time.
//   node scripts/fuzz_scene.mjs [--seconds 60]
// A failure prints the seed, the path and the shrunk input; keep that input as
// tests/data/fuzz-regressions/scenes/<name>.json (tests/js/scene_fuzz.test.js replays it) and fix the parser.
import fc from 'fast-check';
import { checkScene, sceneInput } from '../tests/fuzz/scene_property.mjs';
import { fuzzFor, fuzzSeconds } from './lib/fuzz_loop.mjs';

await fuzzFor('fuzz_scene', fc.property(sceneInput, checkScene), fuzzSeconds('fuzz_scene'), 2000);
