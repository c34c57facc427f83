// The glTF reader against random edits of a valid file (property in tests/fuzz/gltf_property.mjs) and its
// newer paths -- buffer uris, data: URIs, node forests read, written back and read again
// (tests/fuzz/gltf_reader_property.mjs): every input is read into a valid mesh or refused with a named
// InputError, nothing written holds NaN, each instance comes back as written. Fixed seeds keep these runs
// reproducible; `npm run fuzz` runs the same properties for minutes with fresh seeds. What the fuzzing found
// is kept below as replays.
import { describe, expect, it } from 'vitest';
import { checkGltf, fc, gltfInput } from '../fuzz/gltf_property.mjs';
import {
  checkDataUri, checkNodeTree, checkResource, dataUriInput, nodeTreeInput, resourceInput,
} from '../fuzz/gltf_reader_property.mjs';

describe('readGltf fuzzing', () => {
  it('reads or refuses by name every edited document (1000 inputs, seed 2026)', async () => {
    await fc.assert(fc.asyncProperty(gltfInput, checkGltf), { seed: 2026, numRuns: 1000 });
  });

  it('reads a buffer only from inside the folder, or refuses its uri by name (1000 uris, seed 32)', async () => {
    await fc.assert(fc.asyncProperty(resourceInput, checkResource), { seed: 32, numRuns: 1000 });
  });

  it('reads or refuses by name every spoiled data: URI (1000 inputs, seed 32)', async () => {
    await fc.assert(fc.asyncProperty(dataUriInput, checkDataUri), { seed: 32, numRuns: 1000 });
  });

  it('reads, writes back and reads again every node forest, or refuses it by name (150 inputs, seed 32)', async () => {
    await fc.assert(fc.asyncProperty(nodeTreeInput, checkNodeTree), { seed: 32, numRuns: 150 });
  }, 60000);
});

describe('what gltf-nodes found (issue 32, item 6), replayed', () => {
  const node = (parent, mesh, transform) => ({ parent, mesh, transform });
  it.each([
    // One mesh under two nodes: both instances were written with the second's positions.
    ['a mesh shared by two roots', [node(0, 0, 0), node(0, 0, 0)]],
    // A node scaled by zero: its inverse transform wrote NaN positions.
    ['a zero-scaled instance beside a normal one', [node(0, 0, 1), node(0, 0, 0)]],
    // Two unnormalised rotations over a 1e-30 scale (ill-conditioned): kept to float32's precision there.
    ['an ill-conditioned instance', [node(0, 0, 9), node(9, 0, 9), node(3, 0, 0), node(10, 0, 5)]],
  ])('%s', async (_, nodes) => {
    expect(await checkNodeTree({ nodes, corrupt: undefined, chain: 0 })).toBe(true);
  });
});
