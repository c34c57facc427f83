// The interactive deformation app, used full-window by index.html and per element by the embed. It composes
// the parts and offers the scripting API (docs/embed.md) and events:
//   AppState (app_state.js)          what the user has and chose (settings: settings.js), one change event
//   ModelLoader (loading/)           examples, URLs, files, scenes, generated cages; holds the current model
//   SolverViews / SolverView (view/) one view + solver session per method (one, or several in compare mode)
//   HandleEditor (interaction/)      the handle groups shared by the views and the pending selection
//   KeyboardShortcuts, FileInput (input/), AppLayout, ControlPanel, ToolStrip (ui/), FrameLoop
//   VolumeParts (parts/), Skeleton (skeleton/)  volume kept per part; joints and bones kept rigid (the bone tool)
//   StepThrough (step_through.js)    the solver paused and advanced one iteration (or ARAP half step) at a time
//   Influence (influence/), Lessons (lessons/)   what one basis column controls; the report's experiments as lessons
// Events (docs/embed.md): load, nocage, frame, options, compare, handles, parts, influence, stats, panel, stepping, trace,
// lesson, skeleton, dispose. The threads the views' workers share are the page's (solver_client.js: setPageThreads).
import { EventDispatcher } from 'three';
import { ViewWiring } from './view/view_wiring.js';
import { SolverViews } from './view/solver_views.js';
import { HandleEditor } from './interaction/handle_editor.js';
import { EditTimeline } from './interaction/edit_timeline.js';
import { ModelLoader } from './loading/model_loader.js';
import { deformable } from './loading/no_cage.js';
import { VolumeParts } from './parts/volume_parts.js';
import { Skeleton } from './skeleton/skeleton.js';
import { KeyboardShortcuts } from './input/keyboard_shortcuts.js';
import { FileInput } from './input/file_input.js';
import { AppLayout } from './ui/app_layout.js';
import { ControlPanel } from './ui/panel.js';
import { ToolStrip } from './ui/tool_strip.js';
import { StepThrough } from './step_through.js';
import { Lessons } from './lessons/lessons.js';
import { LessonBar } from './ui/lesson_bar.js';
import { screenshotOf } from './ui/screenshot.js';
import { savedScene } from './loading/saved_scene.js';
import { FrameLoop } from './frame_loop.js';
import { AppState } from './app_state.js';
import { collaboratorState } from './collaborator_state.js';
import { appIntents, appQueries } from './app_intents.js';
import { checkCageSize } from './settings.js';
import { buildNote, fpsLine, modelLine } from './stats_format.js';
import { setPageThreads } from '../lib/worker/solver_client.js';
import { AppLifetime } from './app_lifetime.js';
import { checkCompare, viewKeys } from './methods.js';
import { Influence } from './influence/influence.js';
import { refuseCompare } from './view/refused_compare.js';
import { checkPageOptions, showIgnoredOptions } from './page_options.js';

export class DeformerApp extends EventDispatcher {
  /**
   * @param {HTMLElement} container
   * @param {object} [requested] mount()'s options (docs/embed.md: example, mesh, cage, scene, compare, panel, help, tools,
   *   paused, lesson, settings ...)
   */
  constructor(container, requested = {}) {
    super();
    // One check of all the page asked for (page_options.js): a bad value is dropped (its default used) and
    // named in the banner once the first load has settled, so the page never stays empty.
    const { options, settings, problems } = checkPageOptions(requested);
    this.options = options;
    /** What the page asked for and the app left out (a bad URL parameter, attribute or option), one sentence each. */
    this.ignoredOptions = Object.freeze(problems);
    this.layout = new AppLayout(container, { help: options.help !== false, tools: options.tools !== false, onCancel: () => this.cancelLoad() });
    this.#state = new AppState(settings);
    this.#settings = this.#state.settings;
    this.#state.subscribe((change) => this.#onStateChange(change));
    this.#state.subscribe((change) => change.settings && this.dispatchEvent({ type: 'options', settings: this.#settings.snapshot() }), { last: true });
    const timeline = this.#timeline = new EditTimeline(); // one undo for the handles, the skeleton and the painted parts
    this.#editor = new HandleEditor(timeline);
    this.#editor.addEventListener('change', (e) => this.#onHandlesChanged(e.what));
    this.#editor.handles.addEventListener('release', () => this.#views.released());
    // The views the collaborators act on; the wiring that makes each view needs them, so the first view comes with setMethods.
    const views = this.#views = new SolverViews(this.layout.views, { before: this.layout.help, create: (key) => this.#wiring.create(key) });
    this.#parts = new VolumeParts({ views, banner: this.banner, timeline });
    this.#parts.addEventListener('change', (e) => { this.#copyState(); this.dispatchEvent({ ...e, type: 'parts' }); });
    this.#stepping = new StepThrough({ views, ready: () => this.ready.then(() => this.#binding), life: this.#life }); // compare views binding too
    for (const type of ['change', 'trace']) {
      this.#stepping.addEventListener(type, (e) => { this.#copyState(); this.dispatchEvent({ ...e, type: type === 'change' ? 'stepping' : type }); });
    }
    this.#influence = new Influence({ views, banner: this.banner, dispatch: (e) => { this.#copyState(); this.dispatchEvent(e); } });
    this.skeleton = new Skeleton({ views, banner: this.banner, timeline,
      dispatch: (e) => { this.#copyState(); this.dispatchEvent(e); } });
    this.#wiring = new ViewWiring({ parent: this.layout.views, state: this.#state, editor: this.#editor, parts: this.#parts,
      stepping: this.#stepping, influence: this.#influence, skeleton: this.skeleton, banner: this.banner, views, dispatch: (e) => this.dispatchEvent(e) });
    this.#loader = new ModelLoader({ views: this.#views, banner: this.banner, progress: this.layout.progress, settings: this.#settings,
      editor: this.#editor, parts: this.#parts, skeleton: this.skeleton, noCage: options.noCage });
    this.#loader.addEventListener('load', (e) => this.#onLoad(e.model, e.keepHandles));
    this.#loader.addEventListener('nocage', (e) => this.dispatchEvent({ type: 'nocage', choice: e.choice, model: e.model }));
    this.#loader.addEventListener('view', (e) => this.setCompare(e.compare).catch(() => {})); // a saved scene's compared methods
    this.#views.setMethods(viewKeys(options.compare ?? null, this.#settings.values), { labels: options.labels });
    this.#copyState();
    const intents = appIntents(this); // what the panel, the tool strip, the keys and the lesson bar send; they show the state
    if (options.panel !== false) this.#panel = new ControlPanel(this.element, { state: this.#state, intents, queries: appQueries(this), compact: this.layout.compact,
      closed: options.panel === 'closed', beside: options.panelBeside !== false, shareLink: options.shareLink });
    this.#lessons = new Lessons({ loader: this.#loader, banner: this.banner, stepping: this.#stepping,
      setCompare: (compare) => this.setCompare(compare), fitView: (direction) => this.fitView(direction) });
    this.#lessons.addEventListener('change', (e) => { this.#state.update({ lesson: e.lesson }); this.dispatchEvent({ type: 'lesson', lesson: e.lesson }); });
    this.#lessonBar = new LessonBar(this.layout.lessonBar, { state: this.#state, intents });
    if (this.layout.tools) this.#tools = new ToolStrip(this.layout.tools, { state: this.#state, intents, help: this.layout.helpCard, panel: options.panel !== false });
    this.#keys = new KeyboardShortcuts(this.element, { state: this.#state, intents });
    this.#files = new FileInput(this.element, (files) => this.loadFiles(files));

    if (options.paused) this.#stepping.setPaused(true).catch(() => {}); // step-through from the first iteration (rejects if disposed)
    this.#started = this.#start(options); // settles with the first load; `ready` once a model is deformable
    this.ready = this.#life.guard(() => deformable(this.#started, this.#loader).finally(() => showIgnoredOptions(this.banner, problems)));
    this.ready.catch(() => {}); // failures are shown in the page; awaiting callers still see the rejection
    this.loop = this.loop.bind(this); // replaceable (scripts/bench/browser.mjs times it); the frame loop calls the current one
    this.frameLoop = new FrameLoop({ frame: (now) => this.loop(now), tick: () => this.#drawStats() });
    this.frameLoop.start();
  }

  #state; #started; #settings; // the state's settings store (solverOptions, toScene, values)
  // The collaborators (the file's head); the app's life, which dispose() ends: the API's pending promises reject then.
  #editor; #views; #loader; #parts; #stepping; #influence; #lessons; #lessonBar; #wiring; #keys; #files; #tools; #panel; #timeline; #life = new AppLifetime();
  #binding = Promise.resolve(); // compare views binding the model (solve() waits for them)

  // ---------------------------------------------------------------- parts and state (read-only)

  /** The app's root element (in the container given to the constructor). */
  get element() { return this.layout.root; }
  get banner() { return this.layout.banner; }

  /** The bound model (the worker's Model plus `source`), or null before the first load. */
  get model() { return this.#loader.model; }
  get exampleNames() { return this.#loader.exampleNames; }

  /** A copy of the settings (change them with setOptions). */
  get settings() { return this.#settings.snapshot(); }

  /** The views, one per method on screen (SolverView: viewport, session, gizmo, picker). */
  get views() { return this.#views.list; }
  get compare() { return this.#views.compare; }

  /** The handle groups shared by the views (HandleSet), and the pending selection (vertex indices not yet in a group). */
  get handles() { return this.#editor.handles; }
  get selection() { return this.#editor.selection; }

  /** Volume kept per part (VolumeParts: setPainting, setCurrent, apply, auto(K), clear, use(description)). */
  get parts() { return this.#parts; }

  /** Step-through (StepThrough: paused, setPaused(on), toggle(), next(), nextHalf()). */
  get stepping() { return this.#stepping; }
  get influence() { return this.#influence; } // what one cage vertex controls: show(column), hide(), setPicking(on)

  /** Whether the control panel is open (the tool strip's panel button and the panel's title toggle it). */
  get panelOpen() { return this.#state.current.panelOpen; }
  setPanelOpen(open) { this.#state.setPanelOpen(!!open); }

  // The state's one change event as the app's events (docs/embed.md); the views follow it themselves (SolverView).
  #onStateChange(change) {
    if (change.settings) this.#applySettings(change.settings);
    if ('panelOpen' in change) this.dispatchEvent({ type: 'panel', open: change.panelOpen });
  }

  // The collaborators' state that the tool strip shows, copied into the app's state (none while being built).
  #copyState() {
    if (this.#loader) this.#state.update(collaboratorState({ model: this.model, views: this.#views, editor: this.#editor, skeleton: this.skeleton,
      stepping: this.#stepping, parts: this.#parts, influence: this.#influence, timeline: this.#timeline }));
  }

  // ---------------------------------------------------------------- loading

  #start(options) {
    if (options.lesson) return this.loadLesson(options.lesson); // checked by page_options.js
    if (options.scene) return this.loadScene(options.scene);
    if (options.mesh) return this.loadUrls(options.mesh, options.cage);
    return this.loadExample(options.example);
  }

  /**
   * Loads a built-in lesson (lessons/catalogue.js: its scene, views, camera and caption); resolves with the
   * lesson { id, title, caption, view }. An unknown name is an InputError naming the lessons. A load asked for
   * while it waits (for its scene, its views) wins: the lesson then rejects with a CancelledError.
   */
  loadLesson(id) { return this.#lessons.load(id); }

  /** The current lesson ({ id, title, caption, view }), or null. */
  get lesson() { return this.#lessons.current; }

  /** Loads a built-in example (no name: the default one). */
  loadExample(name) { return this.#loader.example(name); }

  /** Fetches a mesh (and cage) by URL, relative to the page. */
  loadUrls(meshUrl, cageUrl) { return this.#loader.urls(meshUrl, cageUrl); }

  /** Dropped / picked files: a mesh and its cage (the larger is the mesh) and/or a scene .json (errors in the page). */
  loadFiles(files) { return this.#loader.files(files); }

  /**
   * Loads a scene (docs/scene-format.md; parsed by web/lib/scene.js, the CLI's parser): a URL (mesh
   * and cage paths relative to it), an object, or JSON text (with `json: true`). Its options and handles then
   * apply; without "mesh" or "example" they apply to the current model.
   */
  async loadScene(input, options = {}) {
    await this.#loader.loadScene(input, options);
    return this.model;
  }

  /** Binds the model again with the basis 'cage' (a lone mesh has none) or 'spectral' with `modes` eigenvectors; handles and parts stay. */
  async setBasis(basis, modes = this.#settings.values.spectralModes) {
    const ticket = this.#loader.request(); // taken before the wait: a load asked for meanwhile wins
    await this.#started.catch(() => {});
    return this.#loader.setBasis(basis, modes, ticket);
  }

  /** Binds the model again with cage coordinates 'mvc' | 'pmvc' | 'harmonic' (and `resolution`); handles and parts stay. */
  setCoordinates(coordinates, resolution) {
    const ticket = this.#loader.request();
    return this.#started.catch(() => {}).then(() => this.#loader.setCoordinates(coordinates, resolution, () => this.setCompare('coordinates'), ticket));
  }

  /**
   * Replaces the current model's cage by a generated one with about `vertices` vertices (in a fresh worker,
   * with progress and Cancel; on failure the current model stays). Handle groups are kept (same mesh).
   * @param {number} [vertices] target size K (default: settings.cageVertices)
   */
  async generateCage(vertices = this.#settings.values.cageVertices) {
    checkCageSize(vertices);
    const ticket = this.#loader.request();
    await this.#started.catch(() => {});
    return this.#loader.generateCage(vertices, ticket);
  }

  /** Stops every load in progress (the progress bar's Cancel); the previous model stays. */
  cancelLoad() { this.#loader.cancel(); }

  #onLoad(model, keepHandles) {
    // Same mesh, new cage ("Generate cage" on the current model): the groups and their displacements stay.
    const keep = keepHandles && this.handles.groups.length ? this.handles.toScene() : null;
    this.#wiring.diagonal = this.#views.showModel(model, this.views, { cageShown: this.#settings.values.showCage });
    this.#editor.setModel(model.mesh.positions, { keep, defaults: model.defaultHandles });
    this.#parts.onLoad(model, keepHandles);
    this.skeleton.onLoad(model, keepHandles); // the same mesh keeps its bones
    if (keepHandles) this.#influence.refresh(); else this.#influence.hide(); // another mesh: no column
    this.#lessons.onLoad(model); // another model ends the lesson
    this.#copyState();
    this.dispatchEvent({ type: 'load', model });
  }

  // ---------------------------------------------------------------- views

  /**
   * Compare mode on/off (true, a list of methods or view keys, or 'coordinates': methods.js). New views bind the
   * current model in their own worker and are framed for their new widths; solve() meanwhile waits for them too.
   * Rejects with a CancelledError when the app is disposed first (or was: no views are made then).
   */
  setCompare(compare) {
    if (this.#life.ended) return this.#life.guard(() => null);
    const keys = viewKeys(checkCompare(compare), this.#settings.values);
    const previous = this.compare && this.views.map((v) => v.key); // put back if a new view cannot bind
    for (const view of this.#views.setMethods(keys, { labels: this.options.labels })) view.applySolverSettings(this.#settings);
    this.#copyState();
    this.dispatchEvent({ type: 'compare', compare: this.compare, methods: this.views.map((v) => v.method), views: this.views.map((v) => v.key) });
    this.fitView();
    if (!this.model) return Promise.resolve();
    const binding = this.#loader.bindNewViews().then(async () => {
      this.fitView(); // the new widths
      await Promise.all([this.#parts.onLoad(this.model, true), this.skeleton.onLoad(this.model, true), this.#influence.refresh()]); // same parts, bones, column
    }, (error) => refuseCompare(error, previous, (c) => this.setCompare(c), this.banner));
    this.#binding = binding.catch(() => {});
    return this.#life.guard(() => binding);
  }

  /** Frames the model as it is, the targets (the gizmo) and the cage (unless far larger) in every view, along `direction` (or as now). */
  fitView(direction) {
    const targets = this.handles.groups.length ? this.handles.targets() : null;
    this.#views.fitView({ targets, cageShown: this.#settings.values.showCage, ...(direction ? { direction } : {}) });
  }

  // ---------------------------------------------------------------- handles

  #onHandlesChanged(what) {
    this.#views.showHandleChange(what, this.handles, this.selection);
    this.#copyState();
    this.dispatchEvent({ type: 'handles', ...this.#editor.summary() });
  }

  /** Turns the pending selection into a new handle group (moving or fixed); returns its index, or -1. */
  addGroupFromSelection(moving) {
    if (this.selection.size === 0) {
      this.banner.show('Select vertices first: click, shift-drag (brush) or alt-drag (lasso) on the mesh.', { kind: 'info' });
      return -1;
    }
    return this.#editor.addGroupFromSelection(moving);
  }

  clearSelection() { this.#editor.clearSelection(); }
  removeActiveGroup() { this.handles.remove(this.handles.active); }
  clearGroups() { this.handles.clear(); }
  undo() { this.#timeline.undo(); } // handle, skeleton and paint edits in one timeline (edit_timeline.js)
  redo() { this.#timeline.redo(); }

  /** "reset pose and handles": every group back to no displacement (one undo step), so the mesh returns to rest. */
  resetHandles() {
    this.handles.resetTransforms();
    return this.resolveFromRest();
  }

  /** Replaces the handle groups: arrays of vertex indices; `moving` lists the indices of moving groups (default: the last). */
  setHandles(groups, { moving } = {}) {
    this.#editor.setGroups(groups, moving);
  }

  /**
   * Moves handle group `index` rigidly: translation [x,y,z] and optional rotation { axis, angle } about the group's
   * rest centroid. Resolves with the stats once every view has converged (or stopped).
   */
  drag(index, translation, rotation = null) { // a disposed app rejects at once, editing nothing (app_lifetime.js)
    return this.#life.guard(() => { this.#editor.move(index, translation, rotation); return this.#settled(); });
  }

  /** Raw targets (one xyz row per handle vertex, groups in order), overriding the group transforms until the next edit. */
  setTargets(targets) {
    const t = this.#editor.checkTargets(targets);
    for (const view of this.views) view.session.setTargets(t);
  }

  // ---------------------------------------------------------------- options and solving

  /** Merges settings (solver options, display, method) and applies them. */
  setOptions(partial) { this.#state.setOptions(partial); }

  // What a settings change means for the app itself: the first view's method (before the views apply their options:
  // the app subscribed first), the page's threads, a new second view for "compare coordinates". The 'options' event
  // follows once the views have applied it (a last listener).
  #applySettings(changed) {
    const first = this.#views.first;
    if (changed.method && !this.compare && first.method !== changed.method) first.setMethod(changed.method);
    if (changed.threads !== undefined) setPageThreads(changed.threads === 'auto' ? 0 : changed.threads);
    if (changed.compareCoordinates && this.views.some((v) => v.coordinates)) this.setCompare('coordinates').catch(() => {}); // a new second view
  }

  /** "re-solve from rest": the mesh back to the rest pose, then the same targets solved again (a fresh plot series). */
  async resolveFromRest() { await Promise.all(this.views.map((v) => v.session.resolveFromRest())); }

  reset() { return this.resetHandles(); } // the same: back to rest, no group displaced (undoable)

  /** Resolves with the stats once every view's solve has settled; rejects (CancelledError) if the app is disposed first. */
  solve() { return this.#life.guard(() => this.#settled()); }

  async #settled() {
    await this.ready;
    await this.#binding; // compare views still binding
    // Let the next animation frames send the latest state before waiting.
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
    await Promise.all(this.views.map((v) => v.session.settled()));
    return this.stats;
  }

  // ---------------------------------------------------------------- the loop and stats

  /** One animation frame: each session sends what changed, each view redraws if needed. Returns redraws per view. */
  loop(now) { return this.#views.frame(now); }

  #drawStats() {
    this.layout.showStatus(modelLine(this.model), fpsLine(this.frameLoop.fps, this.frameLoop.renderFps), buildNote(this.model?.solver));
    this.layout.placeHelp(this.views.length);
    this.#views.drawStats(this.model, this.#rates(), this.#loader.status);
    this.dispatchEvent({ type: 'stats', stats: this.stats });
  }

  /** The stats of one view (docs/embed.md). */
  viewStats(view = this.views[0]) {
    return view.stats(this.model, this.#rates());
  }

  #rates() { return { fps: this.frameLoop?.fps ?? 0, renderFps: this.frameLoop?.renderFps ?? 0 }; }

  /** Stats of the first view (all views: statsAll()). */
  get stats() { return this.viewStats(this.views[0]); }
  statsAll() { return this.views.map((v) => this.viewStats(v)); }

  // ---------------------------------------------------------------- results and exports

  /** Current deformed positions (Float64Array copy) of a view (default the first). */
  positions(view = 0) { return this.views[view]?.positions?.slice() ?? null; }
  cagePositions(view = 0) { return this.views[view]?.cagePositions?.slice() ?? null; }
  restPositions() { return this.model?.mesh.positions.slice() ?? null; }
  indices() { return this.model?.mesh.indices.slice() ?? null; }

  /** OBJ text of the deformed mesh ('mesh'), the deformed cage ('cage') or the cage at rest ('restCage', e.g. a generated one). */
  async exportObj(what = 'mesh', view = this.views[0]) { return view.session.request('exportObj', { what }); }

  /** The deformed mesh as .glb bytes in the model's own vertex layout (a glTF keeps its materials and nodes). */
  async exportGlb(view = this.views[0]) { return view.session.request('exportGlb'); }

  /** The scene (docs/scene-format.md) of the current state: the panel's method and, in compare mode, the views' (saved_scene.js). */
  sceneJson() {
    return savedScene(this.model, this.handles.toScene(), this.#settings.toScene(this.#settings.values.method), this.#parts.sceneSpec,
      this.skeleton.sceneSpec, this.compare ? this.views.map((v) => v.key) : null);
  }

  screenshot() { return screenshotOf(this.views.map((v) => v.viewport)); } // PNG data URL of all views side by side

  openFilePicker() { this.#files.openPicker(); } // the browser's file chooser (mesh + cage, or a scene)

  dispose() {
    this.frameLoop.stop();
    this.#life.end();
    this.dispatchEvent({ type: 'dispose' });
    for (const part of [this.#keys, this.#tools, this.#lessonBar, this.#panel, this.#files, this.#loader, this.#views, this.layout]) part?.dispose();
  }
}
