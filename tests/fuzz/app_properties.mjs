// Fuzz properties of the app's input surface without a page (fast-check), shared by the Vitest runs with fixed
// seeds (tests/js/app_fuzz.test.js) and the long runs of `npm run fuzz` (scripts/fuzz_properties.mjs):
//   page      URL parameters and embed attributes (text) and mount() options (any value) through
//             pageOptionsFromText and checkPageOptions (web/app/page_options.js)
//   settings  sequences of setOptions on AppSettings (web/app/settings.js)
//   edits     sequences of script edits of the handles (setHandles, drag, setTargets: HandleEditor)
// Each property throws (for fast-check) with the offending detail when the code misbehaves: a failure inside
// (a TypeError, anything but the app's InputError), a value accepted that its schema refuses, a refused edit
// that changed something, or a state whose saved scene the scene parser would refuse.
import fc from 'fast-check';
import { InputError } from '../../web/lib/errors.js';
import { EXAMPLE_NAMES } from '../../web/lib/examples.js';
import { OPTIONS, checkSolverOptions } from '../../web/lib/options.js';
import { parseScene, parseSceneHandles } from '../../web/lib/scene.js';
import { METHODS } from '../../web/app/methods.js';
import { PAGE_TEXT_NAMES, checkPageOptions, pageOptionsFromText } from '../../web/app/page_options.js';
import { AppSettings, SETTING_NAMES, checkSettings } from '../../web/app/settings.js';
import { HandleEditor } from '../../web/app/interaction/handle_editor.js';

const PROTOTYPE_KEYS = ['__proto__', 'constructor', 'toString', 'valueOf', 'hasOwnProperty'];
const hostileNumber = fc.oneof(
  fc.constantFrom(0, -0, 1, -1, 0.5, 2, 3, 20, 1000, 1001, 2 ** 31 - 1, 2 ** 31, 2 ** 53, 1e300, -1e300, NaN, Infinity,
    -Infinity, Number.MIN_VALUE),
  fc.integer({ min: -10, max: 2000 }),
  fc.double(),
);
const hostileText = fc.oneof(
  fc.constantFrom('', ' ', 'true', 'false', '1', '0', 'none', 'open', 'closed', 'show', 'auto', 'arap', 'ARAP', 'arap ',
    ' subspace', 'full', 'exact', 'fast', 'rotate', 'fly', 'bar', 'sphere', 'bunny', 'NaN', '1e999', '-5', '0x10', '1e3',
    '2147483648', 'arap,subspace,full,arap,arap', 'arap,bogus', ...PROTOTYPE_KEYS),
  fc.string({ maxLength: 12 }),
  hostileNumber.map(String),
);
// Scripts may pass what JSON has no word for: BigInts, functions, symbols, objects whose toString is not one.
const notJson = fc.oneof(fc.bigInt({ min: -(2n ** 70n), max: 2n ** 70n }), fc.constantFrom(() => 1, Symbol('s'), { toString: null },
  { valueOf: 'x' }, Object.create(null)), fc.bigInt().map((n) => [n]));
const hostileValue = fc.oneof(hostileNumber, hostileText, fc.boolean(), fc.constantFrom(null, undefined),
  fc.array(fc.oneof(hostileText, hostileNumber), { maxLength: 4 }), fc.jsonValue({ maxDepth: 2 }), notJson);
const settingName = fc.oneof({ weight: 8, arbitrary: fc.constantFrom(...SETTING_NAMES) },
  { weight: 1, arbitrary: fc.constantFrom(...PROTOTYPE_KEYS, 'fly', 'maxiterations') });
// A value near what a setting takes: its default, one of its choices, a value at or past its limits.
const plausibleSetting = fc.constantFrom(...OPTIONS).chain((o) => fc.constantFrom(o.default, ...o.choices, o.min, o.max,
  (o.min ?? 0) - 1, (o.max ?? 0) + 1).map((v) => [o.name, v]));
const partialSettings = fc.oneof(
  fc.dictionary(settingName, hostileValue, { maxKeys: 3 }),
  fc.array(plausibleSetting, { maxLength: 3 }).map((pairs) => Object.fromEntries(pairs)),
);

/** URL parameters or attributes: name -> text (the names a page may use, others, prototype keys). */
export const pageTextInput = fc.dictionary(
  fc.oneof({ weight: 6, arbitrary: fc.constantFrom(...PAGE_TEXT_NAMES) }, { weight: 1, arbitrary: fc.constantFrom(...PROTOTYPE_KEYS) },
    { weight: 1, arbitrary: fc.string({ maxLength: 8 }) }),
  hostileText, { maxKeys: 6 });

/** mount() options: anything, mostly objects whose keys are the options' and whose values are hostile. */
export const mountInput = fc.oneof(
  { weight: 1, arbitrary: hostileValue },
  { weight: 6, arbitrary: fc.tuple(fc.dictionary(fc.constantFrom('example', 'mesh', 'cage', 'scene', 'compare', 'panel',
    'panelBeside', 'help', 'tools', 'paused', 'labels', ...PROTOTYPE_KEYS), hostileValue, { maxKeys: 5 }), fc.option(partialSettings))
    .map(([options, settings]) => (settings === null ? options : { ...options, settings })) },
);

function expectInputError(error, what) {
  if (!(error instanceof InputError)) throw new Error(`${what} failed inside: ${error?.stack ?? error}`);
}

// What checkPageOptions returns must be usable as it is.
function checkPageResult({ options, settings, problems }, input) {
  if (!Array.isArray(problems) || !problems.every((p) => typeof p === 'string' && p.length > 0)) {
    throw new Error(`problems are not sentences: ${JSON.stringify(problems)}`);
  }
  try {
    checkSettings(settings, 'page');
    new AppSettings(settings);
  } catch (error) {
    throw new Error(`accepted settings ${JSON.stringify(settings)} that the settings refuse (${error.message}) from ${JSON.stringify(input)}`);
  }
  if (options.example !== undefined && !EXAMPLE_NAMES.includes(options.example)) throw new Error(`accepted example ${options.example}`);
  const compare = options.compare;
  if (compare !== undefined && compare !== null) {
    if (!Array.isArray(compare) || compare.length > METHODS.length || new Set(compare).size !== compare.length ||
        !compare.every((m) => METHODS.includes(m))) throw new Error(`compare became ${JSON.stringify(compare)}`);
  }
  for (const key of Object.keys(options)) if (PROTOTYPE_KEYS.includes(key)) throw new Error(`accepted option ${key}`);
}

/** Property: text from a page never throws, and what is kept is valid. */
export function checkPageText(text) {
  const get = (name) => (Object.hasOwn(text, name) ? text[name] : null);
  let result;
  try {
    result = checkPageOptions(pageOptionsFromText(get));
  } catch (error) {
    throw new Error(`reading ${JSON.stringify(text)} threw: ${error?.stack ?? error}`);
  }
  checkPageResult(result, text);
}

/** Property: mount() options never throw, and what is kept is valid. */
export function checkMountOptions(input) {
  let result;
  try {
    result = checkPageOptions(input);
  } catch (error) {
    throw new Error(`checkPageOptions threw on ${String(input)}: ${error?.stack ?? error}`);
  }
  checkPageResult(result, input);
}

/** Sequences of setOptions. */
export const settingsInput = fc.array(partialSettings, { minLength: 1, maxLength: 6 });

/**
 * Property: each update is refused (an InputError, nothing changed) or applied; the values stay valid, the
 * solver options of every method pass the library's check, and a saved scene's "solver" parses.
 */
export function checkSettingsSequence(updates) {
  const settings = new AppSettings();
  for (const partial of updates) {
    const before = JSON.stringify(settings.values);
    try {
      settings.update(partial);
    } catch (error) {
      expectInputError(error, 'setOptions');
      if (JSON.stringify(settings.values) !== before) throw new Error(`a refused update changed the settings: ${String(partial)}`);
      continue;
    }
    try {
      checkSettings(settings.values, 'values');
      for (const method of METHODS) {
        checkSolverOptions(settings.solverOptions(method), 'solverOptions');
        parseScene({ example: 'bar', handles: [], solver: settings.toScene(method) });
      }
    } catch (error) {
      throw new Error(`after ${JSON.stringify(updates)}: ${error.message}`);
    }
  }
}

// A tetrahedron's worth of rest positions: the editor's mesh has 4 vertices.
const REST = new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]);
const vertexIndex = fc.oneof({ weight: 6, arbitrary: fc.integer({ min: 0, max: 3 }) }, { weight: 1, arbitrary: hostileValue });
const vector = fc.oneof({ weight: 4, arbitrary: fc.array(fc.double({ min: -5, max: 5, noNaN: true }), { minLength: 3, maxLength: 3 }) },
  { weight: 1, arbitrary: hostileValue }, { weight: 1, arbitrary: fc.array(hostileNumber, { minLength: 3, maxLength: 3 }) });
const edit = fc.oneof(
  fc.record({ kind: fc.constant('setGroups'), groups: fc.oneof(fc.array(fc.array(vertexIndex, { maxLength: 3 }), { maxLength: 3 }), hostileValue),
    moving: fc.oneof(fc.constant(undefined), fc.array(fc.oneof(fc.integer({ min: -1, max: 4 }), hostileValue), { maxLength: 2 }), hostileValue) }),
  fc.record({ kind: fc.constant('move'), index: fc.oneof(fc.integer({ min: -1, max: 3 }), hostileValue), translation: vector,
    rotation: fc.oneof(fc.constant(null), fc.record({ axis: vector, angle: fc.oneof(fc.double({ min: -7, max: 7, noNaN: true }), hostileNumber) }), hostileValue) }),
  fc.record({ kind: fc.constant('targets'), targets: fc.oneof(fc.array(fc.oneof(fc.double({ min: -5, max: 5, noNaN: true }), hostileNumber), { maxLength: 9 }), hostileValue) }),
);

/** Sequences of script edits of the handles. */
export const editsInput = fc.array(edit, { minLength: 1, maxLength: 6 });

/**
 * Property: each edit is refused (an InputError, the groups as they were) or applied, and the groups then
 * save as a scene's handles that the scene parser takes back (no NaN stored, no null written).
 */
export function checkEdits(edits) {
  const editor = new HandleEditor();
  editor.setModel(REST);
  for (const e of edits) {
    const before = JSON.stringify(editor.handles.toScene());
    try {
      if (e.kind === 'setGroups') editor.setGroups(e.groups, e.moving);
      else if (e.kind === 'move') editor.move(e.index, e.translation, e.rotation);
      else editor.checkTargets(e.targets);
    } catch (error) {
      expectInputError(error, e.kind);
      if (JSON.stringify(editor.handles.toScene()) !== before) throw new Error(`a refused ${e.kind} changed the handles`);
      continue;
    }
    const saved = editor.handles.toScene();
    try {
      parseSceneHandles(JSON.parse(JSON.stringify(saved)));
    } catch (error) {
      throw new Error(`after ${e.kind} the saved handles ${JSON.stringify(saved)} do not parse: ${error.message}`);
    }
  }
}
