// The control panel (lil-gui): model, solver options, handle editing, display, export and live stats.
// It calls only the app's public API, so everything it does is also scriptable, and follows the app through
// its events ('load', 'options', 'compare', 'handles', 'stats', 'dispose'); the app never calls into it.
import GUI from 'lil-gui';
import { JACOBIANS, METHODS, optionSchema } from '../../lib/options.js';
import { CAGE_VERTICES_RANGE } from '../settings.js';
import { panelStats } from '../stats_format.js';
import { downloadObj, downloadScene, downloadScreenshot } from './download.js';

const ITERATION_CHOICES = { 'auto (frame budget)': 'auto', 1: 1, 2: 2, 3: 3, 5: 5, 10: 10, 20: 20 };
const STAT_ROWS = { status: 'status', merit: 'merit', volume: 'volume change', iterations: 'iterations', msPerIteration: 'ms / iteration', fps: 'fps' };

export class ControlPanel {
  /**
   * @param {import('../deformer_app.js').DeformerApp} app
   * @param {{ closed?: boolean, beside?: boolean }} [options] beside: the views make room for the open panel
   */
  constructor(app, { closed = false, beside = true } = {}) {
    this.app = app;
    this.gui = new GUI({ container: app.element, title: 'Subspace deformation', width: 250 });
    if (closed) this.gui.close();
    this.values = app.settings; // a copy, bound to the controllers; changes go through app.setOptions
    this.state = { example: '', compare: app.compare, handleInfo: '', ...Object.fromEntries(Object.keys(STAT_ROWS).map((k) => [k, ''])) };
    this.#build();
    app.element.classList.add('sd-has-panel');
    const onOpenClose = () => app.element.classList.toggle('sd-panel-open', !this.gui._closed && beside);
    this.gui.onOpenClose(onOpenClose);
    onOpenClose();
    this.listeners = {
      load: () => this.#showExamples(),
      options: (e) => this.#showOptions(e.settings),
      compare: (e) => this.#show('compare', e.compare),
      handles: (e) => this.#show('handleInfo', `${e.fixed} fixed, ${e.moving} moving; ${e.selected} selected`),
      stats: (e) => this.#showStats(e.stats),
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
    const set = (key) => (value) => app.setOptions({ [key]: value });
    const button = (folder, name, run) => folder.add({ [name]: run }, name);
    const quietly = (promise) => promise.catch(() => {}); // failures are shown in the page

    const model = this.model = this.gui.addFolder('Model');
    this.exampleController = model.add(this.state, 'example', []).name('example');
    button(model, 'open mesh + cage / scene\u2026', () => app.openFilePicker());
    model.add(v, 'cageVertices', CAGE_VERTICES_RANGE.min, CAGE_VERTICES_RANGE.max, 1).name('cage vertices').onFinishChange(set('cageVertices'));
    button(model, 'generate cage for this mesh', () => quietly(app.generateCage(Math.round(v.cageVertices))));
    this.compareController = model.add(this.state, 'compare').name('compare ARAP | subspace | full')
      .onChange((on) => quietly(app.setCompare(on)));

    const solver = this.gui.addFolder('Solver');
    solver.add(v, 'method', METHODS).name('method').onChange(set('method'));
    solver.add(v, 'jacobian', JACOBIANS).name('Jacobian').onChange(set('jacobian'));
    solver.add(v, 'volume').name('volume constraint').onChange(set('volume'));
    solver.add(v, 'positionWeight', 0.01, 100).name('position weight').onFinishChange(set('positionWeight'));
    solver.add(v, 'c1', 1e-6, 0.5).name('Armijo c1').onFinishChange(set('c1'));
    solver.add(v, 'c2', 0.1, 0.9).name('backtrack c2').onFinishChange(set('c2'));
    solver.add(v, 'maxIterations', 1, 1000, 1).name('max iterations').onFinishChange(set('maxIterations'));
    solver.add(v, 'arapMaxIterations', 1, 5000, 1).name('ARAP max iterations').onFinishChange(set('arapMaxIterations'));
    solver.add(v, 'iterationsPerFrame', ITERATION_CHOICES).name('iterations / request').onChange(set('iterationsPerFrame'));
    button(solver, 'reset to rest pose', () => app.reset());
    for (const c of solver.controllers) { // the library's one-line description of each option, on hover
      const option = optionSchema(c.property);
      if (option) c.domElement.title = option.doc;
    }

    const handles = this.gui.addFolder('Handles');
    this.infoController = handles.add(this.state, 'handleInfo').name('groups').disable();
    button(handles, 'add fixed group (F)', () => app.addGroupFromSelection(false));
    button(handles, 'add moving group (M)', () => app.addGroupFromSelection(true));
    button(handles, 'remove active group (Del)', () => app.removeActiveGroup());
    button(handles, 'clear groups', () => app.clearGroups());
    button(handles, 'clear selection (Esc)', () => app.clearSelection());
    button(handles, 'undo (Ctrl+Z)', () => app.undo());
    button(handles, 'redo (Ctrl+Shift+Z)', () => app.redo());
    button(handles, 'undo all displacement', () => app.resetHandles());
    handles.add(v, 'gizmoMode', ['translate', 'rotate']).name('gizmo (T / R)').onChange(set('gizmoMode'));
    handles.add(v, 'brushRadius', 0.005, 0.2).name('brush radius').onChange(set('brushRadius'));

    const display = this.gui.addFolder('Display');
    display.add(v, 'showCage').name('show cage (C)').onChange(set('showCage'));
    display.add(v, 'showHandles').name('show handles').onChange(set('showHandles'));
    display.add(v, 'wireframe').name('wireframe').onChange(set('wireframe'));
    display.add(v, 'flatShading').name('flat shading').onChange(set('flatShading'));

    const files = this.gui.addFolder('Export');
    button(files, 'deformed mesh (OBJ)', () => downloadObj(app, 'mesh'));
    button(files, 'deformed cage (OBJ)', () => downloadObj(app, 'cage'));
    button(files, 'cage at rest (OBJ)', () => downloadObj(app, 'restCage'));
    button(files, 'save scene (JSON)', () => downloadScene(app));
    button(files, 'load scene\u2026', () => app.openFilePicker());
    button(files, 'screenshot (PNG)', () => downloadScreenshot(app));
    files.close();

    const stats = this.gui.addFolder('Stats');
    this.statControllers = Object.entries(STAT_ROWS).map(([key, name]) => stats.add(this.state, key).name(name).disable());
  }

  /** The example menu for the names the loaded model brought, showing the current one. */
  #showExamples() {
    const app = this.app;
    const names = app.exampleNames;
    const current = app.model?.source?.example ?? (names.includes(app.model?.name) ? app.model.name : '');
    this.state.example = current;
    this.exampleController.destroy();
    this.exampleController = this.model.add(this.state, 'example', names).name('example')
      .onChange((name) => app.loadExample(name).catch(() => {}));
    this.model.$children.prepend(this.exampleController.domElement); // keep "example" first in its folder
  }

  #showOptions(settings) {
    Object.assign(this.values, settings);
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
