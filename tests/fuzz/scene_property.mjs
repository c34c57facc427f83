// The scene parser's fuzz property (fast-check), shared by the Vitest run with a fixed seed
// (tests/js/scene_fuzz.test.js) and the long run of `npm run fuzz` (scripts/fuzz_properties.mjs).
//
// Inputs: random JSON values, random text, and scenes whose every field may hold a hostile value (wrong
// types, 2^31, 1e300, -0, huge or nested arrays, unknown keys). Property: parseScene either returns a
// scene whose values the solver can take as they are, or throws the parser's own Error naming the field
// (an InputError); it never fails inside (a TypeError, a stack overflow) and never accepts a number the
// C++ side would wrap around. handleTargets on an accepted scene gives finite targets or a scene Error.
import fc from 'fast-check';
import { InputError } from '../../web/lib/errors.js';
import { OPTIONS } from '../../web/lib/options.js';
import { handleTargets, parseScene } from '../../web/lib/scene.js';

const INT32_MAX = 2 ** 31 - 1;
// A tetrahedron's worth of rest positions: handles may name vertices 0..3.
const REST = new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]);

const hostileNumber = fc.oneof(
  fc.constantFrom(0, -0, 1, -1, 0.5, 3, 4, 100, 2 ** 31 - 1, 2 ** 31, 2 ** 53, 1e300, -1e300, Number.MAX_VALUE,
    Number.MIN_VALUE, 1e-320),
  fc.integer({ min: -10, max: 2000 }),
  fc.double({ noNaN: true, noDefaultInfinity: true }),
);
const hostileValue = fc.oneof(
  hostileNumber,
  fc.boolean(),
  fc.constantFrom(null, '', 'subspace', 'full', 'arap', 'fast', 'exact', 'bar', 'mesh.obj', 'NaN', '1e999', '__proto__'),
  fc.string({ maxLength: 8 }),
  fc.array(hostileNumber, { maxLength: 5 }),
  fc.jsonValue({ maxDepth: 3 }),
);
// Mostly plausible values, sometimes hostile ones: most inputs then get deep into the parser.
const mostly = (plausible, weight = 12) => fc.oneof({ weight, arbitrary: plausible }, { weight: 1, arbitrary: hostileValue });
// null most of the time, else a value.
const rarely = (value) => fc.oneof({ weight: 7, arbitrary: fc.constant(null) }, { weight: 1, arbitrary: value });
const vector = mostly(fc.array(fc.oneof(fc.double({ min: -10, max: 10, noNaN: true }), hostileNumber), { minLength: 3, maxLength: 3 }));
const handle = fc.record(
  {
    vertices: mostly(fc.uniqueArray(fc.integer({ min: 0, max: 4 }), { minLength: 1, maxLength: 3 })),
    translate: vector,
    rotate: mostly(fc.oneof(
      fc.record({ axis: vector, angle: hostileNumber, center: vector }, { requiredKeys: ['axis', 'angle'] }),
      fc.record({ axis: vector, degrees: hostileNumber, center: vector }, { requiredKeys: ['axis', 'degrees'] }))),
  },
  { requiredKeys: ['vertices'] },
).chain((h) => rarely(hostileValue).map((move) => (move === null ? h : { ...h, move })));
const plausibleOption = {
  method: fc.constantFrom('subspace', 'full', 'arap'),
  jacobian: fc.constantFrom('fast', 'exact'),
  volume: fc.boolean(),
  maxIterations: fc.oneof(fc.integer({ min: 1, max: 1000 }), fc.constantFrom(2 ** 31 - 1, 2 ** 31, 1e300)),
  cgMaxIterations: fc.oneof(fc.integer({ min: 1, max: 100 }), fc.constantFrom(2 ** 31, 2 ** 53)),
  cgMemory: fc.integer({ min: -1, max: 600 }),
  arapAcceleration: fc.integer({ min: -1, max: 60 }),
  cageRegularization: fc.oneof(fc.double({ min: 0, max: 1, noNaN: true }), fc.constantFrom(-1e-3, 1.5, 1e300)),
};
const solverOptions = fc.dictionary(
  fc.constantFrom(...OPTIONS.map((o) => o.name), 'bogus', 'valueOf'),
  hostileValue,
  { maxKeys: 4 },
).chain((hostile) => fc.record(plausibleOption, { requiredKeys: [] }).map((plausible) => ({ ...plausible, ...hostile })));
const modelSource = fc.oneof(
  { weight: 3, arbitrary: fc.constant({ mesh: 'mesh.obj' }) },
  { weight: 2, arbitrary: fc.constant({ mesh: 'mesh.obj', cage: 'cage.obj' }) },
  { weight: 2, arbitrary: fc.constant({ example: 'bar' }) },
  { weight: 2, arbitrary: fc.oneof(fc.integer({ min: 2, max: 300 }), hostileNumber).map((vertices) => ({ mesh: 'mesh.obj', generateCage: { vertices } })) },
  { weight: 1, arbitrary: fc.constant({}) },
  { weight: 2, arbitrary: fc.record({ mesh: hostileValue, cage: hostileValue, example: hostileValue, generateCage: hostileValue },
    { requiredKeys: [] }) },
);
const structuredScene = fc.tuple(modelSource, mostly(fc.array(handle, { maxLength: 3 })), mostly(solverOptions),
  rarely(fc.dictionary(fc.constantFrom('description', 'name', 'extra'), hostileValue, { maxKeys: 1 })))
  .map(([model, handles, solver, extra]) => ({ ...model, handles, solver, ...(extra ?? {}) }));

/** Inputs for parseScene: scenes with hostile fields, any JSON value, and text (JSON or not). */
export const sceneInput = fc.oneof(
  { weight: 6, arbitrary: structuredScene },
  { weight: 2, arbitrary: fc.jsonValue({ maxDepth: 4 }) },
  { weight: 1, arbitrary: structuredScene.map((s) => JSON.stringify(s)) },
  { weight: 1, arbitrary: fc.string({ maxLength: 40 }) },
);

// The parser's own refusals are InputErrors (naming the field).
function isSceneError(error) {
  return error instanceof InputError;
}

/**
 * The property: throws (for fast-check) with the offending detail when the parser misbehaves.
 * @param {unknown} input
 */
export function checkScene(input) {
  let scene;
  for (const modelOptional of [false, true]) {
    try {
      scene = parseScene(input, { modelOptional });
    } catch (error) {
      if (!isSceneError(error)) throw new Error(`parseScene failed inside: ${error?.stack ?? error}`);
      continue;
    }
    checkAccepted(scene);
  }
}

// Options the C++ side holds in an int (from the options table).
const INTEGER_OPTIONS = new Set(OPTIONS.filter((o) => o.kind === 'integer').map((o) => o.name));

function checkAccepted(scene) {
  for (const [key, value] of Object.entries(scene.solver)) {
    if (typeof value !== 'number') continue;
    const fits = INTEGER_OPTIONS.has(key) ? Number.isInteger(value) && Math.abs(value) <= INT32_MAX : Number.isFinite(value);
    if (!fits) throw new Error(`accepted solver.${key} = ${value}, which the solver's ${INTEGER_OPTIONS.has(key) ? 'int' : 'double'} cannot hold`);
  }
  let result;
  try {
    result = handleTargets(REST, scene.handles);
  } catch (error) {
    if (!isSceneError(error)) throw new Error(`handleTargets failed inside: ${error?.stack ?? error}`);
    return;
  }
  const count = scene.handles.reduce((sum, h) => sum + h.vertices.length, 0);
  if (result.targets.length !== 3 * count) throw new Error(`handleTargets gave ${result.targets.length} numbers for ${count} vertices`);
  if (!result.targets.every(Number.isFinite)) throw new Error(`handleTargets gave non-finite targets for ${JSON.stringify(scene.handles)}`);
}
