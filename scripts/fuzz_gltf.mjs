// Long fuzzing run of the glTF reader (run by scripts/fuzz.sh): the property of tests/fuzz/gltf_property.mjs
// with fresh random seeds for a bounded time.
//   node scripts/fuzz_gltf.mjs [--seconds 60]
// A failure prints the seed, the path and the shrunk input; keep it as a case in tests/js/gltf.test.js and fix
// the reader.
import { checkGltf, fc, gltfInput } from '../tests/fuzz/gltf_property.mjs';
import { fuzzFor, fuzzSeconds } from './lib/fuzz_loop.mjs';

await fuzzFor('fuzz_gltf', fc.asyncProperty(gltfInput, checkGltf), fuzzSeconds('fuzz_gltf'), 500);
