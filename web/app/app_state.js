// The app's state: one observable model of what the user has and chose, with one change event. Components
// (the tool strip, the app's own events for the panel and scripts) subscribe to it and read `current`; they
// change it through its intents, never by holding the app. It holds:
//   settings   the solver options, display and interaction choices, the next binding (settings.js: AppSettings
//              keeps the values and their per-method views; every write to it, from here or from the loader,
//              reaches the subscribers as this state's change)
//   panelOpen  whether the control panel is open
//   views      the view choices: compare mode (null, the methods or 'coordinates') and the views' keys
//   model      the bound model (the worker's Model plus its source; null before the first load), read-only
//   handles    the handle groups' and the selection's counts, and whether undo and redo can do anything
//   stepping   step-through: paused, whether a view runs ARAP, and the name of its next half step
//   parts      volume parts: whether the picker paints them, the painted part, how many the solvers keep
//   influence  whether a click picks a cage vertex, and the basis column shown (null: none)
//   skeleton   how many joints and bones, and whether the solvers keep the bones
//   lesson     the current lesson ({ id, title, caption, view, model }), or null
// The app's collaborators still own handles, parts, influence, skeleton, stepping and lessons: the app copies their
// summaries in (collaborator_state.js).
import { InputError } from '../lib/errors.js';
import { AppSettings } from './settings.js';

/** The state's parts besides `settings`, with their values before anything is loaded. */
const INITIAL = Object.freeze({
  panelOpen: false,
  views: Object.freeze({ compare: null, keys: Object.freeze([]) }),
  model: null,
  handles: Object.freeze({ fixed: 0, moving: 0, selected: 0, canUndo: false, canRedo: false }),
  stepping: Object.freeze({ paused: false, hasArap: false, nextPhase: 'local' }),
  parts: Object.freeze({ painting: false, current: 0, count: 0 }),
  influence: Object.freeze({ picking: false, column: null }),
  skeleton: Object.freeze({ joints: 0, bones: 0, enabled: true }),
  lesson: null,
});

/** The parts update() takes (settings change only through setOptions, which checks them). */
export const STATE_PARTS = Object.freeze(Object.keys(INITIAL));

export class AppState {
  #settings;
  #parts = { ...INITIAL };
  #listeners = new Set();
  #lastListeners = new Set();
  #current = null; // the frozen snapshot, rebuilt after a change

  /** @param {object} [initialSettings] values replacing the settings' defaults (checked by AppSettings) */
  constructor(initialSettings = {}) {
    this.#settings = new AppSettings(initialSettings);
    // The loader writes the next binding's settings itself (a scene's solver, a no-cage choice): one event either way.
    this.#settings.addEventListener('change', (e) => this.#emit({ settings: e.changed }));
  }

  /** The settings' store (settings.js), for what reads them per method (solverOptions, toScene); write through setOptions. */
  get settings() { return this.#settings; }

  /**
   * A snapshot of everything: { settings, panelOpen, views, model, handles, stepping, parts, influence, skeleton,
   * lesson }, frozen with its
   * settings; the other parts are the values update() was given, which nobody changes.
   */
  get current() {
    this.#current ??= Object.freeze({ settings: Object.freeze(this.#settings.snapshot()), ...this.#parts });
    return this.#current;
  }

  /**
   * Calls `listener(change, current)` after every change; `change` holds only what changed (settings: the
   * settings given). Returns the function that unsubscribes it. `last`: after every other listener (the app's own
   * events, so that a page's listener sees the views with the change applied).
   * @param {(change: object, current: object) => void} listener
   * @param {{ last?: boolean }} [options]
   */
  subscribe(listener, { last = false } = {}) {
    const listeners = last ? this.#lastListeners : this.#listeners;
    listeners.add(listener);
    return () => listeners.delete(listener);
  }

  // ---------------------------------------------------------------- intents

  /** Merges settings; an InputError names an unknown setting or a bad value, and nothing changes. */
  setOptions(partial) {
    this.#settings.update(partial);
  }

  setPanelOpen(open) {
    if (typeof open !== 'boolean') throw new InputError(`setPanelOpen: open must be true or false (got ${JSON.stringify(open)})`);
    this.update({ panelOpen: open });
  }

  // ---------------------------------------------------------------- the app's copies of its collaborators' state

  /**
   * Replaces parts (STATE_PARTS) by the values given (kept as given: pass fresh objects, never change them); a
   * part equal to its current value (field by field) is no change. One event for all that changed, none if nothing did. An unknown part is a programming error.
   */
  update(change) {
    const changed = {};
    for (const [key, value] of Object.entries(change)) {
      if (!STATE_PARTS.includes(key)) throw new Error(`AppState.update: unknown part '${key}' (known: ${STATE_PARTS.join(', ')})`);
      if (sameValue(this.#parts[key], value)) continue;
      changed[key] = value;
    }
    if (Object.keys(changed).length === 0) return;
    Object.assign(this.#parts, changed);
    this.#emit(changed);
  }

  #emit(change) {
    this.#current = null;
    const current = this.current;
    // A listener that an earlier one unsubscribed (a view disposed by a change) hears nothing more.
    for (const listeners of [this.#listeners, this.#lastListeners])
      for (const listener of [...listeners]) if (listeners.has(listener)) listener(change, current);
  }
}

// Equal values, or plain objects whose fields are equal (arrays by their items).
function sameValue(a, b) {
  if (a === b) return true;
  if (!a || !b || typeof a !== 'object' || typeof b !== 'object') return false;
  const keys = Object.keys(a);
  if (keys.length !== Object.keys(b).length) return false;
  return keys.every((k) => a[k] === b[k] || (Array.isArray(a[k]) && Array.isArray(b[k]) && a[k].length === b[k].length && a[k].every((x, i) => x === b[k][i])));
}
