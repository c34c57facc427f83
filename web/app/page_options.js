// What a page asks the app for, read and checked in one place: mount()'s options, the attributes of
// <subspace-deformer> and the URL parameters of index.html. Attributes and parameters are text:
// pageOptionsFromText turns them into the values mount() takes (numbers, booleans, lists) by the same tables
// (PAGE_OPTIONS here, the settings' schema of settings.js for every setting, e.g. method="arap" or
// ?jacobian=exact); checkPageOptions then checks whatever came, by those tables. A bad value never leaves the
// page empty: it is dropped (its default applies) and named in `problems`, which the app shows in its banner.
import { EXAMPLE_NAMES } from '../lib/example_names.js'; // not examples.js: that would bundle the bunny a second time
import { LESSON_IDS } from './lessons/catalogue.js';
import { describeValue } from '../lib/options.js';
import { COMPARE_METHODS, readCompare } from './methods.js';
import { SETTING_NAMES, settingAllows, settingSchema } from './settings.js';

/** The values of the page option noCage (attribute no-cage, URL ?noCage=); 'ask', the default: the banner offers both. */
export const NO_CAGE_CHOICES = Object.freeze(['ask', 'generate', 'spectral']);

const isText = (v) => typeof v === 'string' && v.trim() !== '';
const isBoolean = (v) => typeof v === 'boolean';

/**
 * The options of mount() besides `settings`: what each takes (for messages) and its check. A Map: the names
 * come from pages and scripts.
 * @type {Map<string, { expects: string, allows: (value: unknown) => boolean }>}
 */
const PAGE_OPTIONS = new Map([
  ['example', { expects: `a built-in example: ${EXAMPLE_NAMES.join(', ')}`, allows: (v) => EXAMPLE_NAMES.includes(v) }],
  ['lesson', { expects: `a built-in lesson: ${LESSON_IDS.join(', ')}`, allows: (v) => LESSON_IDS.includes(v) }],
  ['mesh', { expects: 'a URL of a mesh file', allows: isText }],
  ['cage', { expects: 'a URL of a cage file', allows: isText }],
  ['scene', { expects: 'a URL of a scene file, or a scene object', allows: (v) => isText(v) || (!!v && typeof v === 'object' && !Array.isArray(v)) }],
  ['compare', { expects: `true, false or a list of methods (${COMPARE_METHODS.join(', ')})`, allows: () => true }], // checked by readCompare
  ['panel', { expects: "true, false or 'closed' (attribute: open, closed or none)", allows: (v) => isBoolean(v) || v === 'closed' }],
  ['panelBeside', { expects: 'true or false', allows: isBoolean }],
  ['help', { expects: 'true or false (attribute: none or show)', allows: isBoolean }],
  ['tools', { expects: 'true or false (attribute: none or show)', allows: isBoolean }],
  ['paused', { expects: 'true or false (attribute: present, or true, 1, false, 0)', allows: isBoolean }],
  ['labels', { expects: 'true or false', allows: isBoolean }],
  // The panel's "copy link to this pose" (ui/share_link.js): on in index.html, which reads ?pose= (main.js).
  ['shareLink', { expects: 'true or false', allows: isBoolean }],
  // A lone mesh without a cage (loading/no_cage.js): the banner asks, or it gets a generated cage or the spectral basis.
  ['noCage', { expects: `one of ${NO_CAGE_CHOICES.map((c) => `'${c}'`).join(', ')}`, allows: (v) => NO_CAGE_CHOICES.includes(v) }],
]);

/** The names pages may use as attributes or URL parameters: the page options and every setting. */
export const PAGE_TEXT_NAMES = Object.freeze([...PAGE_OPTIONS.keys(), ...SETTING_NAMES]);

const NUMBER_TEXT = /^\s*[-+]?(\d+\.?\d*|\.\d+)(e[-+]?\d+)?\s*$/i;

// A text value as the setting's kind reads it; text that is no such value stays text (the check names it).
function settingFromText(schema, text) {
  if (schema.also.includes(text)) return text;
  if (schema.kind === 'boolean') return text === '' || text === 'true' || text === '1' ? true : text === 'false' || text === '0' ? false : text;
  if (schema.kind === 'integer' || schema.kind === 'number') return NUMBER_TEXT.test(text) ? Number(text) : text;
  return text;
}

// The page options whose text differs from mount()'s values.
const TEXT_READERS = new Map([
  ['compare', (t) => (t === '' || t === '1' || t === 'true' ? true : t === '0' || t === 'false' ? false : t)],
  ['panel', (t) => (t === 'none' ? false : t === 'open' ? true : t)],
  ['help', (t) => (t === 'none' ? false : t === 'show' || t === '' ? true : t)],
  ['tools', (t) => (t === 'none' ? false : t === 'show' || t === '' ? true : t)],
  ['paused', (t) => (t === '' || t === '1' || t === 'true' ? true : t === '0' || t === 'false' ? false : t)],
  ['labels', (t) => (t === '' || t === 'true' ? true : t === 'false' ? false : t)],
  ['panelBeside', (t) => (t === '' || t === 'true' ? true : t === 'false' ? false : t)],
  ['shareLink', (t) => (t === '' || t === 'true' ? true : t === 'false' ? false : t)],
]);

/** An option's name as an attribute may also spell it: noCage as no-cage (attributes ignore case: nocage works too). */
export const kebabName = (name) => name.replace(/[A-Z]/g, (c) => `-${c.toLowerCase()}`);

/**
 * mount() options from text: `get(name)` returns an attribute's or a URL parameter's value, or null when it
 * is absent. Only the names of PAGE_TEXT_NAMES are asked for (other attributes and parameters are the page's).
 * @param {(name: string) => string|null} get
 * @returns {object} mount() options, with `settings`
 */
export function pageOptionsFromText(get) {
  const options = {};
  const settings = {};
  for (const name of PAGE_OPTIONS.keys()) {
    const text = get(name);
    if (text === null || text === undefined) continue;
    options[name] = TEXT_READERS.has(name) ? TEXT_READERS.get(name)(text) : text;
  }
  for (const name of SETTING_NAMES) {
    const text = get(name);
    if (text !== null && text !== undefined) settings[name] = settingFromText(settingSchema(name), text);
  }
  return { ...options, settings };
}

/**
 * Checks mount() options. Bad values are dropped and named in `problems` (one sentence each); the rest is
 * returned, `settings` as AppSettings takes it and `compare` as a list of distinct methods (or null).
 * @param {object} requested
 * @returns {{ options: object, settings: object, problems: string[] }}
 */
export function checkPageOptions(requested) {
  const problems = [];
  const drop = (name, expects, value) => problems.push(`${name} must be ${expects} (got ${describeValue(value)}): the default is used`);
  if (!requested || typeof requested !== 'object' || Array.isArray(requested)) {
    if (requested !== undefined) problems.push(`the options must be an object (got ${describeValue(requested)}): the defaults are used`);
    requested = {};
  }
  const options = {};
  for (const [name, value] of Object.entries(requested)) {
    if (name === 'settings' || value === undefined) continue;
    const option = PAGE_OPTIONS.get(name);
    if (!option) problems.push(`unknown option "${name}" (known: ${[...PAGE_OPTIONS.keys(), 'settings'].join(', ')}): ignored`);
    else if (!option.allows(value)) drop(name, option.expects, value);
    else options[name] = value;
  }
  if (options.compare !== undefined) {
    const { methods, unknown } = readCompare(options.compare);
    if (unknown.length) problems.push(`compare: ${unknown.map((m) => describeValue(m)).join(', ')} ${unknown.length > 1 ? 'are no methods' : 'is no method'} (methods: ${COMPARE_METHODS.join(', ')}): left out`);
    options.compare = methods;
  }
  return { options, settings: checkedSettings(requested.settings, drop, problems), problems };
}

// The settings one by one: a bad one is dropped, the others kept.
function checkedSettings(settings, drop, problems) {
  if (settings === undefined) return {};
  if (!settings || typeof settings !== 'object' || Array.isArray(settings)) {
    problems.push(`settings must be an object (got ${describeValue(settings)}): the defaults are used`);
    return {};
  }
  const out = {};
  for (const [name, value] of Object.entries(settings)) {
    if (value === undefined) continue;
    const schema = settingSchema(name);
    if (!schema) problems.push(`unknown setting "${name}": ignored`);
    else if (!settingAllows(schema, value)) drop(name, schema.expects, value);
    else out[name] = value;
  }
  return out;
}

/**
 * Says in the banner what the page asked for in vain, below what the first load may have shown there.
 * @param {import('./ui/overlays.js').Banner} banner
 * @param {string[]} problems from checkPageOptions
 */
export function showIgnoredOptions(banner, problems) {
  if (!problems.length) return;
  const note = `Ignored:\n${problems.map((p) => `\u2022 ${p}`).join('\n')}`;
  const shown = banner.text;
  banner.show(shown ? `${shown}\n\n${note}` : note, { kind: shown ? banner.element.dataset.kind : 'warning' });
}
