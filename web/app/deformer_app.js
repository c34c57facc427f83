// The interactive deformation app, used full-window by index.html and per element by the embed. It owns the
// handle groups (shared by all views), one view + solver session per method (one, or three in compare
// mode), loading (examples, files, URLs, scenes), the per-frame loop and the scripting API the embed exposes.
import { EventDispatcher, Quaternion, Vector3 } from 'three';
import { Viewport, boxOf } from './view/viewport.js';
import { HandleSet } from './interaction/handle_set.js';
import { VertexPicker } from './interaction/vertex_picker.js';
import { HandleGizmo } from './interaction/handle_gizmo.js';
import { Session } from './session.js';
import { Banner, ProgressBar } from './ui/overlays.js';
import { injectStyles } from './ui/styles.js';
import { buildPanel } from './ui/panel.js';
import { downloadText, downloadDataUrl } from './ui/download.js';
import { parseScene } from '../lib/scene.js';

import { METHODS, COMPARE_METHODS, METHOD_LABELS, METHOD_COLORS } from './methods.js';

export { METHODS, COMPARE_METHODS, METHOD_LABELS };
const MESH_FILE = /\.(obj|off|ply|stl)$/i;

export const DEFAULT_SETTINGS = {
  method: 'subspace',
  jacobian: 'fast',
  volume: true,
  positionWeight: 1,
  c1: 1e-4,
  c2: 0.5,
  maxIterations: 100, // Gauss-Newton (subspace, full): iterations after the last change before "stopped"
  // ARAP's local-global iterations converge linearly: from rest to a large pull they need 70-180+ (bar, sphere;
  // docs/app.md), far more than Gauss-Newton, while each is cheap. Its own cap, so 100 does not stop it early.
  arapMaxIterations: 1000,
  iterationsPerFrame: 'auto',
  showCage: true,
  showHandles: true,
  wireframe: false,
  flatShading: false,
  gizmoMode: 'translate',
  brushRadius: 0.04, // fraction of the bounding-box diagonal
  cageVertices: 120, // target size K of "Generate cage" (docs/cage.md: 20-1000 tested)
};

/** Solver options a scene may set beyond the panel's (tolerances; sent to the worker only when set). */
const EXTRA_SOLVER_KEYS = ['stepTolerance', 'meritTolerance', 'cgTolerance', 'cgMaxIterations', 'cgMemory', 'arapEnergyTolerance',
  'arapAcceleration'];

/** Range of the "Generate cage" size control. */
export const CAGE_VERTICES_RANGE = { min: 20, max: 1000 };

export class DeformerApp extends EventDispatcher {
  /**
   * @param {HTMLElement} container
   * @param {{ example?: string, mesh?: string, cage?: string, scene?: string|object, compare?: boolean|string[],
   *           panel?: boolean|'closed', help?: boolean, settings?: object }} [options]
   */
  constructor(container, options = {}) {
    super();
    injectStyles(container.ownerDocument);
    this.options = options;
    this.settings = { ...DEFAULT_SETTINGS, ...(options.settings ?? {}) };
    this.root = document.createElement('div');
    this.root.className = 'sd-app';
    this.root.tabIndex = 0;
    container.appendChild(this.root);
    this.viewsElement = document.createElement('div');
    this.viewsElement.className = 'sd-views';
    this.root.appendChild(this.viewsElement);
    this.banner = new Banner(this.root);
    this.progress = new ProgressBar(this.root, () => this.cancelLoad());
    this.fpsElement = Object.assign(document.createElement('div'), { className: 'sd-fps' });
    this.viewsElement.appendChild(this.fpsElement);
    if (options.help !== false) {
      const help = Object.assign(document.createElement('div'), { className: 'sd-help' });
      help.textContent = 'click: pick vertex \u00b7 shift-drag: brush \u00b7 alt-drag: lasso \u00b7 +ctrl: remove\n' +
        'F: add fixed group \u00b7 M: add moving group \u00b7 Del: remove group \u00b7 drag the gizmo to deform';
      help.style.whiteSpace = 'pre';
      this.viewsElement.appendChild(help);
      this.helpElement = help;
    }
    const drop = Object.assign(document.createElement('div'), { className: 'sd-drop' });
    drop.textContent = 'Drop a mesh and its cage (OBJ, OFF, PLY, STL) or a scene (.json)';
    this.root.appendChild(drop);
    this.fileInput = Object.assign(document.createElement('input'), { type: 'file', multiple: true, hidden: true });
    this.fileInput.accept = '.obj,.off,.ply,.stl,.json';
    this.fileInput.onchange = () => {
      const files = [...this.fileInput.files];
      this.fileInput.value = '';
      this.loadFiles(files).catch(() => {});
    };
    this.root.appendChild(this.fileInput);

    this.handles = new HandleSet();
    this.handles.addEventListener('change', (e) => this.#onHandlesChanged(e.what));
    this.handles.addEventListener('active', () => this.#refreshHandleViews());
    this.selection = new Set();
    this.views = [];
    this.model = null;
    this.exampleNames = [];
    this.canGenerateCage = false;
    this.fps = 0;
    this.dragging = false;
    this.disposed = false;

    this.#setViews(this.#compareMethods(options.compare) ?? [this.settings.method]);
    if (options.panel !== false) {
      this.panel = buildPanel(this, { closed: options.panel === 'closed' });
      this.root.classList.add('sd-has-panel');
      const onOpen = () => this.root.classList.toggle('sd-panel-open', !this.panel.gui._closed && this.options.panelBeside !== false);
      this.panel.gui.onOpenClose(onOpen);
      onOpen();
    }
    this.#bindKeys();
    this.#bindDrop();

    this.ready = this.#start(options);
    this.ready.catch(() => {}); // failures are shown in the page; awaiting callers still see the rejection
    this.frames = 0;
    this.rendered = 0;
    this.renderFps = 0;
    this.fpsTime = performance.now();
    this.statsTime = 0;
    this.loop = this.loop.bind(this);
    this.raf = requestAnimationFrame(this.loop);
  }

  // ---------------------------------------------------------------- loading

  async #start(options) {
    if (options.scene) return this.loadScene(options.scene);
    if (options.mesh) return this.loadUrls(options.mesh, options.cage);
    return this.loadExample(options.example);
  }

  /** Loads a built-in example (no name: the default one). */
  loadExample(name) {
    return this.#load('loadExample', { name }, { label: `Loading ${name ?? 'example'}`, source: { example: name } });
  }

  /** Fetches a mesh (and cage) by URL, relative to the page. */
  async loadUrls(meshUrl, cageUrl) {
    const files = [];
    for (const url of [meshUrl, cageUrl].filter(Boolean)) {
      const resolved = new URL(url, document.baseURI);
      const response = await fetch(resolved).catch((e) => ({ ok: false, statusText: e.message }));
      if (!response.ok) {
        const error = new Error(`could not fetch ${resolved}: ${response.status ?? ''} ${response.statusText}`);
        this.banner.show(error.message);
        throw error;
      }
      files.push({ name: resolved.pathname.split('/').pop(), bytes: new Uint8Array(await response.arrayBuffer()) });
    }
    return this.#loadMeshFiles(files);
  }

  /**
   * Loads dropped / picked files: meshes (the larger is the mesh, the other the cage) and/or a scene .json.
   * Errors are shown in the page; the previous model stays.
   * @param {File[]} files
   */
  async loadFiles(files) {
    const scenes = files.filter((f) => /\.json$/i.test(f.name));
    const meshes = files.filter((f) => MESH_FILE.test(f.name));
    const other = files.filter((f) => !scenes.includes(f) && !meshes.includes(f));
    if (other.length) {
      const error = new Error(`${other.map((f) => f.name).join(', ')}: unsupported file type (use OBJ, OFF, PLY, STL, or a scene .json)`);
      this.banner.show(`${error.message}\nThe previous model is kept.`);
      throw error;
    }
    const read = async (f) => ({ name: f.name, bytes: new Uint8Array(await f.arrayBuffer()) });
    if (scenes.length) {
      return this.loadScene(await scenes[0].text(), { json: true, files: await Promise.all(meshes.map(read)), name: scenes[0].name });
    }
    if (meshes.length > 2) {
      const error = new Error(`drop one mesh and at most one cage (got ${meshes.length} mesh files)`);
      this.banner.show(error.message);
      throw error;
    }
    if (meshes.length === 0) return undefined;
    return this.#loadMeshFiles(await Promise.all(meshes.map(read)));
  }

  async #loadMeshFiles(files, generateCage = null) {
    // The worker's progress phases say what is running (generating a K-vertex cage, computing weights).
    const label = `Loading ${files.map((f) => f.name).join(' + ')}`;
    // Copies stay here so "Generate cage" can retry without asking for the file again.
    const kept = files.map((f) => ({ name: f.name, bytes: f.bytes.slice() }));
    const source = { files: files.map((f) => f.name), ...(generateCage ? { generateCage } : {}) };
    try {
      return await this.#load('loadFiles', { files, generateCage }, { label, source });
    } catch (error) {
      // A lone mesh: offer (again, after a cancelled or failed generation) a cage of a chosen size.
      const fixable = !/cannot get a/.test(error.message); // an open or broken mesh: the checker's findings only
      if (kept.length === 1 && this.canGenerateCage && fixable && (generateCage || /has no cage/.test(error.message))) {
        this.#offerCage(error.message === 'cancelled' ? `Cage generation for ${kept[0].name} cancelled.` : error.message, kept);
      }
      throw error;
    }
  }

  /** The "has no cage" banner with a cage-size field and a "Generate cage" button (which loads the kept file). */
  #offerCage(message, files) {
    this.banner.show(`${message}\nThe previous model is kept.`, {
      actions: [{
        label: 'Generate cage',
        input: { label: 'cage vertices', value: this.settings.cageVertices, ...CAGE_VERTICES_RANGE },
        run: (vertices) => {
          this.settings.cageVertices = vertices;
          this.panel?.refresh();
          this.#loadMeshFiles(files, { vertices }).catch(() => {});
        },
      }],
    });
  }

  /**
   * Replaces the current model's cage by a generated one with about `vertices` vertices (in a fresh worker,
   * with progress and Cancel; on failure the current model stays). Handle groups are kept (same mesh).
   * @param {number} [vertices] target size K (default: settings.cageVertices)
   */
  async generateCage(vertices = this.settings.cageVertices) {
    if (!Number.isInteger(vertices) || vertices < CAGE_VERTICES_RANGE.min || vertices > CAGE_VERTICES_RANGE.max) {
      throw new RangeError(`generateCage: vertices must be an integer from ${CAGE_VERTICES_RANGE.min} to ${CAGE_VERTICES_RANGE.max} (got ${vertices})`);
    }
    await this.ready.catch(() => {});
    if (!this.model) throw new Error('generateCage: no model is loaded');
    const m = this.model;
    const generateCage = { vertices };
    return this.#load('loadMeshes', { name: m.name, mesh: m.mesh, generateCage },
      { label: `New cage for ${m.name}`, source: { ...m.source, generateCage }, keepHandles: true });
  }

  /**
   * Loads a scene (docs/scene-format.md, parsed and validated by lib/scene.js, the CLI's parser): a URL
   * (mesh/cage paths relative to it), an object, or JSON text (with `json: true`). Besides "mesh"/"cage", a scene may name a
   * built-in "example" or ask for a generated cage ("generateCage"). Without "mesh" or "example" the current
   * model stays and gets the scene's handles and options.
   */
  async loadScene(input, { json = false, files = [], baseUrl = document.baseURI, name = 'scene' } = {}) {
    let raw;
    let scene;
    try {
      let text = input;
      if (typeof input === 'string' && !json) {
        const url = new URL(input, document.baseURI);
        const response = await fetch(url).catch((e) => ({ ok: false, statusText: e.message }));
        if (!response.ok) throw new Error(`could not fetch the scene ${url}: ${response.status ?? ''} ${response.statusText}`);
        name = url.pathname.split('/').pop();
        baseUrl = url.href;
        text = await response.text();
      }
      if (typeof text === 'string') {
        try {
          raw = JSON.parse(text);
        } catch (e) {
          throw new Error(`scene: not valid JSON (${e.message})`);
        }
      } else {
        raw = text;
      }
      scene = parseScene(raw, { modelOptional: true });
    } catch (error) {
      error.message = `${name}: ${error.message}`;
      this.banner.show(`${error.message}\nThe previous model is kept.`);
      throw error;
    }
    if (scene.example) {
      await this.loadExample(scene.example);
      if (scene.generateCage) await this.generateCage(scene.generateCage.vertices);
    } else if (scene.mesh) {
      const fetchOne = async (path) => {
        const local = files.find((f) => f.name === path.split('/').pop());
        if (local) return local;
        const url = new URL(path, baseUrl);
        const response = await fetch(url).catch((e) => ({ ok: false, statusText: e.message }));
        if (!response.ok) {
          throw new Error(`${name} refers to ${path}, which could not be loaded (${response.status ?? ''} ${response.statusText}); ` +
            'drop the scene together with its mesh and cage files');
        }
        return { name: url.pathname.split('/').pop(), bytes: new Uint8Array(await response.arrayBuffer()) };
      };
      let meshFiles;
      try {
        meshFiles = [await fetchOne(scene.mesh), ...(scene.cage ? [await fetchOne(scene.cage)] : [])];
      } catch (error) {
        this.banner.show(`${error.message}\nThe previous model is kept.`);
        throw error;
      }
      await this.#loadMeshFiles(meshFiles, scene.cage ? null : scene.generateCage);
    } else if (!this.model) {
      await this.loadExample();
    }
    this.setOptions(this.#settingsFromScene(scene.solver));
    if (raw.handles) {
      try {
        this.handles.fromScene(raw.handles);
      } catch (error) {
        this.banner.show(`${name}: ${error.message}`);
        throw error;
      }
    }
    this.selection.clear();
    this.#refreshHandleViews();
    return this.model;
  }

  /** Binds a model in the first view's worker, then in the other views; shows progress, keeps the old model on failure. */
  async #load(type, payload, { label, source, keepHandles = false }) {
    this.progress.start(label);
    const [first, ...rest] = this.views;
    first.session.onProgress = (f, phase) => this.progress.set(f, phase);
    let model;
    try {
      model = await first.session.load(type, payload);
      for (const view of rest) {
        await view.session.load('loadMeshes', { name: model.name, description: model.description, mesh: model.mesh, cage: model.cage });
      }
    } catch (error) {
      this.progress.done();
      if (error.message === 'cancelled') this.banner.show('Loading cancelled; the previous model is kept.', { kind: 'info' });
      else this.banner.show(`${error.message}\nThe previous model is kept.`);
      throw error;
    }
    this.progress.done();
    this.exampleNames = model.exampleNames ?? this.exampleNames;
    this.canGenerateCage = !!model.canGenerateCage;
    this.#setModel(model, source, keepHandles);
    return model;
  }

  cancelLoad() {
    for (const view of this.views) view.session.cancelLoad();
  }

  #setModel(model, source, keepHandles = false) {
    // Same mesh, new cage ("Generate cage" on the current model): the groups and their displacements stay.
    const kept = keepHandles && this.handles.groups.length ? this.handles.toScene() : null;
    this.model = { ...model, source };
    this.banner.hide();
    this.selection.clear();
    this.handles.setRest(model.mesh.positions);
    const box = boxOf(model.mesh.positions).union(boxOf(model.cage.positions));
    this.diagonal = box.getSize(new Vector3()).length();
    for (const view of this.views) this.#showModel(view, box);
    if (kept) {
      this.handles.fromScene(kept);
      this.handles.undoStack = [];
    } else {
      this.#defaultHandles(model.defaultHandles);
    }
    this.panel?.onModel();
    this.dispatchEvent({ type: 'load', model: this.model });
  }

  #showModel(view, box) {
    const model = this.model;
    view.positions = model.mesh.positions.slice();
    view.cagePositions = model.cage.positions.slice();
    view.viewport.meshView.setMesh(model.mesh);
    view.viewport.cageView.setCage(model.cage);
    view.viewport.fit(box ?? boxOf(model.mesh.positions).union(boxOf(model.cage.positions)));
    this.#applyDisplay(view);
  }

  /**
   * One end fixed (blue), the other end moving (orange): ready to drag. By default the ends of the longest
   * axis; an example may name the axis and the fractions (the bunny: feet fixed, ears moving).
   * @param {{ axis: number, fixedBelow: number, movingAbove: number }} [spec]
   */
  #defaultHandles(spec) {
    const p = this.model.mesh.positions;
    const box = boxOf(p);
    const size = box.getSize(new Vector3());
    const axis = spec?.axis ?? (size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2);
    const fixedBelow = spec?.fixedBelow ?? 0.08;
    const movingAbove = spec?.movingAbove ?? 0.92;
    const lo = box.min.getComponent(axis);
    const extent = size.getComponent(axis);
    const fixed = [];
    const moving = [];
    for (let v = 0; v < p.length / 3; ++v) {
      const t = (p[3 * v + axis] - lo) / extent;
      if (t <= fixedBelow) fixed.push(v);
      else if (t >= movingAbove) moving.push(v);
    }
    if (fixed.length && moving.length) {
      this.handles.setGroups([fixed, moving], [1]);
      this.handles.undoStack = [];
    }
  }

  // ---------------------------------------------------------------- views

  #compareMethods(compare) {
    if (!compare) return null;
    if (Array.isArray(compare)) return compare.filter((m) => METHODS.includes(m));
    if (typeof compare === 'string' && compare !== 'true' && compare !== '') {
      const list = compare.split(/[\s,|]+/).filter((m) => METHODS.includes(m));
      if (list.length) return list;
    }
    return COMPARE_METHODS;
  }

  get compare() {
    return this.views.length > 1;
  }

  /** Compare mode on/off (or a list of methods). New views bind the current model in their own worker. */
  async setCompare(compare) {
    const methods = this.#compareMethods(compare) ?? [this.settings.method];
    this.#setViews(methods);
    if (!this.model) return;
    const fresh = this.views.filter((v) => !v.session.model);
    this.progress.start('Binding compare views');
    try {
      for (const view of fresh) {
        const m = this.model;
        await view.session.load('loadMeshes', { name: m.name, description: m.description, mesh: m.mesh, cage: m.cage });
        this.#showModel(view);
        this.#applySolverSettings(view);
        view.session.setHandles(this.handles.vertexGroups(), this.handles.targets());
        this.#refreshHandleViews();
      }
    } catch (error) {
      if (error.message !== 'cancelled') this.banner.show(error.message);
      throw error;
    } finally {
      this.progress.done();
    }
    // New view sizes: frame the model again in every view, then link the cameras.
    const box = boxOf(this.model.mesh.positions).union(boxOf(this.model.cage.positions));
    for (const view of this.views) view.viewport.fit(box);
    this.#syncCameras(this.views[0]);
  }

  #setViews(methods) {
    const old = this.views;
    const views = methods.map((method) => {
      const i = old.findIndex((v) => v.method === method);
      return i >= 0 ? old.splice(i, 1)[0] : this.#createView(method);
    });
    if (views.length === 1 && old.length && !views[0].session.model) {
      // Leaving compare mode onto a method that had no view: keep an existing bound view and switch its method.
      views[0].dispose();
      const keep = old.shift();
      keep.setMethod(methods[0]);
      views[0] = keep;
    }
    for (const v of old) v.dispose();
    this.views = views;
    for (const v of views) this.viewsElement.insertBefore(v.viewport.element, this.fpsElement);
    for (const v of views) v.viewport.label.textContent = views.length > 1 || this.options.labels ? METHOD_LABELS[v.method] : '';
  }

  #createView(method) {
    const viewport = new Viewport(this.viewsElement, { label: METHOD_LABELS[method], color: METHOD_COLORS[method] });
    const view = { method, viewport, positions: null, cagePositions: null };
    view.session = new Session({
      method,
      onFrame: (frame, session) => this.#onFrame(view, frame, session),
      onError: (error) => this.banner.show(`${METHOD_LABELS[view.method]}: ${error.message}`),
    });
    view.session.iterationsPerStep = this.settings.iterationsPerFrame;
    view.session.maxIterations = this.#maxIterationsFor(method);
    view.gizmo = new HandleGizmo(viewport, this.handles);
    view.gizmo.setMode(this.settings.gizmoMode);
    view.gizmo.addEventListener('dragstart', () => (this.dragging = true));
    view.gizmo.addEventListener('dragend', () => (this.dragging = false));
    view.picker = new VertexPicker(viewport, {
      isGizmoActive: () => view.gizmo.active,
      brushRadius: () => this.settings.brushRadius * (this.diagonal ?? 1),
    });
    view.picker.addEventListener('pick', (e) => this.#onPick(e.vertex, e.op));
    view.picker.addEventListener('select', (e) => this.#onSelect(e.vertices, e.op));
    viewport.controls.addEventListener('change', () => this.#syncCameras(view));
    view.setMethod = (m) => {
      view.method = m;
      view.session.setMethod(m);
      this.#applySolverSettings(view);
      viewport.label.textContent = METHOD_LABELS[m];
      viewport.plot.color = METHOD_COLORS[m];
    };
    view.dispose = () => {
      view.picker.dispose();
      view.gizmo.dispose();
      view.session.dispose();
      viewport.dispose();
    };
    if (this.views[0]) viewport.camera.copy(this.views[0].viewport.camera);
    return view;
  }

  #syncCameras(source) {
    if (this.syncing) return;
    this.syncing = true;
    for (const view of this.views) {
      if (view === source) continue;
      view.viewport.camera.position.copy(source.viewport.camera.position);
      view.viewport.camera.quaternion.copy(source.viewport.camera.quaternion);
      view.viewport.controls.target.copy(source.viewport.controls.target);
      view.viewport.controls.update();
    }
    this.syncing = false;
  }

  #onFrame(view, frame) {
    view.positions = frame.positions;
    view.cagePositions = frame.cage;
    view.viewport.meshView.update(frame.render);
    view.viewport.cageView.update(frame.render.cage);
    view.viewport.handleView.update(view.viewport.meshView.positions);
    view.viewport.invalidate();
    this.dispatchEvent({ type: 'frame', view: view.method });
  }

  // ---------------------------------------------------------------- handles

  #onPick(vertex, op) {
    if (op === 'remove') {
      this.selection.delete(vertex);
    } else {
      const group = this.handles.groupOf(vertex);
      if (group >= 0 && this.selection.size === 0) this.handles.setActive(group);
      else if (this.selection.has(vertex)) this.selection.delete(vertex);
      else this.selection.add(vertex);
    }
    this.#refreshHandleViews();
  }

  #onSelect(vertices, op) {
    for (const v of vertices) op === 'remove' ? this.selection.delete(v) : this.selection.add(v);
    this.#refreshHandleViews();
  }

  /** Turns the pending selection into a new handle group. */
  addGroupFromSelection(moving) {
    if (this.selection.size === 0) {
      this.banner.show('Select vertices first: click, shift-drag (brush) or alt-drag (lasso) on the mesh.', { kind: 'info' });
      return -1;
    }
    const index = this.handles.add([...this.selection], moving);
    this.selection.clear();
    this.#refreshHandleViews();
    return index;
  }

  clearSelection() {
    this.selection.clear();
    this.#refreshHandleViews();
  }

  removeActiveGroup() {
    this.handles.remove(this.handles.active);
  }

  #onHandlesChanged(what) {
    const targets = this.handles.targets();
    for (const view of this.views) {
      if (what === 'handles') view.session.setHandles(this.handles.vertexGroups(), targets);
      else view.session.setTargets(targets);
    }
    if (what === 'handles') this.#refreshHandleViews();
    else {
      for (const view of this.views) {
        view.viewport.handleView.setArrows(this.handles);
        if (!view.gizmo.dragging) view.gizmo.sync();
        view.viewport.invalidate();
      }
    }
    this.panel?.onHandles();
  }

  #refreshHandleViews() {
    for (const view of this.views) {
      view.viewport.handleView.setHandles(this.handles, this.selection);
      view.viewport.handleView.update(view.viewport.meshView.positions);
      view.gizmo.sync();
      view.viewport.invalidate();
    }
    this.panel?.onHandles();
  }

  undo() {
    this.handles.undo();
  }

  redo() {
    this.handles.redo();
  }

  // ---------------------------------------------------------------- options and display

  /** The iteration cap of a method (ARAP has its own, see DEFAULT_SETTINGS). */
  #maxIterationsFor(method) {
    return method === 'arap' ? this.settings.arapMaxIterations : this.settings.maxIterations;
  }

  #solverOptions(method) {
    const s = this.settings;
    const options = { jacobian: s.jacobian, volume: s.volume, positionWeight: s.positionWeight, c1: s.c1, c2: s.c2,
      maxIterations: this.#maxIterationsFor(method) };
    for (const key of EXTRA_SOLVER_KEYS) if (s[key] !== undefined) options[key] = s[key];
    return options;
  }

  /** App settings from a parsed scene's "solver": its maxIterations is the cap of the scene's method. */
  #settingsFromScene(solver) {
    const { maxIterations, ...rest } = solver;
    const method = solver.method ?? this.views[0].method;
    if (maxIterations !== undefined) rest[method === 'arap' ? 'arapMaxIterations' : 'maxIterations'] = maxIterations;
    return rest;
  }

  #applySolverSettings(view) {
    view.session.iterationsPerStep = this.settings.iterationsPerFrame;
    view.session.maxIterations = this.#maxIterationsFor(view.method);
    view.session.setOptions(this.#solverOptions(view.method));
  }

  /** Merges settings (solver options, display, method) and applies them. */
  setOptions(partial) {
    Object.assign(this.settings, partial);
    if (partial.method && !this.compare && this.views[0].method !== partial.method) this.views[0].setMethod(partial.method);
    for (const view of this.views) {
      this.#applySolverSettings(view);
      view.gizmo.setMode(this.settings.gizmoMode);
      this.#applyDisplay(view);
    }
    this.panel?.refresh();
  }

  #applyDisplay(view) {
    const s = this.settings;
    view.viewport.cageView.object.visible = s.showCage;
    view.viewport.handleView.object.visible = s.showHandles;
    view.viewport.meshView.setWireframe(s.wireframe);
    if (view.viewport.meshView.material.flatShading !== s.flatShading) view.viewport.meshView.setFlat(s.flatShading);
    view.viewport.invalidate();
  }

  /** Back to the rest pose with the handles' current targets re-solved from scratch. */
  async reset() {
    await Promise.all(this.views.map((v) => v.session.reset()));
  }

  /** Back to the rest pose and no displacement of any group (one undo step). */
  resetHandles() {
    this.handles.beginTransform();
    for (const g of this.handles.groups) {
      g.translate = [0, 0, 0];
      g.rotation = [0, 0, 0, 1];
    }
    this.#onHandlesChanged('targets');
    this.reset();
  }

  // ---------------------------------------------------------------- the loop

  loop(now) {
    if (this.disposed) return;
    this.raf = requestAnimationFrame(this.loop);
    for (const view of this.views) {
      view.session.pump();
      if (view.viewport.renderIfNeeded(now)) this.rendered++;
    }
    this.frames++;
    if (now - this.fpsTime >= 1000) {
      this.fps = (1000 * this.frames) / (now - this.fpsTime);
      this.renderFps = (1000 * this.rendered) / (now - this.fpsTime) / Math.max(1, this.views.length);
      this.frames = 0;
      this.rendered = 0;
      this.fpsTime = now;
      this.fpsElement.textContent = `${this.fps.toFixed(0)} fps \u00b7 ${this.renderFps.toFixed(0)} redraws/s`;
    }
    if (now - this.statsTime > 200) {
      this.statsTime = now;
      this.#drawStats();
    }
  }

  #drawStats() {
    // The key help needs room: single view, wide enough not to cover the stats.
    if (this.helpElement) this.helpElement.hidden = this.views.length > 1 || this.viewsElement.clientWidth < 820;
    for (const view of this.views) {
      // Small views keep the model visible: no plot, smaller stats.
      const el = view.viewport.element;
      el.classList.toggle('sd-compact', el.clientHeight < 440 || el.clientWidth < 300);
      const s = this.viewStats(view);
      const state = { converged: 'converged', solving: 'solving\u2026', stopped: 'stopped', error: 'error', idle: 'no handles' }[s.state] ?? s.state;
      const line = s.iterations
        ? `merit ${s.merit.toExponential(3)}   volume change ${(100 * s.volumeRelError).toFixed(6)}%\n` +
          `iterations ${s.iterations}   ${s.msPerIteration.toFixed(1)} ms/iteration   k=${view.session.iterationsForNextStep}/request`
        : `${this.model ? `${this.model.vertexCount ?? this.model.mesh.positions.length / 3} vertices, bind ${(this.model.bindMs ?? 0).toFixed(0)} ms` : 'loading\u2026'}`;
      const reason = s.state === 'stopped' || s.state === 'error' ? `: ${s.stopReason}` : '';
      // The DOM and the plot change only when the numbers do (no layout or canvas work while idle).
      const key = `${line}|${s.state}|${reason}`;
      if (view.statsKey !== key) {
        view.statsKey = key;
        view.viewport.statsLine.replaceChildren(
          document.createTextNode(`${line}\n`),
          Object.assign(document.createElement('span'), { className: `sd-${s.state}`, textContent: state }),
          document.createTextNode(reason),
        );
      }
      const history = view.session.history;
      const plotKey = `${history.length}|${history.at(-1)?.iteration}|${view.viewport.plot.color}|${el.classList.contains('sd-compact')}`;
      if (view.plotKey !== plotKey) {
        view.plotKey = plotKey;
        view.viewport.plot.draw(history);
      }
    }
    this.panel?.onStats();
  }

  // ---------------------------------------------------------------- exports

  /** OBJ text of the deformed mesh ('mesh'), the deformed cage ('cage') or the cage at rest ('restCage', e.g. a generated one). */
  async exportObj(what = 'mesh', view = this.views[0]) {
    const text = await view.session.request('exportObj', { what });
    return text;
  }

  async downloadObj(what) {
    try {
      const text = await this.exportObj(what);
      const file = what === 'restCage'
        ? `${baseName(this.model?.name)}-cage.obj`
        : `${baseName(this.model?.name)}-${this.views[0].method}-deformed${what === 'cage' ? '-cage' : ''}.obj`;
      downloadText(text, file, 'text/plain');
    } catch (error) {
      this.banner.show(`export failed: ${error.message}`);
    }
  }

  /** The scene JSON (docs/scene-format.md) of the current state. */
  sceneJson() {
    const s = this.settings;
    const scene = {};
    const source = this.model?.source ?? {};
    if (source.files) {
      scene.mesh = source.files[0];
      if (source.files[1]) scene.cage = source.files[1];
    } else {
      scene.example = this.model?.name;
    }
    // An app extension of the scene format: regenerate the cage on load (the cage file was never saved).
    if (source.generateCage) scene.generateCage = { vertices: source.generateCage.vertices };
    scene.handles = this.handles.toScene();
    const method = this.views[0].method;
    scene.solver = { method, jacobian: s.jacobian, volume: s.volume, maxIterations: this.#maxIterationsFor(method),
      positionWeight: s.positionWeight, c1: s.c1, c2: s.c2 };
    for (const key of EXTRA_SOLVER_KEYS) if (s[key] !== undefined) scene.solver[key] = s[key];
    return scene;
  }

  downloadScene() {
    downloadText(JSON.stringify(this.sceneJson(), null, 2), `${baseName(this.model?.name)}-scene.json`, 'application/json');
  }

  /** PNG data URL of all views side by side. */
  screenshot() {
    const canvases = this.views.map((v) => {
      v.viewport.renderFull();
      return v.viewport.canvas;
    });
    const out = document.createElement('canvas');
    out.width = canvases.reduce((w, c) => w + c.width, 0);
    out.height = Math.max(...canvases.map((c) => c.height));
    const ctx = out.getContext('2d');
    let x = 0;
    for (const c of canvases) {
      ctx.drawImage(c, x, 0);
      x += c.width;
    }
    return out.toDataURL('image/png');
  }

  downloadScreenshot() {
    downloadDataUrl(this.screenshot(), `${baseName(this.model?.name)}-${this.compare ? 'compare' : this.views[0].method}.png`);
  }

  openFilePicker() {
    this.fileInput.click();
  }

  // ---------------------------------------------------------------- scripting API (the embed delegates here)

  /** Replaces the handle groups: arrays of vertex indices; `moving` lists the indices of moving groups (default: the last). */
  setHandles(groups, { moving } = {}) {
    if (!Array.isArray(groups) || groups.some((g) => !Array.isArray(g))) throw new TypeError('setHandles: groups must be arrays of vertex indices');
    const n = this.model.mesh.positions.length / 3;
    groups.forEach((g, i) => g.forEach((v) => {
      if (!Number.isInteger(v) || v < 0 || v >= n) throw new RangeError(`setHandles: group ${i} has vertex ${v}, but the mesh has ${n} vertices`);
    }));
    this.handles.setGroups(groups, moving ?? [groups.length - 1]);
  }

  /**
   * Moves handle group `index` rigidly: translation [x,y,z] and optional rotation { axis, angle } about the group's
   * rest centroid. Resolves with the stats once every view has converged (or stopped).
   */
  async drag(index, translation, rotation = null) {
    const q = rotation ? new Quaternion().setFromAxisAngle(new Vector3(...rotation.axis).normalize(), rotation.angle).toArray() : null;
    this.handles.setTransform(index, translation, q, true);
    return this.solve();
  }

  /** Raw targets (one xyz row per handle vertex, groups in order), overriding the group transforms until the next edit. */
  setTargets(targets) {
    const t = Float64Array.from(targets);
    const count = this.handles.groups.reduce((k, g) => k + g.vertices.length, 0);
    if (t.length !== 3 * count) throw new RangeError(`setTargets: expected ${3 * count} numbers (3 per handle vertex), got ${t.length}`);
    for (const view of this.views) view.session.setTargets(t);
  }

  /** Resolves with the stats when every view's solve has settled (converged, stopped or failed). */
  async solve() {
    await this.ready;
    // Let the next animation frames send the latest state before waiting.
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
    await Promise.all(this.views.map((v) => v.session.settled()));
    return this.stats;
  }

  viewStats(view = this.views[0]) {
    const session = view.session;
    const last = session.last;
    return {
      method: view.method,
      state: session.state,
      converged: session.state === 'converged',
      stopReason: session.stopReason,
      merit: last?.merit ?? 0,
      energy: last?.energy ?? 0,
      volume: last?.volume ?? this.model?.restVolume ?? 0,
      restVolume: this.model?.restVolume ?? 0,
      volumeRelError: last?.volumeRelError ?? 0,
      iterations: session.totalIterations,
      msPerIteration: session.msPerIteration,
      fps: this.fps,
      renderFps: this.renderFps,
      vertexCount: this.model ? this.model.mesh.positions.length / 3 : 0,
      bindMs: this.model?.bindMs ?? 0,
    };
  }

  /** Stats of the first view (all views: statsAll()). */
  get stats() {
    return this.viewStats(this.views[0]);
  }

  statsAll() {
    return this.views.map((v) => this.viewStats(v));
  }

  /** Current deformed positions (Float64Array copy) of a view (default the first). */
  positions(view = 0) {
    return this.views[view]?.positions?.slice() ?? null;
  }

  cagePositions(view = 0) {
    return this.views[view]?.cagePositions?.slice() ?? null;
  }

  restPositions() {
    return this.model?.mesh.positions.slice() ?? null;
  }

  indices() {
    return this.model?.mesh.indices.slice() ?? null;
  }

  // ---------------------------------------------------------------- input

  #bindKeys() {
    this.root.addEventListener('pointerdown', (e) => {
      if (!e.target.closest?.('input, select, textarea, button')) this.root.focus({ preventScroll: true });
    });
    this.root.addEventListener('keydown', (e) => {
      if (e.target !== this.root && e.target.closest?.('.lil-gui, input, select, textarea')) return;
      const key = e.key.toLowerCase();
      const mod = e.ctrlKey || e.metaKey;
      if (mod && key === 'z') this[e.shiftKey ? 'redo' : 'undo']();
      else if (mod && key === 'y') this.redo();
      else if (mod) return;
      else if (key === 'f') this.addGroupFromSelection(false);
      else if (key === 'm') this.addGroupFromSelection(true);
      else if (key === 'delete' || key === 'backspace') this.removeActiveGroup();
      else if (key === 'escape') this.clearSelection();
      else if (key === 't' || key === 'r') this.setOptions({ gizmoMode: key === 't' ? 'translate' : 'rotate' });
      else if (key === 'c') this.setOptions({ showCage: !this.settings.showCage });
      else return;
      e.preventDefault();
    });
  }

  #bindDrop() {
    const root = this.root;
    let depth = 0;
    root.addEventListener('dragenter', (e) => {
      e.preventDefault();
      depth++;
      root.classList.add('sd-dragover');
    });
    root.addEventListener('dragover', (e) => e.preventDefault());
    root.addEventListener('dragleave', () => {
      if (--depth <= 0) root.classList.remove('sd-dragover');
    });
    root.addEventListener('drop', (e) => {
      e.preventDefault();
      depth = 0;
      root.classList.remove('sd-dragover');
      const files = [...(e.dataTransfer?.files ?? [])];
      if (files.length) this.loadFiles(files).catch(() => {});
    });
  }

  dispose() {
    this.disposed = true;
    cancelAnimationFrame(this.raf);
    this.panel?.dispose();
    for (const v of this.views) v.dispose();
    this.views = [];
    this.root.remove();
  }
}


function baseName(name = 'model') {
  return String(name).replace(/\.[a-z0-9]+$/i, '').replace(/[^\w-]+/g, '_');
}

