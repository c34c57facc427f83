// The app's one observable state (web/app/app_state.js): one change event per change, naming what changed;
// intents that refuse bad values without changing anything; unsubscribe; a snapshot that cannot be edited.
import { describe, expect, it } from 'vitest';
import { AppState, STATE_PARTS } from '../../web/app/app_state.js';
import { collaboratorState } from '../../web/app/collaborator_state.js';
import { DEFAULT_SETTINGS } from '../../web/app/settings.js';
import { InputError } from '../../web/lib/errors.js';

function recorded(state) {
  const changes = [];
  const unsubscribe = state.subscribe((change, current) => changes.push({ change, current }));
  return { changes, unsubscribe };
}

describe('AppState', () => {
  it('starts from the default settings, with the page\'s values over them', () => {
    const state = new AppState({ tool: 'orbit' });
    expect(state.current.settings.tool).toBe('orbit');
    expect(state.current.settings.method).toBe(DEFAULT_SETTINGS.method);
    expect(state.current.panelOpen).toBe(false);
    expect(() => new AppState({ tool: 'fly' })).toThrow(InputError);
  });

  it('fires once per setOptions with the settings given, and the snapshot after it', () => {
    const state = new AppState();
    const { changes } = recorded(state);
    state.setOptions({ tool: 'brush', erase: true });
    expect(changes).toHaveLength(1);
    expect(changes[0].change).toEqual({ settings: { tool: 'brush', erase: true } });
    expect(changes[0].current.settings.tool).toBe('brush');
    expect(state.current.settings.erase).toBe(true);
  });

  it('calls a last listener after every other one, even those subscribed after it', () => {
    const state = new AppState();
    const order = [];
    state.subscribe(() => order.push('first'));
    const stop = state.subscribe(() => order.push('last'), { last: true });
    state.subscribe(() => order.push('later'));
    state.setOptions({ tool: 'brush' });
    expect(order).toEqual(['first', 'later', 'last']);
    stop();
    state.setPanelOpen(true);
    expect(order).toEqual(['first', 'later', 'last', 'first', 'later']);
  });

  it('refuses a bad setting without a change or an event', () => {
    const state = new AppState();
    const { changes } = recorded(state);
    expect(() => state.setOptions({ tool: 'brush', dragIntegration: 'sometimes' })).toThrow(/dragIntegration must be one of/);
    expect(() => state.setOptions({ noSuchSetting: 1 })).toThrow(/unknown setting 'noSuchSetting'/);
    expect(changes).toHaveLength(0);
    expect(state.current.settings.tool).toBe(DEFAULT_SETTINGS.tool);
  });

  it('reports a write to the settings\' store (the loader\'s) as its own change', () => {
    const state = new AppState();
    const { changes } = recorded(state);
    state.settings.update({ basis: 'spectral' });
    expect(changes.map((c) => c.change)).toEqual([{ settings: { basis: 'spectral' } }]);
    expect(state.current.settings.basis).toBe('spectral');
  });

  it('setPanelOpen takes a boolean and fires only when the panel opens or closes', () => {
    const state = new AppState();
    const { changes } = recorded(state);
    expect(() => state.setPanelOpen('yes')).toThrow(InputError);
    state.setPanelOpen(false); // already closed
    state.setPanelOpen(true);
    state.setPanelOpen(true);
    expect(changes.map((c) => c.change)).toEqual([{ panelOpen: true }]);
  });

  it('update fires once for several parts, names only those that changed, and compares field by field', () => {
    const state = new AppState();
    const { changes } = recorded(state);
    const handles = { fixed: 1, moving: 1, selected: 0, canUndo: true, canRedo: false };
    state.update({ handles, stepping: { ...state.current.stepping }, views: { compare: null, keys: ['subspace'] } });
    expect(changes).toHaveLength(1);
    expect(Object.keys(changes[0].change).sort()).toEqual(['handles', 'views']);
    state.update({ handles: { ...handles }, views: { compare: null, keys: ['subspace'] } }); // equal again: nothing
    expect(changes).toHaveLength(1);
    state.update({ views: { compare: true, keys: ['subspace', 'arap'] } });
    expect(changes[1].change).toEqual({ views: { compare: true, keys: ['subspace', 'arap'] } });
    state.update({ lesson: null, model: null }); // as they were: nothing
    expect(changes).toHaveLength(2);
    expect(() => state.update({ camera: 1 })).toThrow(/unknown part 'camera'/);
    expect(STATE_PARTS).toEqual(expect.arrayContaining(['model', 'lesson', 'handles', 'stepping', 'views', 'panelOpen']));
  });

  it('stops calling a listener once it unsubscribes, and keeps calling the others', () => {
    const state = new AppState();
    const first = recorded(state);
    const second = recorded(state);
    first.unsubscribe();
    state.setOptions({ wireframe: true });
    expect(first.changes).toHaveLength(0);
    expect(second.changes).toHaveLength(1);
  });

  it('does not call a listener that an earlier one unsubscribed during the same change', () => {
    const state = new AppState();
    const heard = [];
    state.subscribe(() => { heard.push('first'); unsubscribeSecond(); });
    const unsubscribeSecond = state.subscribe(() => heard.push('second'));
    state.setOptions({ flatShading: true });
    state.setOptions({ flatShading: false });
    expect(heard).toEqual(['first', 'first']);
  });

  it('hands out a frozen snapshot, the same until the next change', () => {
    const state = new AppState();
    const before = state.current;
    expect(state.current).toBe(before);
    expect(Object.isFrozen(before) && Object.isFrozen(before.settings)).toBe(true);
    expect(() => { before.settings.tool = 'lasso'; }).toThrow(TypeError);
    state.setOptions({ tool: 'lasso' });
    expect(state.current).not.toBe(before);
    expect(before.settings.tool).toBe(DEFAULT_SETTINGS.tool);
  });
});

describe('collaboratorState', () => {
  // Stand-ins with what the summary reads of each collaborator.
  const collaborators = (over = {}) => ({
    model: null,
    views: { compare: false, list: [{ key: 'subspace' }] },
    editor: { summary: () => ({ fixed: 0, moving: 0, selected: 0 }) },
    skeleton: { joints: 0, bones: 0, enabled: true },
    timeline: { canUndo: false, canRedo: false },
    stepping: { paused: false, hasArap: false, nextPhase: 'local' },
    parts: { painting: false, current: 0, count: 0 },
    influence: { picking: false, column: null },
    ...over,
  });

  it('summarises the volume parts, the influence view and the skeleton, which the panel shows from the state', () => {
    const state = new AppState();
    state.update(collaboratorState(collaborators()));
    const { changes } = recorded(state);
    state.update(collaboratorState(collaborators())); // nothing changed: no event
    expect(changes).toHaveLength(0);
    state.update(collaboratorState(collaborators({ parts: { painting: true, current: 3, count: 2 }, influence: { picking: true, column: 7 },
      skeleton: { joints: 2, bones: 1, enabled: false }, timeline: { canUndo: true, canRedo: false } })));
    expect(changes).toHaveLength(1);
    expect(Object.keys(changes[0].change).sort()).toEqual(['handles', 'influence', 'parts', 'skeleton']);
    expect(changes[0].current.parts).toEqual({ painting: true, current: 3, count: 2 });
    expect(changes[0].current.influence).toEqual({ picking: true, column: 7 });
    expect(changes[0].current.skeleton).toEqual({ joints: 2, bones: 1, enabled: false });
    expect(changes[0].current.handles.canUndo).toBe(true); // the one timeline of handle, skeleton and paint edits
  });
});
