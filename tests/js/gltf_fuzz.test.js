// The glTF reader against random edits of a valid file (property in tests/fuzz/gltf_property.mjs): every
// input is read into a valid mesh or refused with a named InputError. A fixed seed keeps this run
// reproducible; `npm run fuzz` runs the same property for minutes with fresh seeds.
import { describe, it } from 'vitest';
import { checkGltf, fc, gltfInput } from '../fuzz/gltf_property.mjs';

describe('readGltf fuzzing', () => {
  it('reads or refuses by name every edited document (1000 inputs, seed 2026)', async () => {
    await fc.assert(fc.asyncProperty(gltfInput, checkGltf), { seed: 2026, numRuns: 1000 });
  });
});
