// Loading models into the views' solver sessions: built-in examples, URLs, dropped files, scenes (parsed by
// web/lib/scene.js, the CLI's parser) and generated cages. Each load binds the model in a fresh worker per
// view while the current model stays on screen and keeps working; the progress bar has Cancel, and any
// failure is shown in the banner with the previous model kept. It holds the current model.
//
// The user's last request wins: each public request takes a ticket when it is made, before anything it waits
// for (a fetch, a lesson's scene, the app being ready), and a request whose ticket is no longer the newest
// rejects with a CancelledError before it binds, so an older request that waited longer never cancels or
// replaces a newer one (a newer one that binds first cancels the older's binding, as before).
//
// Events: { type: 'request', ticket } when a request takes its ticket; { type: 'load', model, keepHandles } once a
// model is bound in every view (keepHandles: same mesh, new cage: the handle groups stay); then { type: 'nocage',
// choice, model } when a lone mesh was bound as chosen (no_cage.js: 'generate' or 'spectral'); { type: 'view',
// compare } once a scene that names the methods it compares (its "view") is loaded: the app shows them; { type:
// 'dispose' } when the app is disposed (dispose()).
import { EventDispatcher } from 'three';
import { CancelledError, InputError } from '../../lib/errors.js';
import { parseScene } from '../../lib/scene.js';
import { cannotGetCage, isCancelled, isMissingCage, isOverBudget } from '../errors.js';
import { AppSettings, checkCageSize } from '../settings.js';
import { isModelName } from '../../lib/formats.js';
import { describeSubspace, isSpectral } from '../../lib/subspace.js';
import { gltfFileOf, gltfLookOf, meshesOf, showNotes } from './model_extras.js';
import { coordinatesSettings, sceneSubspaceNote, sceneSubspaceSettings, subspaceChoice, withSettings } from './subspace_choice.js';
import { asModelFile, fetchFile, readDropped, withDroppedFiles, withGltfFiles } from './files.js';
import { loadEveryView } from './prepared_load.js';
import { offerFewerModes, warnPoorCage } from './load_offers.js';
import { NoCage } from './no_cage.js';
import { sceneFits } from './scene_fits.js';

export class ModelLoader extends EventDispatcher {
  /**
   * @param {{ views: import('../view/solver_views.js').SolverViews, banner: import('../ui/overlays.js').Banner,
   *           progress: import('../ui/overlays.js').ProgressBar, settings: import('../settings.js').AppSettings,
   *           editor: import('../interaction/handle_editor.js').HandleEditor,
   *           parts: import('../parts/volume_parts.js').VolumeParts, skeleton: import('../skeleton/skeleton.js').Skeleton,
   *           noCage?: string }} parts editor, parts, skeleton: a scene's handles, volume parts and skeleton go
   *   there; noCage: what a lone mesh without a cage does (no_cage.js)
   */
  constructor({ views, banner, progress, settings, editor, parts, skeleton, noCage }) {
    super();
    this.views = views;
    this.banner = banner;
    this.progress = progress;
    this.settings = settings;
    this.editor = editor;
    this.parts = parts;
    this.skeleton = skeleton;
    /** The bound model (the worker's Model plus `source`: what a saved scene names), or null. */
    this.model = null;
    /** What the views show while no model is bound: loading, or why none is. */
    this.status = 'loading\u2026';
    this.exampleNames = [];
    /** A lone mesh without a cage: the choice made up front, or the banner's offer, and the mesh that waits. */
    this.noCage = new NoCage({ loader: this, choice: noCage, load: (...a) => this.meshFiles(...a), keptNote: () => this.#keptNote() });
  }

  #newest = 0; // the ticket of the user's last request
  #shown = 0; // the ticket of the request whose model is this.model
  #abort = new AbortController(); // aborted by dispose(): the fetches under way stop

  /** Whether the app was disposed: no load binds any more. */
  get disposed() { return this.#abort.signal.aborted; }

  /**
   * The app is disposed: the fetches under way stop and every load rejects with a CancelledError before it binds
   * (else a fetch that ended later would start workers for views that are gone); the model's look (a glTF's
   * geometries and the object URLs of its files) and the bytes of a lone mesh waiting for its choice are let go, and
   * `ready` waiting for that choice rejects (event 'dispose', no_cage.js deformable()).
   */
  dispose() {
    this.#abort.abort();
    this.model?.look?.dispose();
    this.model = null;
    this.noCage.bound();
    this.dispatchEvent({ type: 'dispose' });
  }

  /**
   * A ticket for a request the user makes now, taken before the request waits for anything; the public methods
   * take their own unless given one (`ticket`: one taken earlier, by the app or a lesson before they waited).
   */
  request() {
    this.dispatchEvent({ type: 'request', ticket: ++this.#newest }); // lessons.js: the one it replaces goes back
    return this.#newest;
  }

  isNewest(ticket) { return ticket === this.#newest; } // no request was made after the one of `ticket`

  /** Rejects the request of `ticket` as cancelled (CancelledError) when a later one was made, or the app was disposed. */
  checkNewest(ticket, what) {
    if (this.disposed) throw new CancelledError(`${what} cancelled: the app was disposed`);
    if (!this.isNewest(ticket)) throw new CancelledError(`${what} cancelled: a later request replaced it`);
  }

  /** The subspace a view's next binding uses (subspace_choice.js; default: the first view's, from the settings). */
  subspaceFor(view = this.views.first, values = this.settings.values) {
    return subspaceChoice(values, view?.coordinates ?? null);
  }

  /**
   * A built-in example (no name: the default one).
   * @param {string} [name]
   * @param {{ check?: Function, generateCage?: { vertices: number }|null }} [options] check: see Session.load;
   *   generateCage: a generated cage instead of the example's own, in the same binding
   */
  example(name, { check, generateCage = null, ticket = this.request() } = {}) {
    return this.#bind('loadExample', { name, generateCage, subspace: this.subspaceFor() },
      { label: `Loading ${name ?? 'example'}`, source: { example: name, ...(generateCage ? { generateCage } : {}) }, check, ticket });
  }

  /**
   * Binds the current model again with another basis (settings basis and spectralModes); on failure the model
   * stays as it was bound (a lone mesh has no cage to go back to), and so do the settings.
   */
  async setBasis(basis, modes, ticket = this.request()) {
    this.checkNewest(ticket, 'Changing the basis');
    return withSettings(this.settings, { basis, spectralModes: modes }, () => this.rebind(ticket));
  }

  /**
   * Binds the current model again with other cage coordinates ('mvc' | 'pmvc' | 'harmonic'; the cage basis) and
   * that type's resolution if given; the settings take them once bound (failed: never). In "compare coordinates" (views
   * with their own coordinates) `compareAgain()` (the app's setCompare('coordinates')) makes the views from them instead.
   */
  async setCoordinates(coordinates, resolution, compareAgain, ticket = this.request()) {
    this.checkNewest(ticket, 'Changing the coordinates');
    const change = coordinatesSettings(coordinates, resolution);
    const compared = compareAgain && this.views.list.some((view) => view.coordinates);
    const model = compared ? null : await this.rebind(ticket, { ...this.settings.values, ...change }); // as an argument
    this.settings.update(change);
    return compared ? compareAgain() : model;
  }

  /** Binds the current model again (same mesh: handles and parts stay) with `values`' basis (default: the settings'). */
  rebind(ticket = this.request(), values = undefined) {
    const m = this.model;
    const subspace = this.subspaceFor(this.views.first, values);
    if (!m && this.noCage.waiting && isSpectral(subspace)) return this.noCage.choose('spectral', {}, ticket);
    if (!m) return Promise.reject(new InputError('no model is loaded'));
    const what = `${describeSubspace(subspace)}${isSpectral(subspace) ? '' : ' of its cage'}`;
    return this.#bind('loadMeshes', { ...meshesOf(m), subspace },
      { label: `Binding ${m.name} with ${what}`, source: m.source, keepHandles: true, ticket, values });
  }

  /** A mesh (and cage) by URL, relative to the page. */
  async urls(meshUrl, cageUrl, ticket = this.request()) {
    const files = [], signal = this.#abort.signal; // dispose() aborts the fetches, a .gltf's own files' too
    for (const url of [meshUrl, cageUrl].filter(Boolean)) files.push(...await fetchFile(url, { signal }).then((f) => withGltfFiles(asModelFile(f), [], { signal })).catch((error) => this.#fail(error)));
    return this.meshFiles(files, null, { ticket });
  }

  /** Dropped or picked files: a scene (with the meshes it names), or a mesh and its cage. */
  async files(files, ticket = this.request()) {
    const { scene, meshes } = await readDropped(files, (error) => this.#fail(error));
    if (scene) return this.loadScene(scene.text, { json: true, files: meshes, name: scene.name, ticket });
    return meshes.length ? this.meshFiles(await withDroppedFiles(meshes).catch((error) => this.#fail(error)), null, { ticket }) : undefined;
  }

  /**
   * A scene (see scene()), then its solver options, handle groups and volume parts (on its model, or the
   * current one). Nothing changes unless all of it fits: a handle or a part the mesh does not have is
   * refused (banner, rejection) with the previous model, handles, parts and settings kept. `fresh` (a lesson):
   * the solver settings start from the app's first ones (AppSettings.lessonStart), not from the current ones.
   */
  async loadScene(input, { ticket = this.request(), fresh = false, ...options } = {}) {
    const { scene, name, partition } = await this.scene(input, { ...options, ticket });
    try {
      // A scene without a model applies to the current one: check it there, the same way, before any change.
      const own = !!(scene.example || scene.mesh); // its own model starts a fresh undo history (docs/app.md)
      const parts = own ? partition : await this.#checkOnCurrentModel(scene, ticket, name);
      this.settings.update(fresh ? this.settings.lessonStart(scene.solver) : AppSettings.fromScene(scene.solver, this.views.first.method));
      this.editor.fromScene(scene.handles, { freshHistory: own });
      if (scene.volumeParts) await this.parts.use(scene.volumeParts, { partition: parts, freshHistory: own });
      if (scene.skeleton) await this.skeleton.use(scene.skeleton, { freshHistory: own });
      if (!fresh && scene.view?.compare) this.dispatchEvent({ type: 'view', compare: scene.view.compare }); // a lesson sets its own
    } catch (error) {
      if (isCancelled(error)) throw error; // a later request's outcome is what the page shows
      if (!error.message.startsWith(`${name}:`)) error.message = `${name}: ${error.message}`;
      this.banner.show(error.message);
      throw error;
    }
    return this.model;
  }

  // The handles of a scene without a model, on the model on screen; its parts, made by the first view's worker.
  async #checkOnCurrentModel(scene, ticket, name) {
    this.checkNewest(ticket, name);
    if (!this.model) return null;
    const parts = await sceneFits(scene, this.model, this.views.first.session.client);
    this.checkNewest(ticket, name);
    return parts;
  }

  /**
   * Mesh files ({ name, bytes }): the larger is the mesh, the other the cage. A lone mesh that has no cage (or
   * whose cage generation failed or was cancelled) is loaded as the page chose up front, or gets the offers of
   * "Generate cage" and the spectral basis (no_cage.js).
   * @param {{ name: string, bytes: Uint8Array }[]} files
   * @param {{ vertices: number }|null} [generateCage] generate the cage of a lone mesh
   * @param {{ choice?: 'generate'|'spectral' }} [options] choice: the load is a lone mesh's as chosen (event 'nocage')
   */
  async meshFiles(files, generateCage = null, { check, choice, ticket = this.request() } = {}) {
    // The worker's progress phases say what is running (generating a K-vertex cage, computing weights).
    const models = files.filter((f) => isModelName(f.name));
    const label = `Loading ${models.map((f) => f.name).join(' + ')}`;
    // Copies stay here so "Generate cage" can retry without asking for the file again.
    const kept = files.map((f) => ({ name: f.name, ...(f.url ? { url: f.url } : {}), bytes: f.bytes.slice() }));
    // urls: where the page fetched them, for a link to the pose (ui/share_link.js); dropped files have none.
    const source = { files: models.map((f) => f.name), ...(models.every((f) => f.url) ? { urls: models.map((f) => f.url) } : {}),
      ...(generateCage ? { generateCage } : {}) };
    const chosen = models.length === 1 && !choice && this.noCage.choice !== 'ask'; // no_cage.js loads it as chosen
    try {
      return await this.#bind('loadFiles', { files, generateCage, subspace: this.subspaceFor() }, { label, source, check, files: kept, choice, ticket, chosen });
    } catch (error) {
      // A broken mesh gets the checker's findings only: no cage can help it.
      const offer = models.length === 1 && !cannotGetCage(error) && (generateCage || isMissingCage(error));
      if (offer && this.isNewest(ticket)) return this.noCage.refused(kept, error, ticket, isMissingCage(error) && !choice);
      throw error;
    }
  }

  /**
   * Replaces the current model's cage by a generated one of about `vertices` vertices; the handles stay. With no
   * model yet, the lone mesh waiting for a choice (no_cage.js) gets it. Async: a refusal (a bad size, the app
   * disposed) rejects, as callers that only catch (load_offers.js) expect, rather than throwing.
   */
  async generateCage(vertices, ticket = this.request()) {
    checkCageSize(vertices);
    this.checkNewest(ticket, 'Generating a cage');
    const m = this.model;
    if (!m && this.noCage.waiting) return this.noCage.choose('generate', { vertices }, ticket);
    if (!m) return Promise.reject(new InputError('generateCage: no model is loaded'));
    const generateCage = { vertices };
    return this.#bind('loadMeshes', { name: m.name, mesh: m.mesh, generateCage, subspace: this.subspaceFor(), gltf: m.gltfFile },
      { label: `New cage for ${m.name}`, source: { ...m.source, generateCage }, keepHandles: true, ticket });
  }

  /**
   * Reads a scene and loads the model it names: a URL (its mesh and cage paths are relative to it), a parsed
   * object, or JSON text (`json: true`). A scene may name a built-in "example", or a "mesh" with a "cage" or
   * "generateCage"; with neither the current model stays (or, with none yet, the default example loads).
   * Files the scene names are taken from `files` (dropped with it) when there, else fetched.
   * @returns {Promise<{ scene: import('../../lib/scene.js').Scene, name: string }>} name: the scene's, for messages
   */
  async scene(input, { json = false, files = [], baseUrl = document.baseURI, name = 'scene', ticket = this.request() } = {}) {
    const result = { scene: null, name, partition: null };
    let scene;
    try {
      let content = input;
      if (typeof input === 'string' && !json) {
        const file = await fetchFile(input, { as: 'text', signal: this.#abort.signal });
        ({ name, text: content } = file);
        baseUrl = file.url;
      }
      scene = parseScene(content, { modelOptional: true });
    } catch (error) {
      if (!error.message.startsWith(`${name}:`)) error.message = `${name}: ${error.message}`;
      this.#fail(error);
    }
    Object.assign(result, { scene, name });
    if (!scene.example && !scene.mesh) {
      if (!this.model) await this.example(undefined, { ticket });
      return result;
    }
    // The handles and parts must fit the new model before it replaces the current one (Session.load's check).
    const check = async (model, client) => {
      try {
        result.partition = await sceneFits(scene, model, client);
      } catch (error) {
        if (!error.message.startsWith(`${name}:`)) error.message = `${name}: ${error.message}`;
        throw error;
      }
    };
    // A scene that names a model names its basis too (none: the cage's, with mean value coordinates); back to the
    // old one if it fails.
    await withSettings(this.settings, sceneSubspaceSettings(scene.subspace), async () => {
      if (scene.example) {
        await this.example(scene.example, { check, generateCage: scene.generateCage, ticket });
      } else {
        const paths = [scene.mesh, ...(scene.cage ? [scene.cage] : [])];
        const meshFiles = [];
        for (const path of paths) meshFiles.push(...await this.#sceneFile(path, files, baseUrl, name).catch((error) => this.#fail(error)));
        await this.meshFiles(meshFiles, scene.cage ? null : scene.generateCage, { check, ticket });
      }
    });
    const note = sceneSubspaceNote(scene.subspace ?? {});
    if (note) this.banner.show(note, { kind: 'warning' });
    return result;
  }

  /** A file a scene names (with a .gltf's own files): one dropped with it (same name), else fetched relative to the scene. */
  async #sceneFile(path, files, baseUrl, sceneName) {
    const file = files.find((f) => f.name === path.split('/').pop()) ?? await fetchFile(path, { base: baseUrl, signal: this.#abort.signal }).catch((error) => {
      throw new InputError(`${sceneName} refers to ${path}, which could not be loaded (${error.reason ?? error.message}); ` +
        'drop the scene together with its mesh and cage files', { code: 'unreadable_file' });
    });
    return withGltfFiles(asModelFile(file), files, { signal: this.#abort.signal });
  }

  /** Binds the current model, with the shared handle groups, in the views that have none (new compare views). */
  bindNewViews() {
    const { handles, selection } = this.editor;
    return this.bindViews(this.views.list.filter((v) => !v.session.model), (view) => {
      this.views.showModel(this.model, [view]);
      view.session.setHandles(handles.vertexGroups(), handles.targets(), handles.lines());
      view.showHandles(handles, selection);
    });
  }

  /** Binds the current model in views that have none yet (new compare views); `bound(view)` after each. */
  async bindViews(views, bound) {
    if (!views.length) return;
    this.progress.start('Binding compare views');
    try {
      for (const view of views) {
        await view.session.load('loadMeshes', { ...meshesOf(this.model), subspace: this.subspaceFor(view) });
        bound(view);
      }
    } catch (error) {
      if (!isCancelled(error)) this.banner.show(error.message);
      throw error;
    } finally {
      this.progress.done();
    }
  }

  /** Cancel (the progress bar's button): stops every load in progress; the previous model stays. */
  cancel() {
    for (const view of this.views.list) view.session.cancelLoad();
  }

  /**
   * Binds a model in every view, all or none (prepared_load.js); shows progress, keeps the old model on failure.
   * A request no longer the newest (`ticket`) is cancelled before it binds, and so is one whose model a later
   * request's replaced while it read the model's look.
   */
  async #bind(type, payload, { label, source, keepHandles = false, check, files = [], choice, ticket, chosen = false, values }) {
    this.checkNewest(ticket, label);
    this.progress.start(label);
    this.views.first.session.onProgress = (f, phase) => this.progress.set(f, phase);
    let model;
    try {
      model = await loadEveryView(this.views.list, type, payload, { check, others: (view, m) => ({ ...meshesOf(m), subspace: this.subspaceFor(view, values) }) });
    } catch (error) {
      this.progress.done();
      const spectral = isSpectral(payload.subspace) ? payload.subspace.modes : 0;
      const quiet = chosen && isMissingCage(error); // a lone mesh the page chose for: loaded again at once, no failure
      if (isCancelled(error)) {
        // Cancelled by a later request: that one's outcome is what the page shows.
        if (this.isNewest(ticket)) this.banner.show(`Loading cancelled. ${this.#keptNote()}`, { kind: 'info' });
      } else if (isOverBudget(error) && spectral > 1) {
        offerFewerModes(this, error, spectral, this.#keptNote(),
          (modes) => this.#bind(type, { ...payload, subspace: { basis: 'spectral', modes } }, { label, source, keepHandles, choice, ticket: this.request() }));
      } else if (!quiet) this.banner.show(`${error.message}\n${this.#keptNote()}`);
      if (!quiet) this.#noModel(error);
      throw error;
    }
    this.progress.done();
    this.exampleNames = model.exampleNames ?? this.exampleNames;
    const gltfFile = model.gltf ? payload.gltf ?? gltfFileOf(model.name, files) : undefined;
    const look = gltfFile ? await gltfLookOf(gltfFile, model.gltf.instances) : null;
    if (this.#shown > ticket || this.disposed) {
      look?.dispose();
      throw new CancelledError(`${label} cancelled: ${this.disposed ? 'the app was disposed' : 'a later request replaced it'}`);
    }
    this.#shown = ticket;
    this.model?.look?.dispose();
    // subspace: what the first view was bound with (a saved scene names it).
    this.model = { ...model, source, gltfFile, look, subspace: payload.subspace };
    this.banner.hide();
    if (model.cageQuality?.poor) warnPoorCage(this, model, (vertices) => this.generateCage(vertices));
    showNotes(this.banner, model, { inBanner: !model.cageQuality?.poor });
    this.noCage.bound();
    this.dispatchEvent({ type: 'load', model: this.model, keepHandles });
    if (choice) this.dispatchEvent({ type: 'nocage', choice, model: this.model });
    return model;
  }

  #keptNote() { return this.model ? 'The previous model is kept.' : 'No model is loaded.'; } // a failure's last line

  // A failure before any model was bound: the views say so instead of "loading".
  #noModel(error) { if (!this.model) this.status = `no model loaded: ${isCancelled(error) ? 'cancelled' : error.message.split('\n')[0]}`; }

  /** Shows a failure in the banner (with whether a model stays) and rethrows it; a fetch dispose() stopped is cancelled. */
  #fail(error) {
    if (this.disposed) throw new CancelledError('loading cancelled: the app was disposed');
    this.banner.show(`${error.message}\n${this.#keptNote()}`);
    this.#noModel(error);
    throw error;
  }
}
