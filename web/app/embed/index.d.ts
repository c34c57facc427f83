// Types of 'subspace-deform/element' (index.js): <subspace-deformer> and mount(). Written by hand, unlike the
// library's (generated from web/lib's JSDoc into build/types): the app behind the element is three.js code that
// the package's declarations do not cover, and a page needs only this surface, documented in docs/embed.md
// ("JavaScript API"). tests/js/package.test.js checks that every member of SubspaceDeformerElement is declared
// here and type-checks a strict consumer of it. The library's types are its browser entry's (the package's name
// would resolve to the Node entry's in a consumer that type-checks for Node, which has no WorkerModel).
import type { CoordinateType, Scene, SolverOptions, StopCode, WorkerModel } from '../../../build/types/web/lib/index.js';

/** The three solvers a view runs. */
export type Method = 'subspace' | 'full' | 'arap';

/** A mesh without a cage: the banner asks, or it gets a generated cage, or the spectral basis. */
export type NoCageChoice = 'ask' | 'generate' | 'spectral';

/** The options of mount(), the same as the element's attributes (docs/embed.md, "From a script: mount"). */
export interface MountOptions {
  example?: string;
  lesson?: string;
  mesh?: string;
  cage?: string;
  /** A URL of a scene file, or a scene object (docs/scene-format.md). */
  scene?: string | object;
  /** true: all three methods; a list of methods; 'coordinates': two cage coordinates. */
  compare?: boolean | string | string[];
  panel?: boolean | 'closed';
  panelBeside?: boolean;
  help?: boolean;
  tools?: boolean;
  paused?: boolean;
  labels?: boolean;
  shareLink?: boolean;
  noCage?: NoCageChoice;
  /** Initial values of the panel's settings, such as { method: 'arap', jacobian: 'exact' }; checked by name. */
  settings?: AppSettings;
}

/**
 * What setOptions() and mount()'s settings take: the solver options and the app's own settings (web/app/settings.js;
 * docs/embed.md, setOptions). Every key is checked at run time too: a bad value throws an InputError naming it.
 */
export type AppSettings = SolverOptions & {
  iterationsPerFrame?: 'auto' | number;
  dragIntegration?: 'auto' | 'full' | 'reduced';
  showCage?: boolean;
  showHandles?: boolean;
  wireframe?: boolean;
  flatShading?: boolean;
  gizmoMode?: 'translate' | 'rotate';
  tool?: 'orbit' | 'pick' | 'brush' | 'lasso' | 'bone';
  erase?: boolean;
  brushRadius?: number;
  cageVertices?: number;
  basis?: 'cage' | 'spectral';
  spectralModes?: number;
  autoParts?: number;
  threads?: 'auto' | number;
  arapMaxIterations?: number;
  coordinates?: CoordinateType;
  pmvcResolution?: number;
  harmonicResolution?: number;
  compareCoordinates?: boolean;
};

/** A view's statistics (docs/embed.md, `stats`). */
export interface ViewStats {
  method: Method;
  state: 'converged' | 'solving' | 'paused' | 'stopped' | 'error' | 'idle';
  converged: boolean;
  stopReason: string;
  stop?: StopCode;
  merit: number;
  energy: number;
  lambda: number;
  partLambda: number[] | null;
  volume: number;
  restVolume: number;
  volumeRelError: number;
  iterations: number;
  msPerIteration: number;
  firstIterationMs: number;
  progress: { iteration: number, maxIterations: number, elapsedMs: number, msLeftAtMost: number | null, runningMs: number } | null;
  solver: { build: 'threads' | 'single', threads: number, buildNote?: string };
  fps: number;
  renderFps: number;
  vertexCount: number;
  bindMs: number;
  basis: 'cage' | 'spectral';
  partVolumeChange: number[] | null;
  skeleton: { joints: number[][], bones: { lengthError: number, straightnessError: number, lambda: number, straightHard: boolean }[] } | null;
  warnings: { severity: string, code: string, message: string }[];
  samples: number;
}

/** A rotation of a handle group about its rest centroid. */
export interface Rotation {
  axis: [number, number, number];
  /** radians */
  angle: number;
}

/** A built-in lesson as loaded. */
export interface Lesson {
  id: string;
  title: string;
  caption: string;
  view: unknown;
}

/** The step-through (docs/app.md, step-through). */
export interface Stepping {
  readonly paused: boolean;
  setPaused(on: boolean): Promise<void>;
  toggle(): Promise<void>;
  next(): Promise<unknown[]>;
  nextHalf(): Promise<unknown[]>;
}

/** What one cage vertex controls: its weight over the mesh. */
export interface Influence {
  readonly column: number | null;
  readonly scale: { min: number, max: number } | null;
  show(column: number): Promise<void>;
  hide(): void;
  setPicking(on: boolean): void;
}

/** An event of the app (three.js' EventDispatcher): its type and that type's fields (docs/embed.md). */
export interface AppEvent {
  type: string;
  [field: string]: unknown;
}

/** What the element forwards to its app, the same on both (docs/embed.md, "JavaScript API"). */
export interface DeformerControls {
  statsAll(): ViewStats[];
  loadLesson(id: string): Promise<Lesson>;
  loadExample(name?: string): Promise<WorkerModel>;
  loadUrls(mesh: string, cage?: string): Promise<WorkerModel>;
  loadFiles(files: FileList | File[]): Promise<WorkerModel>;
  setCoordinates(coordinates: CoordinateType, resolution?: number): Promise<WorkerModel>;
  generateCage(vertices?: number): Promise<WorkerModel>;
  setHandles(groups: number[][], options?: { moving?: number[] }): void;
  setTargets(targets: Float64Array | number[]): void;
  drag(index: number, translation: [number, number, number], rotation?: Rotation | null): Promise<ViewStats>;
  solve(): Promise<ViewStats>;
  reset(): Promise<void>;
  resetHandles(): Promise<void>;
  resolveFromRest(): Promise<void>;
  setOptions(options: AppSettings): void;
  setCompare(compare: boolean | string | string[]): Promise<void>;
  positions(view?: number): Float64Array | null;
  cagePositions(view?: number): Float64Array | null;
  restPositions(): Float64Array | null;
  indices(): Uint32Array | null;
  exportObj(what?: 'mesh' | 'cage' | 'restCage'): Promise<string>;
  exportGlb(): Promise<Uint8Array>;
  screenshot(): string;
}

/** The app a mount() returns and the element runs. */
export interface DeformerApp extends DeformerControls {
  addEventListener(type: string, listener: (event: AppEvent) => void): void;
  removeEventListener(type: string, listener: (event: AppEvent) => void): void;
  readonly ready: Promise<WorkerModel>;
  readonly model: WorkerModel | null;
  readonly stats: ViewStats;
  readonly lesson: Lesson | null;
  readonly stepping: Stepping;
  readonly influence: Influence;
  readonly compare: unknown;
  readonly settings: AppSettings;
  readonly panelOpen: boolean;
  readonly ignoredOptions: string[];
  loadScene(scene: string | Scene | object, options?: { json?: boolean }): Promise<WorkerModel>;
  setBasis(basis: 'cage' | 'spectral', modes?: number): Promise<WorkerModel>;
  cancelLoad(): void;
  fitView(direction?: [number, number, number]): void;
  sceneJson(): object;
  undo(): void;
  redo(): void;
  setPanelOpen(open: boolean): void;
  openFilePicker(): void;
  dispose(): void;
}

/** Creates the app inside `element`. */
export function mount(element: HTMLElement, options?: MountOptions): DeformerApp;

/**
 * <subspace-deformer>: attributes as MountOptions (kebab-case); its events are 'load' and 'nocage'. Before it is in
 * the document its methods throw an InputError and `ready` rejects.
 */
export class SubspaceDeformerElement extends HTMLElement {
  /** The running app, null before the element connects and after it disconnects. */
  app: DeformerApp | null;
  connectedCallback(): void;
  disconnectedCallback(): void;
  /** Attributes are read once, at connect: a later change warns once in the console, naming the API to use. */
  attributeChangedCallback(name: string, oldValue: string | null, newValue: string | null): void;
  readonly ready: Promise<WorkerModel>;
  readonly stats: ViewStats | undefined;
  readonly lesson: Lesson | null;
  readonly stepping: Stepping | undefined;
  readonly influence: Influence | undefined;
  fitView(): void;
  loadScene(scene: string | Scene | object): Promise<WorkerModel>;
}
/** The element's forwarding methods (declaration merging with the class above). */
export interface SubspaceDeformerElement extends DeformerControls {}

/** Defines the element (index.js does, as 'subspace-deformer'); again under another name is allowed. */
export function defineElement(name?: string): void;

declare global {
  interface HTMLElementTagNameMap {
    'subspace-deformer': SubspaceDeformerElement;
  }
}
