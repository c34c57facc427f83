// One method's view: a Viewport (canvas, camera, mesh, cage, handle dots, stats line, convergence plot), the
// solver Session that deforms its mesh in a worker, the gizmo on the shared handle groups and the vertex
// picker. Compare mode shows several, one per method, or two subspace views with different cage coordinates
// (the view's key, methods.js: 'subspace:harmonic').
//
// Events: 'frame' (a solver result was drawn), 'error' { error } (the session failed), 'pick' / 'select'
// (from the picker: { vertex | vertices, op }), 'stroke' { phase } (a stroke starts or is cancelled),
// 'camera' (the user moved this view's camera).
import { EventDispatcher } from 'three';
import { isSpectral } from '../../lib/subspace.js';
import { handleLineWarnings } from '../../lib/handle_lines.js';
import { skeletonWarnings } from '../../lib/skeleton.js';
import { Viewport } from './viewport.js';
import { HandleGizmo } from '../interaction/handle_gizmo.js';
import { IterationTrace } from './iteration_trace.js';
import { VertexPicker } from '../interaction/vertex_picker.js';
import { Session } from '../session.js';
import { methodColor, methodLabel, parseViewKey, viewLabel } from '../methods.js';
import { statsLine, volumeChangeText } from '../stats_format.js';
import { InfluenceLegend } from '../influence/influence_legend.js';
import { SkeletonView } from '../skeleton/skeleton_view.js';
import { touchesSolver } from '../settings.js';

/** Whether the main pointer is a finger (phones, tablets): bigger gizmo handles. */
function coarsePointer() {
  return globalThis.matchMedia?.('(pointer: coarse)').matches ?? false;
}

export class SolverView extends EventDispatcher {
  /**
   * @param {HTMLElement} parent
   * @param {string} key the view's key (methods.js): a method, or 'subspace:<coordinates>'
   * @param {{ handles: import('../interaction/handle_set.js').HandleSet, brushRadius: () => number,
   *           tool: () => { tool: string, erase: boolean }, state: import('../app_state.js').AppState }} options
   *   brushRadius: the brush's world-space radius; tool: what a one-finger press does (settings); state: the app's
   *   state, whose settings changes the view follows (its method's solver options, the display) until disposed
   */
  constructor(parent, key, { handles, brushRadius, tool, state }) {
    super();
    const { method, coordinates } = parseViewKey(key);
    this.key = key;
    this.method = method;
    /** The cage coordinates this view binds (null: the app's setting). */
    this.coordinates = coordinates;
    this.viewport = new Viewport(parent, { label: viewLabel(key), color: methodColor(method) });
    // Only the subspace solve moves the cage; the others draw it dimmed, at rest, and say so.
    this.cageNote = Object.assign(document.createElement('div'), { className: 'sd-cage-note' });
    this.viewport.element.appendChild(this.cageNote);
    this.#showCageRole(method);
    /** Latest solver positions of the mesh and the cage (Float64Array), for the scripting API. */
    this.positions = null;
    this.cagePositions = null;
    this.session = new Session({
      method,
      onFrame: (frame) => this.#onFrame(frame),
      onError: (error) => this.dispatchEvent({ type: 'error', error }),
    });
    this.handles = handles; // the groups every view shares
    this.gizmo = new HandleGizmo(this.viewport, handles);
    this.gizmo.setTouchSize(coarsePointer());
    this.picker = new VertexPicker(this.viewport, { gizmoAt: (event) => this.gizmo.hitTest(event), brushRadius, tool });
    this.picker.addEventListener('pick', (e) => this.dispatchEvent({ type: 'pick', vertex: e.vertex, op: e.op }));
    this.picker.addEventListener('select', (e) => this.dispatchEvent({ type: 'select', vertices: e.vertices, op: e.op }));
    this.picker.addEventListener('stroke', (e) => this.dispatchEvent({ type: 'stroke', phase: e.phase }));
    this.viewport.controls.addEventListener('change', () => this.dispatchEvent({ type: 'camera' }));
    this.trace = new IterationTrace(this.viewport.element);
    this.statsKey = '';
    this.plotKey = '';
    this.legend = new InfluenceLegend(this.viewport.element);
    this.partsColors = null; // the volume parts' colours, drawn when no influence is shown
    this.influence = null;
    this.skeletonView = new SkeletonView(this.viewport); // the skeleton's joints and bones (skeleton/skeleton.js draws them)
    this.unsubscribe = state.subscribe((change) => change.settings && this.#followSettings(state.settings, change.settings));
  }

  // A settings change: the solver hears only of those that concern it (settings.js), the display of every one.
  #followSettings(settings, changed) {
    if (touchesSolver(changed)) this.applySolverSettings(settings);
    this.applyDisplay(settings.values);
  }

  /** Step-through: the session waits for single steps; the trace shows what each one did. */
  setPaused(paused) {
    this.session.setPaused(paused);
    if (paused) this.trace.prompt('paused: step (N) runs one iteration; a drag now moves the targets only');
    else this.trace.hide();
  }

  /** Shows what the last single step did (step_through.js). */
  showTrace(trace) {
    const { c1, c2 } = this.session.options;
    const label = viewLabel(trace.method === this.method ? this.key : trace.method, this.model);
    this.trace.show({ ...trace, label, skeleton: this.skeletonView.report }, { c1: c1 ?? 1e-4, c2: c2 ?? 0.5 });
  }

  get element() {
    return this.viewport.element;
  }

  /** Shows the method's name as the view's label, or none (a single view needs none). */
  showLabel(visible) {
    this.labelShown = visible;
    this.viewport.label.textContent = visible ? viewLabel(this.key, this.model) : '';
  }

  /** Switches this view (and its session) to another method; the caller then applies that method's settings. */
  setMethod(method) {
    this.key = method;
    this.coordinates = null;
    this.method = method;
    this.session.setMethod(method);
    this.viewport.label.textContent = this.labelShown === false ? '' : viewLabel(method, this.model);
    this.viewport.plot.color = methodColor(method);
    this.#showCageRole(method);
  }

  #showCageRole(method) {
    const follows = method === 'subspace';
    this.viewport.cageView.setFollows(follows);
    // No note where no cage is drawn (a lone mesh, or the spectral basis).
    const note = follows || !this.viewport.cageView.shown ? '' : `rest cage (dimmed): ${methodLabel(method)} does not move it`;
    this.cageNote.textContent = note;
    this.viewport.invalidate();
  }

  /** Solver settings of this view's method (settings.js) for the session. */
  applySolverSettings(settings) {
    this.session.applySettings({
      options: settings.solverOptions(this.method),
      maxIterations: settings.maxIterationsFor(this.method),
      iterationsPerStep: settings.values.iterationsPerFrame,
      dragIntegration: settings.values.dragIntegration,
    });
  }

  /** Display settings: cage, handles, wireframe, shading, gizmo mode. */
  applyDisplay(values) {
    const viewport = this.viewport;
    viewport.cageView.object.visible = values.showCage;
    this.cageNote.hidden = !values.showCage;
    viewport.handleView.object.visible = values.showHandles;
    viewport.meshView.setWireframe(values.wireframe);
    if (viewport.meshView.material.flatShading !== values.flatShading) viewport.meshView.setFlat(values.flatShading);
    this.gizmo.setMode(values.gizmoMode);
    this.skeletonView.setXray(values.tool === 'bone'); // the bone tool sees the joints inside
    viewport.invalidate();
  }

  /**
   * Shows a newly bound model at rest (the caller frames it). An influence shown before is gone (new mesh), and so is
   * a stroke under way (it painted the mesh before).
   */
  showModel(model) {
    this.picker.endStroke();
    this.model = model; // its basis names the subspace view (the cage's, or the spectral one)
    if (this.labelShown) this.viewport.label.textContent = viewLabel(this.key, model);
    this.plotKey = '';
    this.influence = null;
    this.legend.show(null);
    this.positions = model.mesh.positions.slice();
    this.cagePositions = model.cage.positions.slice();
    this.viewport.meshView.setMesh(model.mesh);
    this.viewport.meshView.setLook(model.look ?? null);
    this.skeletonView.fit(); // joints and sticks sized for this model
    // The spectral basis needs no cage: a cage the model has (to switch back) is not drawn, it drives nothing.
    this.viewport.cageView.setCage(isSpectral(model) ? { positions: new Float64Array(0), indices: new Uint32Array(0) } : model.cage);
    this.#showCageRole(this.method);
  }

  /** Colours the mesh by volume part (RGB per vertex), or plain (null); an influence shown stays on top. */
  showParts(colors) {
    this.partsColors = colors;
    if (!this.influence) this.viewport.meshView.setColors(colors);
    else this.legend.show(this.influence.legend, { partsHidden: !!colors }); // the legend says the paint is under it
    this.viewport.invalidate();
  }

  /**
   * Colours the mesh by a basis column with its legend and marks the cage vertex (influence.js), or back to
   * the parts' colours (null).
   * @param {{ colors: Float32Array, cageVertex: number, legend: object }|null} influence
   */
  showInfluence(influence) {
    this.influence = influence;
    this.viewport.meshView.setColors(influence ? influence.colors : this.partsColors);
    this.legend.show(influence?.legend ?? null, { partsHidden: !!this.partsColors });
    this.viewport.cageView.setHighlight(influence?.cageVertex ?? -1);
    this.viewport.invalidate();
  }

  /** Redraws the handle dots (groups and the pending selection) and places the gizmo. */
  showHandles(handles, selection) {
    const viewport = this.viewport;
    viewport.handleView.setHandles(handles, selection);
    viewport.handleView.update(viewport.meshView.positions);
    this.gizmo.sync();
    viewport.invalidate();
  }

  /** Targets moved (same groups): only the arrows, and the gizmo unless it is the one being dragged. */
  showTargets(handles) {
    this.viewport.handleView.setArrows(handles);
    if (!this.gizmo.dragging) this.gizmo.sync();
    this.viewport.invalidate();
  }

  /** Takes another view's camera (linked cameras in compare mode). */
  copyCamera(source) {
    const from = source.viewport;
    const to = this.viewport;
    to.camera.position.copy(from.camera.position);
    to.camera.quaternion.copy(from.camera.quaternion);
    to.controls.target.copy(from.controls.target);
    to.controls.update();
  }

  #onFrame(frame) {
    const viewport = this.viewport;
    this.positions = frame.positions;
    this.cagePositions = frame.cage;
    viewport.meshView.update(frame.render);
    viewport.cageView.update(frame.render.cage);
    viewport.handleView.update(viewport.meshView.positions);
    this.skeletonView.follow(frame.skeleton); // the joints follow the mesh (the worker's report; none without bones)
    viewport.invalidate();
    this.dispatchEvent({ type: 'frame' });
  }

  /**
   * The stats of the scripting API for this view (docs/embed.md).
   * @param {object|null} model the bound model
   * @param {{ fps: number, renderFps: number }} rates
   */
  stats(model, { fps, renderFps }) {
    const session = this.session;
    const last = session.last;
    return {
      method: this.method,
      state: session.status, // step-through: 'paused' for a solve that waits for the next step
      converged: session.state === 'converged',
      stopReason: session.stopReason,
      merit: last?.merit ?? 0,
      energy: last?.energy ?? 0,
      lambda: last?.lambda ?? 0, // the volume multiplier (with volume parts: partLambda, one per part)
      partLambda: last?.partLambda ?? null,
      volume: last?.volume ?? model?.restVolume ?? 0,
      restVolume: model?.restVolume ?? 0,
      volumeRelError: last?.volumeRelError ?? 0,
      iterations: session.totalIterations,
      msPerIteration: session.msPerIteration,
      firstIterationMs: session.record.firstMs,
      progress: session.progress,
      solver: session.client?.info ?? session.model?.solver ?? null,
      fps,
      renderFps,
      vertexCount: model ? model.mesh.positions.length / 3 : 0,
      bindMs: model?.bindMs ?? 0,
      basis: model?.basis ?? 'cage',
      partVolumeChange: last?.partVolumeChange ?? null, // with volume parts: each part's relative change
      skeleton: this.skeletonView.report, // the bones' errors and multipliers (skeleton_view.js), or null
      // A reduced rule that failed its test, the settled result's (folds, a crossed cage), and what ARAP ignores: the
      // groups' lines (a drag in the screen plane) and the bones its worker holds. The CLI's report says the same in
      // the same words (handle_lines.js, skeleton.js).
      warnings: [...session.warnings, ...handleLineWarnings(session.method, this.handles.lines()),
        ...skeletonWarnings(session.method, this.skeletonView.report)],
      samples: last?.samples ?? 0, // reduced integration (while dragging a large model): its samples; 0: full
      finishing: last?.finishing ?? false, // a reduced solve's last iterations, on every vertex (method.md 17.3)
    };
  }

  /**
   * Redraws the stats line and the plot, touching the DOM and the canvas only when their content changed
   * (no layout or canvas work while idle). Small views keep the model visible: no plot, smaller stats.
   */
  drawStats(stats, loaded) {
    const element = this.viewport.element;
    const compact = element.clientHeight < 440 || element.clientWidth < 300;
    // Views stacked on a phone can be a hundred pixels high: one line of numbers, no cage note.
    const tiny = element.clientHeight < 200;
    element.classList.toggle('sd-compact', compact);
    element.classList.toggle('sd-tiny', tiny);
    const line = statsLine(stats, { loaded, requestSize: this.session.iterationsForNextStep });
    if (compact) line.numbers = line.numbers.split('\n').slice(0, 2).join('\n'); // the model stays visible
    if (tiny && loaded === true && stats.iterations) line.numbers = `volume ${volumeChangeText(stats)}%`;
    const key = `${line.numbers}|${line.state}|${line.reason}|${tiny}`;
    if (this.statsKey !== key) {
      this.statsKey = key;
      this.viewport.statsLine.replaceChildren(
        document.createTextNode(`${line.numbers}${tiny ? '  ' : '\n'}`),
        Object.assign(document.createElement('span'), { className: `sd-${line.state}`, textContent: line.label }),
        document.createTextNode(line.reason),
      );
    }
    const series = this.session.record.current;
    const history = series?.points ?? [];
    const plotKey = `${this.session.record.series.length}|${history.length}|${history.at(-1)?.iteration}|${compact}`;
    if (this.plotKey !== plotKey) {
      this.plotKey = plotKey;
      const method = series?.method ?? this.method;
      const label = viewLabel(method === this.method ? this.key : method, this.model);
      this.viewport.plot.draw(history, { label, color: methodColor(method) });
    }
  }

  dispose() {
    this.unsubscribe();
    this.boneTool?.dispose();
    this.skeletonView.dispose();
    this.legend.dispose();
    this.picker.dispose();
    this.gizmo.dispose();
    this.session.dispose();
    this.viewport.dispose();
  }
}
