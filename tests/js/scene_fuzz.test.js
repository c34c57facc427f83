// The scene parser against random and hostile input (property in tests/fuzz/scene_property.mjs). A fixed
// seed keeps this run reproducible; `npm run fuzz` runs the same property for minutes with fresh seeds.
// Inputs that once failed are kept in tests/data/fuzz-regressions/scenes/ and replayed here.
import { describe, expect, it } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import fc from 'fast-check';
import { checkScene, sceneInput } from '../fuzz/scene_property.mjs';

const regressions = new URL('../data/fuzz-regressions/scenes/', import.meta.url);

describe('parseScene fuzzing', () => {
  it('refuses hostile scenes with its own named error or accepts values the solver can take (3000 inputs, seed 2026)', () => {
    fc.assert(fc.property(sceneInput, checkScene), { seed: 2026, numRuns: 3000 });
  });

  it.each(readdirSync(regressions).filter((f) => f.endsWith('.json')))('replays the kept input %s', (file) => {
    const text = readFileSync(new URL(file, regressions), 'utf8');
    expect(() => checkScene(text)).not.toThrow();
    expect(() => checkScene(JSON.parse(text))).not.toThrow();
  });
});
