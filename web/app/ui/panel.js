// The control panel (lil-gui): model, solver options, handle editing, display, export and live stats.
// It calls only the app's public API, so everything it does is also scriptable, and follows the app through
// its events ('load', 'options', 'compare', 'handles', 'stats', 'dispose'); the app never calls into it. Its
// settings controls send their values to the app's state (app_state.js: setOptions, checked there).
import GUI from 'lil-gui';
import { JACOBIANS, METHODS, optionSchema } from '../../lib/options.js';
import { pageCores } from '../../lib/load.js';
import { COORDINATES } from '../../lib/coordinates.js';
import { isSpectral } from '../../lib/subspace.js';
import { AUTO_PARTS_RANGE, CAGE_VERTICES_RANGE, DRAG_INTEGRATIONS, SPECTRAL_MODES_RANGE } from '../settings.js';
import { COORDINATE_LABELS } from '../methods.js';
import { MAX_PARTS } from '../parts/parts_painter.js';
import { LESSON_IDS } from '../lessons/catalogue.js';
import { skeletonFolder } from '../skeleton/skeleton_panel.js';
import { panelStats } from '../stats_format.js';
import { downloadGlb, downloadObj, downloadScene, downloadScreenshot } from './download.js';
import { copyPoseLink } from './share_link.js';

const COORDINATE_CHOICES = Object.fromEntries(COORDINATES.types.map((t) => [`${COORDINATE_LABELS[t]} (${t})`, t]));
// The panel's sliders stop below the library's limits (1024): a finer grid or sampling is for the CLI.
const PMVC_SLIDER = { min: COORDINATES.pmvcResolution.min, max: 128 };
const HARMONIC_SLIDER = { min: 0, max: 256 };
const ITERATION_CHOICES = { 'auto (frame budget)': 'auto', 1: 1, 2: 2, 3: 3, 5: 5, 10: 10, 20: 20 };
const WIDTH = 290; // px: every name and value fits (tests/e2e/stats.test.mjs checks none is cut)
const STAT_ROWS = { status: 'status', merit: 'merit', volume: 'volume change', parts: 'volume parts', iterations: 'iterations',
  msPerIteration: 'ms / iteration', fps: 'fps' };

export class ControlPanel {
  /**
   * @param {import('../deformer_app.js').DeformerApp} app
   * @param {{ state: import('../app_state.js').AppState, closed?: boolean, beside?: boolean }} options state: where
   *   the settings controls send their values; beside: the views make room for the open panel
   */
  constructor(app, { state, closed = false, beside = true }) {
    this.app = app;
    this.appState = state;
    this.gui = new GUI({ container: app.element, title: 'Subspace deformation', width: WIDTH });
    app.element.style.setProperty('--sd-panel-width', `${WIDTH}px`);
    // Small screens (a phone, a narrow embed) start with the whole view; the panel then opens over it.
    if (closed || app.layout.compact) this.gui.close();
    this.values = app.settings; // a copy, bound to the controllers; changes go through app.setOptions
    // "compare coordinates" (views keyed 'subspace:<coordinates>') is its own box, not "compare methods".
    const types = app.views.some((v) => v.key.includes(':'));
    this.state = { example: '', lesson: '', compare: app.compare && !types, groups: '', selected: '', threads: 'auto', painting: false, part: 0,
      compareTypes: types, picking: false, column: 0,
      ...Object.fromEntries(Object.keys(STAT_ROWS).map((k) => [k, ''])) };
    this.#build();
    app.element.classList.add('sd-has-panel');
    app.element.classList.toggle('sd-panel-float', !beside);
    // Its title and the tool strip's panel button open and close it; the app holds the state (its 'panel' event).
    const onOpenClose = (gui) => {
      if (gui !== this.gui) return; // a folder
      app.element.classList.toggle('sd-panel-open', !this.gui._closed);
      app.setPanelOpen(!this.gui._closed);
    };
    this.gui.onOpenClose(onOpenClose);
    onOpenClose(this.gui);
    this.listeners = {
      panel: (e) => {
        if (e.open === this.gui._closed) this.gui.open(e.open);
      },
      load: (e) => {
        this.#showExamples();
        this.#showThreads(e.model.solver);
        this.columnController.max(Math.max(0, e.model.basisSize - 1));
      },
      options: (e) => this.#showOptions(e.settings),
      compare: (e) => {
        const types = e.views.some((key) => key.includes(':'));
        this.#show('compare', e.compare && !types);
        this.#show('compareTypes', types);
      },
      influence: (e) => {
        this.#show('picking', e.picking);
        if (e.column !== null) this.#show('column', e.column);
      },
      handles: (e) => {
        this.#show('groups', `${e.fixed} fixed, ${e.moving} moving`);
        this.#show('selected', `${e.selected} vertices`);
      },
      parts: (e) => {
        this.#show('painting', e.painting);
        this.#show('part', e.current);
      },
      stats: (e) => this.#showStats(e.stats),
      lesson: (e) => this.#show('lesson', e.lesson?.id ?? ''),
      dispose: () => this.dispose(),
    };
    this.connect();
  }

  connect() {
    for (const [type, listener] of Object.entries(this.listeners)) this.app.addEventListener(type, listener);
  }

  disconnect() {
    for (const [type, listener] of Object.entries(this.listeners)) this.app.removeEventListener(type, listener);
  }

  dispose() {
    this.disconnect();
    this.gui.destroy();
  }

  #build() {
    const app = this.app;
    const v = this.values;
    const set = (key) => (value) => this.appState.setOptions({ [key]: value });
    const button = (folder, name, run) => folder.add({ [name]: run }, name);
    const quietly = (promise) => promise.catch(() => {}); // failures are shown in the page

    const model = this.model = this.gui.addFolder('Model');
    this.exampleController = model.add(this.state, 'example', []).name('example');
    model.add(this.state, 'lesson', ['', ...LESSON_IDS]).name('lesson')
      .onChange((id) => id && quietly(app.loadLesson(id)));
    button(model, 'open mesh + cage / scene\u2026', () => app.openFilePicker());
    model.add(v, 'cageVertices', CAGE_VERTICES_RANGE.min, CAGE_VERTICES_RANGE.max, 1).name('cage vertices').onFinishChange(set('cageVertices'));
    button(model, 'generate cage for this mesh', () => quietly(app.generateCage(Math.round(v.cageVertices))));
    this.compareController = model.add(this.state, 'compare').name('compare methods')
      .onChange((on) => quietly(app.setCompare(on)));
    this.compareController.domElement.title = 'ARAP | subspace | full space side by side, each in its own worker';
    // The subspace basis: changing it binds the model again (the spectral basis needs no cage).
    model.add(v, 'basis', ['cage', 'spectral']).name('subspace basis').onChange((basis) => quietly(app.setBasis(basis)));
    model.add(v, 'spectralModes', SPECTRAL_MODES_RANGE.min, SPECTRAL_MODES_RANGE.max, 1).name('spectral modes')
      .onFinishChange((modes) => (isSpectral(app.settings) ? quietly(app.setBasis('spectral', modes)) : app.setOptions({ spectralModes: modes })));
    this.#coordinateControls(model);

    const solver = this.gui.addFolder('Solver');
    solver.add(v, 'method', METHODS).name('method').onChange(set('method'));
    solver.add(v, 'jacobian', JACOBIANS).name('Jacobian').onChange(set('jacobian'));
    solver.add(v, 'volume').name('volume constraint').onChange(set('volume'));
    solver.add(v, 'weighting', optionSchema('weighting').choices).name('energy weighting').onChange(set('weighting'));
    solver.add(v, 'dragIntegration', DRAG_INTEGRATIONS).name('integration while dragging').onChange(set('dragIntegration'));
    solver.add(v, 'positionWeight', 0.01, 100).name('position weight').onFinishChange(set('positionWeight'));
    solver.add(v, 'c1', 1e-6, 0.5).name('Armijo c1').onFinishChange(set('c1'));
    solver.add(v, 'c2', 0.1, 0.9).name('backtrack c2').onFinishChange(set('c2'));
    solver.add(v, 'maxIterations', 1, 1000, 1).name('max iterations').onFinishChange(set('maxIterations'));
    solver.add(v, 'arapMaxIterations', 1, 5000, 1).name('ARAP max iterations').onFinishChange(set('arapMaxIterations'));
    solver.add(v, 'iterationsPerFrame', ITERATION_CHOICES).name('iterations / request').onChange(set('iterationsPerFrame'));
    this.threadsFolder = solver;
    this.threadsController = null;
    this.#showThreads(app.model?.solver);
    button(solver, 're-solve from rest (same targets)', () => quietly(app.resolveFromRest()));
    for (const c of solver.controllers) { // the library's one-line description of each option, on hover
      const option = optionSchema(c.property);
      if (option) c.domElement.title = option.doc;
    }

    const handles = this.gui.addFolder('Handles');
    handles.add(this.state, 'groups').name('groups').disable();
    handles.add(this.state, 'selected').name('selected').disable();
    button(handles, 'add fixed group (F)', () => app.addGroupFromSelection(false));
    button(handles, 'add moving group (M)', () => app.addGroupFromSelection(true));
    button(handles, 'remove active group (Del)', () => app.removeActiveGroup());
    button(handles, 'clear groups', () => app.clearGroups());
    button(handles, 'clear selection (Esc)', () => app.clearSelection());
    button(handles, 'undo (Ctrl+Z)', () => app.undo());
    button(handles, 'redo (Ctrl+Shift+Z)', () => app.redo());
    button(handles, 'reset pose and handles', () => quietly(app.resetHandles()));
    handles.add(v, 'gizmoMode', ['translate', 'rotate']).name('gizmo (T / R)').onChange(set('gizmoMode'));
    handles.add(v, 'brushRadius', 0.005, 0.2).name('brush radius').onChange(set('brushRadius'));

    const parts = this.gui.addFolder('Volume parts');
    parts.add(this.state, 'painting').name('paint parts (P)').onChange((on) => app.parts.setPainting(on));
    parts.add(this.state, 'part', 0, MAX_PARTS - 1, 1).name('painted part').onFinishChange((k) => app.parts.setCurrent(Math.round(k)));
    button(parts, 'keep painted parts', () => quietly(app.parts.apply()));
    parts.add(v, 'autoParts', AUTO_PARTS_RANGE.min, AUTO_PARTS_RANGE.max, 1).name('auto parts K').onFinishChange(set('autoParts'));
    button(parts, 'auto parts', () => quietly(app.parts.auto(Math.round(app.settings.autoParts))));
    button(parts, 'default (one volume per component)', () => quietly(app.parts.clear()));
    button(parts, 'one global volume', () => quietly(app.parts.use('global')));
    parts.close();
    skeletonFolder(this.gui, app); // the bone tool, bones kept or not, their errors

    const display = this.gui.addFolder('Display');
    display.add(v, 'showCage').name('show cage (C)').onChange(set('showCage'));
    display.add(v, 'showHandles').name('show handles').onChange(set('showHandles'));
    display.add(v, 'wireframe').name('wireframe').onChange(set('wireframe'));
    display.add(v, 'flatShading').name('flat shading').onChange(set('flatShading'));
    button(display, 'fit view (V)', () => app.fitView());

    const influence = this.gui.addFolder('Influence');
    influence.add(this.state, 'picking').name('click a cage vertex (I)').onChange((on) => app.influence.setPicking(on));
    this.columnController = influence.add(this.state, 'column', 0, 1, 1).name('show cage vertex / column')
      .onFinishChange((j) => quietly(app.influence.show(Math.round(j))));
    button(influence, 'hide influence', () => app.influence.hide());
    influence.domElement.title = 'colour the mesh by one cage vertex\'s weight (negative weights in blue)';

    const files = this.gui.addFolder('Export');
    button(files, 'deformed mesh (OBJ)', () => downloadObj(app, 'mesh'));
    button(files, 'deformed mesh (glTF .glb)', () => downloadGlb(app));
    button(files, 'deformed cage (OBJ)', () => downloadObj(app, 'cage'));
    button(files, 'cage at rest (OBJ)', () => downloadObj(app, 'restCage'));
    button(files, 'save scene (JSON)', () => downloadScene(app));
    button(files, 'load scene\u2026', () => app.openFilePicker());
    button(files, 'screenshot (PNG)', () => downloadScreenshot(app));
    if (app.options.shareLink) button(files, 'copy link to this pose', () => copyPoseLink(app));
    files.close();

    const stats = this.gui.addFolder('Stats');
    this.statControllers = Object.entries(STAT_ROWS).map(([key, name]) => stats.add(this.state, key).name(name).disable());
  }

  /**
   * The cage's coordinates (binding the model again, handles and parts kept), each type's resolution, and
   * "compare coordinates": the subspace solve with the chosen coordinates beside the same with a second type.
   */
  #coordinateControls(folder) {
    const app = this.app;
    const v = this.values;
    const quietly = (promise) => promise.catch(() => {});
    folder.add(v, 'coordinates', COORDINATE_CHOICES).name('cage coordinates').onChange((c) => quietly(app.setCoordinates(c)));
    const resolution = (key, type, { min, max }, name) => folder.add(v, key, min, max, 1).name(name).onFinishChange((r) => {
      if (app.settings.coordinates === type && app.settings.basis === 'cage') quietly(app.setCoordinates(type, Math.round(r)));
      else app.setOptions({ [key]: Math.round(r) });
    });
    resolution('pmvcResolution', 'pmvc', PMVC_SLIDER, 'pmvc resolution').domElement.title =
      'positive mean value coordinates: the hidden parts are sampled in cells of a cube map with this many pixels per side';
    resolution('harmonicResolution', 'harmonic', HARMONIC_SLIDER, 'harmonic grid (0: auto)').domElement.title =
      'harmonic coordinates: grid cells along the longest side of the cage\'s box (0: chosen from the cage)';
    folder.add(this.state, 'compareTypes').name('compare coordinates').onChange((on) => quietly(app.setCompare(on ? 'coordinates' : false)))
      .domElement.title = 'the subspace solve with these coordinates beside the same with the "compare with" coordinates';
    folder.add(v, 'compareCoordinates', COORDINATE_CHOICES).name('compare with').onChange((c) => app.setOptions({ compareCoordinates: c }));
  }

  /**
   * The example menu for the names the loaded model brought, showing the current one; a model from a file is
   * named in it too ("cow.obj (file)"), so the menu never goes blank, and choosing that entry changes nothing.
   */
  #showExamples() {
    const app = this.app;
    const names = app.exampleNames;
    const example = app.model?.source?.example ?? (names.includes(app.model?.name) ? app.model.name : null);
    const file = app.model && !example ? `${app.model.name} (file)` : null;
    this.state.example = example ?? file ?? '';
    this.exampleController.destroy();
    this.exampleController = this.model.add(this.state, 'example', file ? [file, ...names] : names).name('example')
      .onChange((name) => names.includes(name) && app.loadExample(name).catch(() => {}));
    this.model.$children.prepend(this.exampleController.domElement); // keep "example" first in its folder
  }

  /**
   * The threads row: 'auto' (every core, shared by the views' workers) or a count, on a threaded build; on the
   * single-threaded build (a page without cross-origin isolation) it says so instead, with the reason on hover.
   */
  #showThreads(solver) {
    this.threadsController?.destroy();
    const single = solver?.build === 'single';
    const choices = single ? { '1 (single-threaded build)': 'auto' } : { 'auto (every core)': 'auto' };
    if (!single) for (let n = 1; n <= pageCores(); ++n) choices[n] = n;
    this.state.threads = single ? 'auto' : this.app.settings.threads;
    this.threadsController = this.threadsFolder.add(this.state, 'threads', choices).name('threads')
      .onChange((threads) => this.app.setOptions({ threads }));
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
  }
}
