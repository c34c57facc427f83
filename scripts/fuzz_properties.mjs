// Long fuzzing runs of the JS properties (run by scripts/fuzz.sh): each target's fast-check property with fresh
// random seeds for a bounded time, then the number of inputs that found nothing.
//   node scripts/fuzz_properties.mjs [--seconds 60] [target ...]     (default: every target, 60 s each)
// Targets:
//   scene     the scene parser (tests/fuzz/scene_property.mjs)
//   page      URL parameters and embed attributes as text (tests/fuzz/app_properties.mjs)
//   mount     mount() options of any value
//   settings  sequences of setOptions
//   edits     sequences of script edits of the handles (setHandles, drag, setTargets)
//   worker    sequences of requests to the solver worker, running in a thread (tests/fuzz/worker_property.mjs)
//   gltf      the glTF reader against random edits of a valid file (tests/fuzz/gltf_property.mjs)
//   gltf-resources, gltf-data, gltf-nodes
//             a .gltf's buffer uri as hostile path pieces, data: URIs spoiled, node forests of any shape and
//             transform read, written back and read again (tests/fuzz/gltf_reader_property.mjs)
// A finding prints the target, the seed, the path and the shrunk input, and exits 1: keep that input as a
// regression test (scenes: tests/data/fuzz-regressions/scenes/<name>.json, replayed by tests/js/scene_fuzz.test.js;
// the others as a case of their Vitest file) and fix the code.
import fc from 'fast-check';
import { checkScene, sceneInput } from '../tests/fuzz/scene_property.mjs';
import {
  checkEdits, checkMountOptions, checkPageText, checkSettingsSequence, editsInput, mountInput, pageTextInput, settingsInput,
} from '../tests/fuzz/app_properties.mjs';
import { checkGltf, gltfInput } from '../tests/fuzz/gltf_property.mjs';
import {
  checkDataUri, checkNodeTree, checkResource, dataUriInput, nodeTreeInput, resourceInput,
} from '../tests/fuzz/gltf_reader_property.mjs';
import { WorkerUnderTest, workerInput, workerProperty } from '../tests/fuzz/worker_property.mjs';
import { Timer } from './lib/timer.mjs';

// Each target: its property for a batch of runs (sync ones run 2000 per seed, the glTF reader 500, its node trees 100, the worker 50).
const TARGETS = new Map([
  ['scene', { batch: 2000, property: () => fc.property(sceneInput, checkScene) }],
  ['page', { batch: 2000, property: () => fc.property(pageTextInput, checkPageText) }],
  ['mount', { batch: 2000, property: () => fc.property(mountInput, checkMountOptions) }],
  ['settings', { batch: 2000, property: () => fc.property(settingsInput, checkSettingsSequence) }],
  ['edits', { batch: 2000, property: () => fc.property(editsInput, checkEdits) }],
  ['gltf', { batch: 500, property: () => fc.asyncProperty(gltfInput, checkGltf) }],
  ['gltf-resources', { batch: 500, property: () => fc.asyncProperty(resourceInput, checkResource) }],
  ['gltf-data', { batch: 500, property: () => fc.asyncProperty(dataUriInput, checkDataUri) }],
  ['gltf-nodes', { batch: 100, property: () => fc.asyncProperty(nodeTreeInput, checkNodeTree) }],
  ['worker', {
    batch: 50,
    async start() { this.worker = await new WorkerUnderTest().start(); },
    property() { return fc.asyncProperty(workerInput, workerProperty(this.worker)); },
    async stop() { await this.worker.stop(); },
  }],
]);

const args = process.argv.slice(2);
const at = args.indexOf('--seconds');
const seconds = at >= 0 ? Number(args.splice(at, 2)[1]) : 60;
const names = args.length ? args : [...TARGETS.keys()];
if (!(seconds > 0) || names.some((n) => !TARGETS.has(n))) {
  console.error(`usage: node scripts/fuzz_properties.mjs [--seconds S] [${[...TARGETS.keys()].join('|')} ...]`);
  process.exit(2);
}

const replacer = (key, value) => (ArrayBuffer.isView(value) ? `${value.constructor.name}(${value.length})` : value);
for (const name of names) {
  const target = TARGETS.get(name);
  await target.start?.();
  const started = new Timer();
  let runs = 0;
  while (started.seconds() < seconds) {
    const seed = Math.floor(Math.random() * 2 ** 31);
    const details = await fc.check(target.property(), { seed, numRuns: target.batch });
    runs += details.numRuns;
    if (details.failed) {
      console.error(`fuzz ${name}: finding after ${runs} inputs (seed ${seed}, path ${details.counterexamplePath}):`);
      console.error(JSON.stringify(details.counterexample?.[0], replacer));
      console.error(String(details.errorInstance?.message ?? details.error));
      await target.stop?.();
      process.exit(1);
    }
  }
  await target.stop?.();
  console.log(`fuzz ${name}: ${runs} inputs in ${started.seconds().toFixed(0)} s, no finding`);
}
