// @ts-check
// The solver's Web Worker: it loads the wasm module, owns one Deformer session and answers requests, so
// binding (W), cage generation and Gauss-Newton iterations never block the page. One worker serves one
// view; compare mode runs one per method. Cancelling a long load = terminating the worker (solver_client.js).
// The messages, their payloads and replies: protocol.js. Failures are posted as { code, message, findings }
// (errors.js) and rebuilt into the same typed errors on the page.
import { loadSolver } from '../load.js';
import { Deformer } from '../deformer.js';
import { InputError, MeshError, errorToData } from '../errors.js';
import { checkMesh, writeObj } from '../mesh.js';
import { isModelName } from '../formats.js';
import { readModel, writeModel } from '../model_io.js';
import { normalGroups } from '../normals.js';
import { volumeParts } from '../parts.js';
import { exampleNames as allExampleNames, loadExample } from '../examples.js';
import { singlePrecisionPays } from '../basis_precision.js';
import { describeSubspace, isSpectral } from '../subspace.js';
import { cageProgress, resolveCage } from './cage_resolution.js';
import { PROGRESS, checkRequest } from './protocol.js';

/** @typedef {import('../mesh.js').MeshData} MeshData */
/**
 * The bound session's model as the worker keeps it for exports and render buffers.
 * @typedef {{ name: string, mesh: MeshData, cage: MeshData, generated: boolean, gltf: any, solverOfFile: Int32Array,
 *             restNormals: Float32Array|null, normalGroups: Int32Array }} BoundModel
 */

/** @type {import('../solver_module.js').SolverModule} set by start() before any handler runs */
let solver = /** @type {any} */ (null);
/** @type {Deformer|null} */
let deformer = null;
/** @type {BoundModel|null} */
let model = null;
/** @type {Promise<void>|null} */
let ready = null;

/** @param {number} [threads] */
function start(threads) {
  ready ??= loadSolver({ threads }).then((module) => {
    solver = module;
  });
  return ready;
}

/** @returns {import('./protocol.js').SolverInfo} */
function solverInfo() {
  return { build: solver.build, threads: solver.threads(), buildNote: solver.buildNote };
}

/** @type {Record<string, (payload: any) => Promise<any>>} one per request type of protocol.js (checkRequest
 *  admits only those types, and the lookup below reads own properties only) */
const handlers = {
  async init() {
    return solverInfo();
  },
  async setThreads({ threads }) {
    solver.setThreads(threads);
    return solverInfo();
  },

  // Each load resolves its cage the one way (load below, cage_resolution.js); they differ in where the model comes from.
  async loadExample({ name, generateCage, subspace }) {
    const example = await loadExample(solver, name ?? exampleNames()[0], { onProgress: cageProgress(progress) });
    const given = { cage: example.cage, cageName: example.cageInfo ? 'generated cage' : 'cage', description: example.description };
    // generateCage: a generated cage instead of the example's own.
    return load({ name: example.name, mesh: example.mesh, given, generate: generateCage, regenerate: true, subspace }, example);
  },

  async loadFiles({ files, generateCage, subspace }) {
    const { models: meshes, resources } = await readFiles(files);
    meshes.sort((a, b) => b.data.positions.length - a.data.positions.length);
    if (meshes.length > 2) throw new InputError(`give one mesh and at most one cage (got ${meshes.length} models)`);
    const [main, cageFile] = meshes;
    const given = cageFile ? { cage: cageFile.data, cageName: cageFile.name, description: `${main.name} in ${cageFile.name}` } : null;
    return load({ name: main.name, mesh: main.data, given, generate: generateCage, subspace }, { gltf: main.gltf, resources });
  },

  async loadMeshes({ name, description, mesh, cage, generateCage, subspace, gltf }) {
    // A glTF model comes back as its file (the page keeps the bytes): read again here for its layout.
    const source = gltf ? await readModel(solver, gltf.bytes, gltf.name, { resources: gltf.resources }) : null;
    const given = cage ? { cage, cageName: 'cage', description: description ?? name } : null;
    return load({ name, mesh, given, generate: generateCage, subspace, description }, { gltf: source?.gltf, resources: gltf?.resources });
  },

  async setVolumeParts({ parts }) {
    const s = session();
    // One part per triangle as sent (the Deformer checks it), or a description parts.js turns into that.
    const partition = parts === null || parts === undefined ? null
      : ArrayBuffer.isView(parts) ? /** @type {Int32Array} */ (parts) : volumeParts(solver, bound().mesh, parts);
    s.setVolumeParts(partition);
    return { parts: s.volumeParts(), restPartVolumes: s.restPartVolumes() };
  },

  async setSkeleton({ skeleton }) {
    const s = session();
    s.setSkeleton(skeleton ?? null);
    return { skeleton: s.skeletonReport() };
  },

  async setOptions({ options }) {
    session().setOptions(options);
  },
  async setHandles({ groups }) {
    session().setHandles(groups);
  },
  async setTargets({ targets, lines }) {
    session().setTargets(targets);
    if (lines !== undefined) session().setHandleLines(lines);
  },
  async reset() {
    session().reset();
    return frame({ iterations: [], converged: false, stop: 'no_iterations', stopReason: 'reset to the rest pose' });
  },
  async step({ iterations }) {
    return frame(session().step(iterations));
  },
  async arapHalfStep({ phase }) {
    const half = session().arapHalfStep(phase);
    return { ...frame({ iterations: [], converged: false, stop: 'no_iterations', stopReason: `ARAP ${phase} step` }), half };
  },
  async resultWarnings() {
    return session().resultWarnings();
  },
  async exportGlb() {
    const s = session();
    const m = bound();
    return writeModel(solver, { mesh: m.mesh, gltf: m.gltf }, s.positions(), `${m.name}.glb`, { solverOfFile: m.solverOfFile });
  },
  async basisColumn({ column }) {
    const values = session().basisColumn(column);
    let min = Infinity, max = -Infinity;
    for (const v of values) {
      if (v < min) min = v;
      if (v > max) max = v;
    }
    return { column, values, min, max };
  },
  async prepareReduced() {
    const s = session();
    s.prepareReduced();
    return s.reducedIntegration();
  },
  async prepareFactor() {
    session().prepareFactor();
  },
  async exportObj({ what }) {
    const s = session();
    const m = bound();
    if (what === 'restCage') {
      return writeObj(solver, m.cage, `subspace-deform: cage of ${m.name} at rest${m.generated ? ' (generated)' : ''}`);
    }
    if (what !== 'mesh' && what !== 'cage') throw new InputError(`exportObj: what must be 'mesh', 'cage' or 'restCage' (got ${what})`);
    const indices = what === 'cage' ? m.cage.indices : m.mesh.indices;
    const positions = what === 'cage' ? s.cagePositions() : s.positions();
    return writeObj(solver, { positions, indices }, `subspace-deform: deformed ${what} of ${m.name}`);
  },
};

// Dropped files: the models (any format readModel reads: the mesh and maybe its cage) and the other files,
// which a .gltf may refer to (its .bin, its textures) by name.
/** @param {{ name: string, bytes: Uint8Array }[]} files */
async function readFiles(files) {
  /** @type {Record<string, Uint8Array>} */
  const resources = {};
  const modelFiles = files.filter((file) => isModelName(file.name));
  for (const file of files) if (!modelFiles.includes(file)) resources[file.name] = file.bytes;
  const models = [];
  for (const file of modelFiles) {
    const read = await readModel(solver, file.bytes, file.name, { resources });
    models.push({ name: file.name, data: read.mesh, gltf: read.gltf });
  }
  if (!models.length) throw new InputError(`no model among ${files.map((f) => f.name).join(', ')}`);
  return { models, resources };
}

/** @returns {Deformer} */
function session() {
  if (!deformer) throw new InputError('no model is loaded');
  return deformer;
}

/** @returns {BoundModel} */
function bound() {
  if (!model) throw new InputError('no model is loaded');
  return model;
}

/** @param {number} fraction @param {string} phase */
function progress(fraction, phase) {
  scope.postMessage({ type: PROGRESS, fraction, phase });
}

function exampleNames() {
  return allExampleNames(solver);
}

/**
 * The one load path: the cage resolved (the one given, a generated one, or none for the spectral basis; else the
 * refusal, cage_resolution.js), then bound. `extra`: what the model's source adds (bind).
 * @param {Parameters<typeof resolveCage>[1] & { subspace?: import('../subspace.js').Subspace }} request
 * @param {BindExtra} [extra]
 */
function load(request, extra = {}) {
  const { cage, cageName, description, generated } = resolveCage({ solver, post: progress }, request);
  return bind(request.name, description, request.mesh, cage, cageName, { ...extra, cageInfo: generated ?? extra.cageInfo, subspace: request.subspace });
}

/**
 * What a model's source adds to its binding. cageInfo: the generateCage result (its statistics go into the
 * Model); defaultHandles and defaultView: an example's suggested handles and viewing direction.
 * @typedef {{ subspace?: import('../subspace.js').Subspace, cageInfo?: import('../cage.js').CageResult|null, gltf?: any,
 *             resources?: Record<string, Uint8Array>,
 *             defaultHandles?: import('./protocol.js').Model['defaultHandles'],
 *             defaultView?: import('./protocol.js').Model['defaultView'] }} BindExtra
 */
/**
 * Binds the basis (the cage's W, with extra.subspace's coordinates if any, or with extra.subspace = { basis:
 * 'spectral', modes } the spectral basis, for which cage may be null), reporting progress; the Deformer checks the
 * pair first (a MeshError with every finding, which gets the model's name here).
 * @param {string} name @param {string} description @param {MeshData} mesh @param {MeshData|null} cage
 * @param {string} [cageName] @param {BindExtra} [extra]
 * @returns {import('./protocol.js').Model}
 */
function bind(name, description, mesh, cage, cageName = 'cage', extra = {}) {
  const phase = `computing ${describeSubspace(extra.subspace, { modes: false })}`;
  const float32 = basisInFloat32(mesh, cage, extra.subspace);
  progress(0, phase);
  let next;
  try {
    next = Deformer.create(solver, mesh, cage, { onProgress: (fraction) => progress(fraction, phase), float32, ...(extra.subspace ?? {}) });
  } catch (error) {
    if (!(error instanceof MeshError)) throw error;
    throw new MeshError(`${name} / ${cageName} cannot be used:\n${error.message}`, { code: error.code, findings: error.findings });
  }
  deformer?.dispose();
  deformer = next;
  const kept = cage ?? { positions: new Float64Array(0), indices: new Uint32Array(0) };
  const layout = deformer.layout();
  const restNormals = extra.gltf?.restNormals ?? null;
  model = { name, mesh, cage: { positions: kept.positions, indices: kept.indices }, generated: !!extra.cageInfo,
    gltf: extra.gltf, solverOfFile: layout.solverOfFile, restNormals,
    normalGroups: normalGroups(mesh.positions.length / 3, { solverOfFile: layout.solverOfFile, restNormals }) };
  progress(1, 'done');
  const info = extra.cageInfo;
  return {
    name,
    description,
    // Copies: the worker keeps its own for exports.
    mesh: { positions: mesh.positions.slice(), indices: mesh.indices.slice() },
    cage: { positions: kept.positions.slice(), indices: kept.indices.slice() },
    basis: deformer.basis,
    basisSize: deformer.basisSize,
    coordinates: deformer.coordinatesReport(),
    // The spectral modes asked for: eigenvectors in the span of those before them are left out (spectral_basis.h),
    // so basisSize - 4 can be less.
    modesAsked: isSpectral(extra.subspace) ? extra.subspace.modes : undefined,
    restVolume: deformer.restVolume,
    bindMs: deformer.bindMs,
    vertexCount: deformer.vertexCount,
    float32,
    exampleNames: exampleNames(),
    canGenerateCage: true,
    solver: solverInfo(),
    // A few ms to a few hundred (a 391-vertex cage on 40k vertices: 0.23 s): worth knowing before a drag.
    // Only a cage basis has a cage to judge.
    cageQuality: deformer.basis === 'cage' && cage ? deformer.cageQuality() : null,
    generatedCage: info ? { vertices: info.positions.length / 3, volumeRatio: info.volumeRatio, minClearance: info.minClearance,
      attempts: info.attempts, ms: info.ms } : undefined,
    defaultHandles: extra.defaultHandles,
    // What loading did to the model (welding, holes, components): the model check's notes and warnings.
    notes: checkMesh(solver, mesh).findings.filter((f) => f.severity !== 'error'),
    layout: { ...layout, solverOfFile: layout.solverOfFile.slice() },
    volumePartCount: deformer.restPartVolumes().length,
    gltf: extra.gltf ? { instances: extra.gltf.instances } : undefined,
    defaultView: extra.defaultView,
  };
}

// Large bases are stored in single precision (basis_precision.js).
/** @param {MeshData} mesh @param {MeshData|null} cage @param {import('../subspace.js').Subspace} [subspace] */
function basisInFloat32(mesh, cage, subspace) {
  const columns = isSpectral(subspace) ? subspace.modes + 4 : (cage?.positions.length ?? 0) / 3;
  return singlePrecisionPays(mesh.positions.length / 3, columns);
}

/** @param {import('../deformer.js').StepResult} result @returns {import('./protocol.js').Frame} */
function frame(result) {
  const s = session();
  const { normalGroups: groups, restNormals } = bound();
  const positions = s.positions();
  const cage = s.cagePositions();
  const render = { ...s.renderBuffers({ groups, restNormals }), cage: Float32Array.from(cage) };
  const skeleton = s.skeletonReport();
  return skeleton ? { result, positions, cage, render, skeleton } : { result, positions, cage, render };
}

/** The buffers a reply hands over rather than copies. @param {any} value a handler's result @returns {ArrayBufferLike[]} */
function transferables(value) {
  if (!value || typeof value !== 'object') return [];
  /** @type {ArrayBufferLike[]} */
  const list = [];
  for (const key of ['positions', 'cage', 'values']) {
    if (ArrayBuffer.isView(value[key])) list.push(value[key].buffer);
  }
  if (value.render) for (const array of Object.values(value.render)) list.push(/** @type {Float32Array} */ (array).buffer);
  for (const key of ['mesh', 'cage']) {
    const m = value[key];
    if (m && ArrayBuffer.isView(m.positions)) list.push(m.positions.buffer, m.indices.buffer);
  }
  return list;
}

// The worker's scope (the library is typed against the DOM, whose `self` is a window).
const scope = /** @type {{ postMessage(message: unknown, transfer?: Transferable[]): void,
  onmessage: ((event: MessageEvent) => void)|null }} */ (/** @type {unknown} */ (self));

scope.onmessage = async (/** @type {MessageEvent} */ event) => {
  const id = event.data?.id;
  try {
    const { type, payload } = checkRequest(event.data);
    await start(type === 'init' ? /** @type {number|undefined} */ (payload.threads) : undefined);
    const handler = Object.hasOwn(handlers, type) ? handlers[type] : null;
    if (!handler) throw new InputError(`unknown request '${type}'`);
    const result = await handler(payload);
    scope.postMessage({ id, ok: true, result }, /** @type {Transferable[]} */ (transferables(result)));
  } catch (error) {
    scope.postMessage({ id, ok: false, error: errorToData(error) });
  }
};
