// The control panel (lil-gui): model, solver options, handle editing, display, export and live stats.
// It never holds the app: it shows the app's state (app_state.js: settings, model, views, handles, parts, influence,
// skeleton, lesson, panelOpen), follows its one change event, and sends intents (app_intents.js), each the public
// API a script would call, so everything it does is also scriptable; the few things the state does not hold (the
// example names, the skeleton's report, the stats of each tick) it reads through queries. The app calls only dispose().
import GUI from 'lil-gui';
import { optionSchema } from '../../lib/options.js';
import { pageCores } from '../../lib/load.js';
import { COORDINATES } from '../../lib/coordinates.js';
import { isSpectral } from '../../lib/subspace.js';
import { AUTO_PARTS_RANGE, CAGE_VERTICES_RANGE, SOLVER_CONTROLS, SPECTRAL_MODES_RANGE, countChoices, settingSchema } from '../settings.js';
import { COORDINATE_LABELS } from '../methods.js';
import { MAX_PARTS } from '../parts/parts_painter.js';
import { LESSON_IDS } from '../lessons/catalogue.js';
import { skeletonFolder } from '../skeleton/skeleton_panel.js';
import { panelStats } from '../stats_format.js';

const COORDINATE_CHOICES = Object.fromEntries(COORDINATES.types.map((t) => [`${COORDINATE_LABELS[t]} (${t})`, t]));
// The panel's sliders stop below the library's limits (1024): a finer grid or sampling is for the CLI.
const PMVC_SLIDER = { min: COORDINATES.pmvcResolution.min, max: 128 };
const HARMONIC_SLIDER = { min: 0, max: 256 };
// px: every name and value fits (tests/e2e/stats.test.mjs checks none is cut). lil-gui's touch styles (a coarse
// pointer: 13 px names, 16 px inputs, so that iOS does not zoom into a field) need more: at 290 px a tablet showed
// "harmonic (harmon" and "auto (frame budg" (a choice too wide wraps out of sight).
const WIDTH = 290;
const TOUCH_WIDTH = 320;
const panelWidth = () => (globalThis.matchMedia?.('(pointer: coarse)').matches ? TOUCH_WIDTH : WIDTH);
const STAT_ROWS = { status: 'status', merit: 'merit', volume: 'volume change', parts: 'volume parts', iterations: 'iterations',
  msPerIteration: 'ms / iteration', fps: 'fps' };

/**
 * One row of the Solver folder from its row of SOLVER_CONTROLS: a choice list (the default first), a checkbox, or
 * a slider (integers by 1). A choice or a checkbox sends its value when changed, a slider when let go.
 */
function solverControl(folder, values, { key, label, min, max, choices }, send) {
  const schema = settingSchema(key);
  const list = choices ?? (schema.kind === 'choice' ? [schema.default, ...schema.choices.filter((c) => c !== schema.default)] : null);
  if (list) return folder.add(values, key, list).name(label).onChange(send);
  if (schema.kind === 'boolean') return folder.add(values, key).name(label).onChange(send);
  return folder.add(values, key, min, max, schema.kind === 'integer' ? 1 : undefined).name(label).onFinishChange(send);
}

export class ControlPanel {
  /**
   * @param {HTMLElement} element the app's root element (the panel goes inside it)
   * @param {{ state: import('../app_state.js').AppState, intents: ReturnType<typeof import('../app_intents.js').appIntents>,
   *           queries: ReturnType<typeof import('../app_intents.js').appQueries>, compact?: boolean, closed?: boolean,
   *           beside?: boolean, shareLink?: boolean }} options state: what the controls show; intents: what they do;
   *   queries: what the state does not hold; compact: a small screen (start closed); beside: the views make room for
   *   the open panel; shareLink: offer "copy link to this pose"
   */
  constructor(element, { state, intents, queries, compact = false, closed = false, beside = true, shareLink = false }) {
    Object.assign(this, { element, appState: state, intents, queries, shareLink });
    const width = panelWidth();
    this.gui = new GUI({ container: element, title: 'Subspace deformation', width });
    element.style.setProperty('--sd-panel-width', `${width}px`);
    // Small screens (a phone, a narrow embed) start with the whole view; the panel then opens over it.
    if (closed || compact) this.gui.close();
    const current = state.current;
    this.values = { ...current.settings }; // a copy, bound to the controllers; changes go through setOptions
    // "compare coordinates" (views keyed 'subspace:<coordinates>') is its own box, not "compare methods".
    const types = current.views.keys.some((key) => key.includes(':'));
    this.state = { example: '', lesson: '', compare: current.views.compare && !types, groups: '', selected: '', threads: 'auto', painting: false,
      part: 0, compareTypes: types, picking: false, column: 0,
      ...Object.fromEntries(Object.keys(STAT_ROWS).map((k) => [k, ''])) };
    this.#build();
    element.classList.add('sd-has-panel');
    element.classList.toggle('sd-panel-float', !beside);
    // Its title and the tool strip's panel button open and close it; the app's state holds whether it is open.
    const onOpenClose = (gui) => {
      if (gui !== this.gui) return; // a folder
      element.classList.toggle('sd-panel-open', !this.gui._closed);
      intents.setPanelOpen(!this.gui._closed);
    };
    this.gui.onOpenClose(onOpenClose);
    onOpenClose(this.gui);
    this.unsubscribe = state.subscribe((change, now) => this.#follow(change, now));
    this.stopStats = queries.followStats((stats) => this.#showStats(stats));
  }

  // One change of the app's state: each control shows its part.
  #follow(change, now) {
    if ('panelOpen' in change && change.panelOpen === this.gui._closed) this.gui.open(change.panelOpen);
    if (change.model) {
      this.#showExamples(now.model);
      this.#showThreads(now.model.solver);
      this.columnController.max(Math.max(0, now.model.basisSize - 1));
    }
    if (change.settings) this.#showOptions(now.settings);
    if (change.views) {
      const types = change.views.keys.some((key) => key.includes(':'));
      this.#show('compare', change.views.compare && !types);
      this.#show('compareTypes', types);
    }
    if (change.influence) {
      this.#show('picking', change.influence.picking);
      if (change.influence.column !== null) this.#show('column', change.influence.column);
    }
    if (change.handles) {
      this.#show('groups', `${change.handles.fixed} fixed, ${change.handles.moving} moving`);
      this.#show('selected', `${change.handles.selected} vertices`);
    }
    if (change.parts) {
      this.#show('painting', change.parts.painting);
      this.#show('part', change.parts.current);
    }
    if ('lesson' in change) this.#show('lesson', change.lesson?.id ?? '');
    this.skeleton.follow(change);
  }

  dispose() {
    this.disposed = true;
    this.unsubscribe();
    this.stopStats();
    this.gui.destroy();
  }

  #build() {
    const { intents, values: v } = this;
    const set = (key) => (value) => this.appState.setOptions({ [key]: value });
    const button = (folder, name, run) => folder.add({ [name]: run }, name);

    const model = this.model = this.gui.addFolder('Model');
    this.exampleController = model.add(this.state, 'example', []).name('example');
    model.add(this.state, 'lesson', ['', ...LESSON_IDS]).name('lesson').onChange((id) => this.#chooseLesson(id));
    button(model, 'open mesh + cage / scene\u2026', () => intents.openFilePicker());
    model.add(v, 'cageVertices', CAGE_VERTICES_RANGE.min, CAGE_VERTICES_RANGE.max, 1).name('cage vertices').onFinishChange(set('cageVertices'));
    button(model, 'generate cage for this mesh', () => intents.generateCage(Math.round(v.cageVertices)));
    this.compareController = model.add(this.state, 'compare').name('compare methods')
      .onChange((on) => intents.setCompare(on));
    this.compareController.domElement.title = 'ARAP | subspace | full space side by side, each in its own worker';
    // The subspace basis: changing it binds the model again (the spectral basis needs no cage).
    model.add(v, 'basis', ['cage', 'spectral']).name('subspace basis').onChange((basis) => intents.setBasis(basis));
    model.add(v, 'spectralModes', SPECTRAL_MODES_RANGE.min, SPECTRAL_MODES_RANGE.max, 1).name('spectral modes')
      .onFinishChange((modes) => (isSpectral(this.appState.current.settings) ? intents.setBasis('spectral', modes) : intents.setOptions({ spectralModes: modes })));
    this.#coordinateControls(model);

    const solver = this.gui.addFolder('Solver');
    for (const row of SOLVER_CONTROLS) solverControl(solver, v, row, set(row.key)); // settings.js' table
    this.threadsFolder = solver;
    this.threadsController = null;
    this.#showThreads(this.appState.current.model?.solver);
    button(solver, 're-solve from rest (same targets)', () => intents.resolveFromRest());
    for (const c of solver.controllers) { // the library's one-line description of each option, on hover
      const option = optionSchema(c.property);
      if (option) c.domElement.title = option.doc;
    }

    const handles = this.gui.addFolder('Handles');
    handles.add(this.state, 'groups').name('groups').disable();
    handles.add(this.state, 'selected').name('selected').disable();
    button(handles, 'add fixed group (F)', () => intents.addGroupFromSelection(false));
    button(handles, 'add moving group (M)', () => intents.addGroupFromSelection(true));
    button(handles, 'remove active group (Del)', () => intents.removeActiveGroup());
    button(handles, 'clear groups', () => intents.clearGroups());
    button(handles, 'clear selection (Esc)', () => intents.clearSelection());
    button(handles, 'undo (Ctrl+Z)', () => intents.undo());
    button(handles, 'redo (Ctrl+Shift+Z)', () => intents.redo());
    button(handles, 'reset pose and handles', () => intents.resetHandles());
    handles.add(v, 'gizmoMode', ['translate', 'rotate']).name('gizmo (T / R)').onChange(set('gizmoMode'));
    handles.add(v, 'brushRadius', 0.005, 0.2).name('brush radius').onChange(set('brushRadius'));

    const parts = this.gui.addFolder('Volume parts');
    parts.add(this.state, 'painting').name('paint parts (P)').onChange((on) => intents.setPainting(on));
    parts.add(this.state, 'part', 0, MAX_PARTS - 1, 1).name('painted part').onFinishChange((k) => intents.setPaintedPart(Math.round(k)));
    button(parts, 'keep painted parts', () => intents.keepPaintedParts());
    parts.add(v, 'autoParts', AUTO_PARTS_RANGE.min, AUTO_PARTS_RANGE.max, 1).name('auto parts K').onFinishChange(set('autoParts'));
    button(parts, 'auto parts', () => intents.autoParts(Math.round(this.appState.current.settings.autoParts)));
    button(parts, 'default (one volume per component)', () => intents.defaultParts());
    button(parts, 'one global volume', () => intents.useParts('global'));
    parts.close();
    // the bone tool, bones kept or not, their errors
    this.skeleton = skeletonFolder(this.gui, { settings: this.appState.current.settings, intents, report: this.queries.skeletonReport });

    const display = this.gui.addFolder('Display');
    display.add(v, 'showCage').name('show cage (C)').onChange(set('showCage'));
    display.add(v, 'showHandles').name('show handles').onChange(set('showHandles'));
    display.add(v, 'wireframe').name('wireframe').onChange(set('wireframe'));
    display.add(v, 'flatShading').name('flat shading').onChange(set('flatShading'));
    button(display, 'fit view (V)', () => intents.fitView());

    const influence = this.gui.addFolder('Influence');
    influence.add(this.state, 'picking').name('click a cage vertex (I)').onChange((on) => intents.setPicking(on));
    this.columnController = influence.add(this.state, 'column', 0, 1, 1).name('show cage vertex / column')
      .onFinishChange((j) => intents.showInfluence(Math.round(j)));
    button(influence, 'hide influence', () => intents.hideInfluence());
    influence.domElement.title = 'colour the mesh by one cage vertex\'s weight (negative weights in blue)';

    const files = this.gui.addFolder('Export');
    button(files, 'deformed mesh (OBJ)', () => intents.downloadObj('mesh'));
    button(files, 'deformed mesh (glTF .glb)', () => intents.downloadGlb());
    button(files, 'deformed cage (OBJ)', () => intents.downloadObj('cage'));
    button(files, 'cage at rest (OBJ)', () => intents.downloadObj('restCage'));
    button(files, 'save scene (JSON)', () => intents.downloadScene());
    button(files, 'load scene\u2026', () => intents.openFilePicker());
    button(files, 'screenshot (PNG)', () => intents.downloadScreenshot());
    if (this.shareLink) button(files, 'copy link to this pose', () => intents.copyPoseLink());
    files.close();

    const stats = this.gui.addFolder('Stats');
    this.statControllers = Object.entries(STAT_ROWS).map(([key, name]) => stats.add(this.state, key).name(name).disable());
  }

  /**
   * The cage's coordinates (binding the model again, handles and parts kept), each type's resolution, and
   * "compare coordinates": the subspace solve with the chosen coordinates beside the same with a second type.
   */
  #coordinateControls(folder) {
    const { intents, values: v } = this;
    // The settings change only once the model is bound again: after a refusal or a Cancel the controls show again
    // what is in effect, not the choice that did not take.
    const bind = (...args) =>
      Promise.resolve(intents.setCoordinates(...args)).then(() => this.#showOptions(this.appState.current.settings));
    folder.add(v, 'coordinates', COORDINATE_CHOICES).name('cage coordinates').onChange((c) => bind(c));
    const resolution = (key, type, { min, max }, name) => folder.add(v, key, min, max, 1).name(name).onFinishChange((r) => {
      const { coordinates, basis } = this.appState.current.settings;
      if (coordinates === type && basis === 'cage') bind(type, Math.round(r));
      else intents.setOptions({ [key]: Math.round(r) });
    });
    resolution('pmvcResolution', 'pmvc', PMVC_SLIDER, 'pmvc resolution').domElement.title =
      'positive mean value coordinates: the hidden parts are sampled in cells of a cube map with this many pixels per side';
    resolution('harmonicResolution', 'harmonic', HARMONIC_SLIDER, 'harmonic grid (0: auto)').domElement.title =
      'harmonic coordinates: grid cells along the longest side of the cage\'s box (0: chosen from the cage)';
    folder.add(this.state, 'compareTypes').name('compare coordinates').onChange((on) => intents.setCompare(on ? 'coordinates' : false))
      .domElement.title = 'the subspace solve with these coordinates beside the same with the "compare with" coordinates';
    folder.add(v, 'compareCoordinates', COORDINATE_CHOICES).name('compare with').onChange((c) => intents.setOptions({ compareCoordinates: c }));
  }

  /**
   * The example menu for the names the loaded model brought, showing the current one; a model from a file is
   * named in it too ("cow.obj (file)"), so the menu never goes blank, and choosing that entry changes nothing.
   */
  #showExamples(model) {
    const names = this.queries.exampleNames();
    const example = model.source?.example ?? (names.includes(model.name) ? model.name : null);
    const file = !example ? `${model.name} (file)` : null;
    this.state.example = example ?? file ?? '';
    this.exampleController.destroy();
    this.exampleController = this.model.add(this.state, 'example', file ? [file, ...names] : names).name('example')
      .onChange((name) => names.includes(name) && this.#settled('example', this.intents.loadExample(name)));
    this.model.$children.prepend(this.exampleController.domElement); // keep "example" first in its folder
  }

  // The lesson menu: a lesson loads; the blank entry is no action (a lesson ends when another model loads), so the
  // menu goes back to the current lesson.
  #chooseLesson(id) {
    if (id) this.#settled('lesson', this.intents.loadLesson(id));
    else this.#show('lesson', this.appState.current.lesson?.id ?? '');
  }

  #choices = { example: 0, lesson: 0 }; // the menus' choices so far, to know the last one

  /**
   * Once the load chosen in a menu ('example' or 'lesson') settles, the menu shows what the app holds: a choice
   * cancelled (the progress bar) or replaced by a later request changes no state, so nothing else would show it.
   * A later choice in the same menu shows itself.
   */
  #settled(menu, loading) {
    const choice = ++this.#choices[menu];
    Promise.resolve(loading).finally(() => {
      if (choice !== this.#choices[menu] || this.disposed) return;
      const { model, lesson } = this.appState.current;
      if (menu === 'lesson') this.#show('lesson', lesson?.id ?? '');
      else if (model) this.#showExamples(model);
    }).catch(() => {});
  }

  /**
   * The threads row: 'auto' (every core, shared by the views' workers) or a count, on a threaded build; on the
   * single-threaded build (a page without cross-origin isolation) it says so instead, with the reason on hover.
   */
  #showThreads(solver) {
    this.threadsController?.destroy();
    const single = solver?.build === 'single';
    const choices = single ? { '1 (single-threaded build)': 'auto' } : { 'auto (every core)': 'auto' };
    if (!single) Object.assign(choices, countChoices(Array.from({ length: pageCores() }, (_, i) => i + 1), 'thread')); // 'auto' first
    this.state.threads = single ? 'auto' : this.appState.current.settings.threads;
    this.threadsController = this.threadsFolder.add(this.state, 'threads', choices).name('threads')
      .onChange((threads) => this.intents.setOptions({ threads }));
    if (single) this.threadsController.disable();
    this.threadsController.domElement.title = single ? `${solver.buildNote ?? 'single-threaded build'}: one thread per view`
      : 'threads the views\' solver workers share (compare mode: split between the views)';
    const reset = this.threadsFolder.controllers.find((c) => c.property?.startsWith('re-solve'));
    if (reset) this.threadsFolder.$children.insertBefore(this.threadsController.domElement, reset.domElement);
  }

  #showOptions(settings) {
    Object.assign(this.values, settings);
    if (!this.threadsController?._disabled) this.#show('threads', settings.threads);
    for (const c of this.gui.controllersRecursive()) if (c.object === this.values) c.updateDisplay();
  }

  #show(key, value) {
    this.state[key] = value;
    for (const c of this.gui.controllersRecursive()) if (c.object === this.state && c.property === key) c.updateDisplay();
  }

  #showStats(stats) {
    Object.assign(this.state, panelStats(stats));
    for (const c of this.statControllers) c.updateDisplay();
    this.skeleton.showStats();
  }
}
