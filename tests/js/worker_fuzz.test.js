// The solver worker against random and hostile requests (property in tests/fuzz/worker_property.mjs), running
// in a Node thread as a browser runs it in a Web Worker. A fixed seed keeps this run reproducible; `npm run fuzz`
// runs the same property for minutes with fresh seeds.
import { afterAll, beforeAll, describe, it } from 'vitest';
import fc from 'fast-check';
import { WorkerUnderTest, workerInput, workerProperty } from '../fuzz/worker_property.mjs';

let worker;
beforeAll(async () => {
  worker = await new WorkerUnderTest().start();
});
afterAll(() => worker?.stop());

describe('worker fuzzing', () => {
  it('every request gets one reply in time, refusals have a known code that is not internal (150 sequences, seed 2026)', async () => {
    await fc.assert(fc.asyncProperty(workerInput, workerProperty(worker)), { seed: 2026, numRuns: 150 });
  });
});
