// The control panel (lil-gui): model, solver options, handle editing, display, export and live stats.
// It only calls the app's public methods, so everything it does is also scriptable.
import GUI from 'lil-gui';
import { METHODS } from '../methods.js';
import { CAGE_VERTICES_RANGE } from '../deformer_app.js';

const ITERATION_CHOICES = { 'auto (frame budget)': 'auto', 1: 1, 2: 2, 3: 3, 5: 5, 10: 10, 20: 20 };

export function buildPanel(app, { closed = false } = {}) {
  const gui = new GUI({ container: app.root, title: 'Subspace deformation', width: 250 });
  if (closed) gui.close();
  const s = app.settings;
  const state = {
    example: '',
    compare: app.compare,
    openFiles: () => app.openFilePicker(),
    reset: () => app.reset(),
    resetHandles: () => app.resetHandles(),
    addFixed: () => app.addGroupFromSelection(false),
    addMoving: () => app.addGroupFromSelection(true),
    removeGroup: () => app.removeActiveGroup(),
    clearGroups: () => app.handles.clear(),
    clearSelection: () => app.clearSelection(),
    undo: () => app.undo(),
    redo: () => app.redo(),
    exportMesh: () => app.downloadObj('mesh'),
    exportCage: () => app.downloadObj('cage'),
    exportRestCage: () => app.downloadObj('restCage'),
    generateCage: () => app.generateCage(Math.round(s.cageVertices)).catch(() => {}),
    saveScene: () => app.downloadScene(),
    loadScene: () => app.openFilePicker(),
    screenshot: () => app.downloadScreenshot(),
    handleInfo: '',
    status: '',
    merit: '',
    volume: '',
    iterations: '',
    msPerIteration: '',
    fps: '',
  };
  const set = (key) => (value) => app.setOptions({ [key]: value });

  const model = gui.addFolder('Model');
  let exampleController = model.add(state, 'example', []).name('example');
  model.add(state, 'openFiles').name('open mesh + cage / scene\u2026');
  model.add(s, 'cageVertices', CAGE_VERTICES_RANGE.min, CAGE_VERTICES_RANGE.max, 1).name('cage vertices');
  model.add(state, 'generateCage').name('generate cage for this mesh');
  model.add(state, 'compare').name('compare ARAP | subspace | full').onChange((on) => app.setCompare(on).catch(() => {}));

  const solver = gui.addFolder('Solver');
  const methodController = solver.add(s, 'method', METHODS).name('method').onChange(set('method'));
  solver.add(s, 'jacobian', ['fast', 'exact']).name('Jacobian').onChange(set('jacobian'));
  solver.add(s, 'volume').name('volume constraint').onChange(set('volume'));
  solver.add(s, 'positionWeight', 0.01, 100).name('position weight').onFinishChange(set('positionWeight'));
  solver.add(s, 'c1', 1e-6, 0.5).name('Armijo c1').onFinishChange(set('c1'));
  solver.add(s, 'c2', 0.1, 0.9).name('backtrack c2').onFinishChange(set('c2'));
  solver.add(s, 'maxIterations', 1, 1000, 1).name('max iterations').onFinishChange(set('maxIterations'));
  solver.add(s, 'arapMaxIterations', 1, 5000, 1).name('ARAP max iterations').onFinishChange(set('arapMaxIterations'));
  solver.add(s, 'iterationsPerFrame', ITERATION_CHOICES).name('iterations / request').onChange(set('iterationsPerFrame'));
  solver.add(state, 'reset').name('reset to rest pose');

  const handles = gui.addFolder('Handles');
  const info = handles.add(state, 'handleInfo').name('groups').disable();
  handles.add(state, 'addFixed').name('add fixed group (F)');
  handles.add(state, 'addMoving').name('add moving group (M)');
  handles.add(state, 'removeGroup').name('remove active group (Del)');
  handles.add(state, 'clearGroups').name('clear groups');
  handles.add(state, 'clearSelection').name('clear selection (Esc)');
  handles.add(state, 'undo').name('undo (Ctrl+Z)');
  handles.add(state, 'redo').name('redo (Ctrl+Shift+Z)');
  handles.add(state, 'resetHandles').name('undo all displacement');
  handles.add(s, 'gizmoMode', ['translate', 'rotate']).name('gizmo (T / R)').onChange(set('gizmoMode'));
  handles.add(s, 'brushRadius', 0.005, 0.2).name('brush radius').onChange(set('brushRadius'));

  const display = gui.addFolder('Display');
  display.add(s, 'showCage').name('show cage (C)').onChange(set('showCage'));
  display.add(s, 'showHandles').name('show handles').onChange(set('showHandles'));
  display.add(s, 'wireframe').name('wireframe').onChange(set('wireframe'));
  display.add(s, 'flatShading').name('flat shading').onChange(set('flatShading'));

  const files = gui.addFolder('Export');
  files.add(state, 'exportMesh').name('deformed mesh (OBJ)');
  files.add(state, 'exportCage').name('deformed cage (OBJ)');
  files.add(state, 'exportRestCage').name('cage at rest (OBJ)');
  files.add(state, 'saveScene').name('save scene (JSON)');
  files.add(state, 'loadScene').name('load scene\u2026');
  files.add(state, 'screenshot').name('screenshot (PNG)');
  files.close();

  const stats = gui.addFolder('Stats');
  const statControllers = ['status', 'merit', 'volume', 'iterations', 'msPerIteration', 'fps'].map((key) =>
    stats.add(state, key).name({ volume: 'volume change', msPerIteration: 'ms / iteration' }[key] ?? key).disable());

  return {
    gui,
    onModel() {
      const names = app.exampleNames;
      state.example = app.model?.source?.example ?? (names.includes(app.model?.name) ? app.model.name : '');
      exampleController.destroy();
      exampleController = model.add(state, 'example', names).name('example').onChange((name) => app.loadExample(name).catch(() => {}));
      // Keep "example" first in its folder.
      model.$children.prepend(exampleController.domElement);
      info.updateDisplay();
    },
    onHandles() {
      const g = app.handles.groups;
      const fixed = g.filter((x) => !x.moving).length;
      state.handleInfo = `${fixed} fixed, ${g.length - fixed} moving; ${app.selection.size} selected`;
      info.updateDisplay();
    },
    onStats() {
      const st = app.stats;
      state.status = st.state === 'stopped' || st.state === 'error' ? `${st.state}: ${st.stopReason}` : st.state;
      state.merit = st.merit.toExponential(3);
      state.volume = `${(100 * st.volumeRelError).toFixed(6)} %`;
      state.iterations = String(st.iterations);
      state.msPerIteration = st.msPerIteration.toFixed(2);
      state.fps = st.fps.toFixed(0);
      for (const c of statControllers) c.updateDisplay();
    },
    refresh() {
      state.compare = app.compare;
      methodController.updateDisplay();
      for (const c of gui.controllersRecursive()) c.updateDisplay();
    },
    dispose() {
      gui.destroy();
    },
  };
}
