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
import { generateCage } from '../cage.js';
import { volumeParts } from '../parts.js';
import { exampleNames as allExampleNames, loadExample } from '../examples.js';
import { singlePrecisionPays } from '../basis_precision.js';
import { PROGRESS, checkRequest } from './protocol.js';

// What the progress bar says while each type of cage coordinates binds.
const COORDINATE_PHASES = { mvc: 'mean value coordinates', pmvc: 'positive mean value coordinates', harmonic: 'harmonic coordinates' };

let solver = null;
let deformer = null;
let model = null; // { name, mesh, cage, gltf?, solverOfFile, restNormals } of the bound session
let ready = null;

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

  async loadExample({ name, generateCage: cageOptions, subspace }) {
    const example = await loadExample(solver, name ?? exampleNames()[0], { onProgress: cageProgress() });
    if (cageOptions) {
      const cage = makeCage(example.mesh, cageOptions, example.name);
      return bind(example.name, `${example.name} in a generated ${cage.positions.length / 3}-vertex cage`, example.mesh, cage,
        'generated cage', { ...example, cageInfo: cage, subspace });
    }
    const cageName = example.cageInfo ? 'generated cage' : 'cage';
    return bind(example.name, example.description, example.mesh, example.cage, cageName, { ...example, subspace });
  },

  async loadFiles({ files, generateCage, subspace }) {
    const { models: meshes, resources } = await readFiles(files);
    meshes.sort((a, b) => b.data.positions.length - a.data.positions.length);
    if (meshes.length > 2) throw new InputError(`give one mesh and at most one cage (got ${meshes.length} models)`);
    const [main, cageFile] = meshes;
    const extra = { gltf: main.gltf, resources };
    if (!cageFile && subspace?.basis === 'spectral') {
      return bind(main.name, `${main.name} in its spectral basis (${subspace.modes} modes)`, main.data, null, 'no cage', { ...extra, subspace });
    }
    if (!cageFile) {
      if (!generateCage) {
        const report = checkMesh(solver, main.data, 'mesh');
        if (!report.ok) {
          throw new MeshError(`${main.name} has no cage, and it cannot get a generated one until these are fixed:\n${report.text}`,
            { findings: report.findings });
        }
        throw new InputError(`${main.name} has no cage. Drop the mesh together with its cage (two files), or use "Generate cage".`,
          { code: 'no_cage' });
      }
      const cage = makeCage(main.data, generateCage, main.name);
      return bind(main.name, `${main.name} in a generated ${cage.positions.length / 3}-vertex cage`, main.data, cage,
        'generated cage', { ...extra, cageInfo: cage, subspace });
    }
    return bind(main.name, `${main.name} in ${cageFile.name}`, main.data, cageFile.data, cageFile.name, { ...extra, subspace });
  },

  async loadMeshes({ name, description, mesh, cage, generateCage: cageOptions, subspace, gltf }) {
    // A glTF model comes back as its file (the page keeps the bytes): read again here for its layout.
    const source = gltf ? await readModel(solver, gltf.bytes, gltf.name, { resources: gltf.resources }) : null;
    const extra = { gltf: source?.gltf, resources: gltf?.resources };
    if (!cage && subspace?.basis === 'spectral') {
      return bind(name, description ?? `${name} in its spectral basis (${subspace.modes} modes)`, mesh, null, 'no cage', { ...extra, subspace });
    }
    if (!cage) {
      if (!cageOptions) throw new InputError(`${name} has no cage`, { code: 'no_cage' });
      const generated = makeCage(mesh, cageOptions, name);
      return bind(name, `${name} in a generated ${generated.positions.length / 3}-vertex cage`, mesh, generated,
        'generated cage', { ...extra, cageInfo: generated, subspace });
    }
    return bind(name, description ?? name, mesh, cage, 'cage', { ...extra, subspace });
  },

  async setVolumeParts({ parts }) {
    const s = session();
    const partition = parts === null || parts === undefined ? null
      : ArrayBuffer.isView(parts) ? parts : volumeParts(solver, model.mesh, parts);
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
    return writeModel(solver, { mesh: model.mesh, gltf: model.gltf }, s.positions(), `${model.name}.glb`,
      { solverOfFile: model.solverOfFile });
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
  async exportObj({ what }) {
    const s = session();
    if (what === 'restCage') {
      return writeObj(solver, model.cage, `subspace-deform: cage of ${model.name} at rest${model.generated ? ' (generated)' : ''}`);
    }
    if (what !== 'mesh' && what !== 'cage') throw new InputError(`exportObj: what must be 'mesh', 'cage' or 'restCage' (got ${what})`);
    const indices = what === 'cage' ? model.cage.indices : model.mesh.indices;
    const positions = what === 'cage' ? s.cagePositions() : s.positions();
    return writeObj(solver, { positions, indices }, `subspace-deform: deformed ${what} of ${model.name}`);
  },
};

// Dropped files: the models (any format readModel reads: the mesh and maybe its cage) and the other files,
// which a .gltf may refer to (its .bin, its textures) by name.
async function readFiles(files) {
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

function session() {
  if (!deformer) throw new InputError('no model is loaded');
  return deformer;
}

function progress(fraction, phase) {
  self.postMessage({ type: PROGRESS, fraction, phase });
}

function exampleNames() {
  return allExampleNames(solver);
}

// A generateCage progress callback that posts at most one message per percent (the generator calls back
// thousands of times).
function cageProgress(phase = 'generating the cage') {
  let shown = -1;
  progress(0, phase);
  return (fraction) => {
    const percent = Math.floor(100 * fraction);
    if (percent !== shown) {
      shown = percent;
      progress(fraction, phase);
    }
  };
}

/**
 * Generates a cage for `mesh` here in the worker, reporting progress (at most one message per percent).
 * The mesh is checked first, so an open or broken mesh gets the checker's findings rather than a
 * generator error.
 */
function makeCage(mesh, { vertices = 120 } = {}, name = 'mesh') {
  const report = checkMesh(solver, mesh, 'mesh');
  if (!report.ok) throw new MeshError(`${name} cannot get a cage:\n${report.text}`, { findings: report.findings });
  return generateCage(solver, mesh, { vertices, onProgress: cageProgress(`generating a ${vertices}-vertex cage`) });
}

// Binds the basis (the cage's W, with extra.subspace's coordinates if any, or with extra.subspace = { basis:
// 'spectral', modes } the spectral basis, for which cage may be null), reporting progress; the Deformer checks
// the pair first (a MeshError with every finding, which gets the model's name here).
// extra.cageInfo: the generateCage result (its statistics go into the Model); extra.defaultHandles and
// extra.defaultView: an example's suggested handles and viewing direction.
function bind(name, description, mesh, cage, cageName = 'cage', extra = {}) {
  const spectral = extra.subspace?.basis === 'spectral';
  const phase = spectral ? 'computing the spectral basis' : `computing ${COORDINATE_PHASES[extra.subspace?.coordinates ?? 'mvc']}`;
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
    modesAsked: spectral ? extra.subspace.modes : undefined,
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
function basisInFloat32(mesh, cage, subspace) {
  const columns = subspace?.basis === 'spectral' ? subspace.modes + 4 : (cage?.positions.length ?? 0) / 3;
  return singlePrecisionPays(mesh.positions.length / 3, columns);
}

function frame(result) {
  const positions = deformer.positions();
  const cage = deformer.cagePositions();
  const render = { ...deformer.renderBuffers({ groups: model.normalGroups, restNormals: model.restNormals }), cage: Float32Array.from(cage) };
  const skeleton = deformer.skeletonReport();
  return skeleton ? { result, positions, cage, render, skeleton } : { result, positions, cage, render };
}

function transferables(value) {
  if (!value || typeof value !== 'object') return [];
  const list = [];
  for (const key of ['positions', 'cage', 'values']) {
    if (ArrayBuffer.isView(value[key])) list.push(value[key].buffer);
  }
  if (value.render) for (const array of Object.values(value.render)) list.push(array.buffer);
  for (const key of ['mesh', 'cage']) {
    const m = value[key];
    if (m && ArrayBuffer.isView(m.positions)) list.push(m.positions.buffer, m.indices.buffer);
  }
  return list;
}

self.onmessage = async (event) => {
  const id = event.data?.id;
  try {
    const { type, payload } = checkRequest(event.data);
    await start(type === 'init' ? payload.threads : undefined);
    const handler = Object.hasOwn(handlers, type) ? handlers[type] : null;
    if (!handler) throw new InputError(`unknown request '${type}'`);
    const result = await handler(payload);
    self.postMessage({ id, ok: true, result }, transferables(result));
  } catch (error) {
    self.postMessage({ id, ok: false, error: errorToData(error) });
  }
};
