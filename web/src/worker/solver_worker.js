// The solver's Web Worker: it loads the wasm module, owns one Deformer session and answers requests, so
// binding (W) and Gauss-Newton iterations never block the page. One worker serves one view; compare mode
// runs one per method. Cancelling a long bind = terminating the worker (see solver_client.js).
//
// Protocol (main -> worker): { id, type, ...payload }; reply: { id, ok: true, result } or
// { id, ok: false, error: message }. Unsolicited: { type: 'progress', fraction, phase }.
//   hello                                  -> { exampleNames }
//   loadExample { name? }                  -> Model (below); no name = the default example
//   loadFiles { files: [{ name, bytes }], generateCage?: { vertices } }
//                                          -> Model; the mesh with more vertices is the mesh, the other the cage
//   loadMeshes { name, mesh, cage }        -> Model (meshes already parsed: compare views, scenes)
//   setOptions { options } | setHandles { groups } | setTargets { targets } | reset
//   step { iterations }                    -> Frame      solve -> Frame
//   exportObj { what: 'mesh'|'cage' }      -> OBJ text of the current deformed mesh or cage
// Model = { name, description, mesh, cage, restVolume, bindMs, vertexCount, check, exampleNames, canGenerateCage }
// Frame = { result: { iterations, converged, stopReason }, positions: Float64Array, cage: Float64Array }
// Positions travel as transferable buffers (no copy).
import { loadSolver } from '../solver/load.js';
import { Deformer } from '../solver/deformer.js';
import { readMesh, checkPair, checkMesh, writeObj, makeExample, exampleNames } from '../solver/mesh.js';

// The cage generator arrives with the cage issue; the glob is empty until web/src/solver/cage.js exists.
const cageModules = import.meta.glob('../solver/cage.js');

let solver = null;
let deformer = null;
let model = null; // { name, mesh, cage } of the bound session
const ready = loadSolver().then((module) => {
  solver = module;
});

const handlers = {
  async hello() {
    return { exampleNames: exampleNames(solver), canGenerateCage: Object.keys(cageModules).length > 0 };
  },

  async loadExample({ name }) {
    const example = makeExample(solver, name ?? exampleNames(solver)[0]);
    return bind(example.name ?? name, example.description ?? name, example.mesh, example.cage);
  },

  async loadFiles({ files, generateCage }) {
    const meshes = files.map((file) => ({ name: file.name, data: readMesh(solver, file.bytes, file.name) }));
    meshes.sort((a, b) => b.data.positions.length - a.data.positions.length);
    const [main, cageFile] = meshes;
    if (!cageFile) {
      if (!generateCage) {
        const report = checkMesh(solver, main.data, 'mesh');
        const problems = report.ok ? '' : `\n${report.text}`;
        throw new Error(`${main.name} has no cage. Drop the mesh together with its cage (two files)` +
          `${Object.keys(cageModules).length ? ', or use "Generate cage"' : ''}.${problems}`);
      }
      const { generateCage: generate } = await Object.values(cageModules)[0]();
      progress(0, 'generating cage');
      const cage = generate(solver, main.data, generateCage);
      return bind(main.name, `${main.name} with a generated cage`, main.data, cage);
    }
    return bind(main.name, `${main.name} in ${cageFile.name}`, main.data, cageFile.data, cageFile.name);
  },

  async loadMeshes({ name, description, mesh, cage }) {
    return bind(name, description ?? name, mesh, cage);
  },

  async setOptions({ options }) {
    session().setOptions(options);
  },
  async setHandles({ groups }) {
    session().setHandles(groups);
  },
  async setTargets({ targets }) {
    session().setTargets(targets);
  },
  async reset() {
    session().reset();
    return frame({ iterations: [], converged: true, stopReason: 'reset' });
  },
  async step({ iterations }) {
    return frame(session().step(iterations));
  },
  async solve() {
    return frame(session().solve());
  },
  async exportObj({ what }) {
    const s = session();
    const indices = what === 'cage' ? model.cage.indices : model.mesh.indices;
    const positions = what === 'cage' ? s.cagePositions() : s.positions();
    return writeObj(solver, { positions, indices }, `subspace-deform: deformed ${what} of ${model.name}`);
  },
};

function session() {
  if (!deformer) throw new Error('no model is loaded');
  return deformer;
}

function progress(fraction, phase) {
  self.postMessage({ type: 'progress', fraction, phase });
}

// Validates the pair (all findings in the message), then binds W, reporting progress.
function bind(name, description, mesh, cage, cageName = 'cage') {
  const report = checkPair(solver, mesh, cage);
  if (!report.ok) throw new Error(`${name} / ${cageName} cannot be used:\n${report.text}`);
  progress(0, 'computing weights');
  const next = Deformer.create(solver, mesh, cage, { onProgress: (fraction) => progress(fraction, 'computing weights') });
  deformer?.dispose();
  deformer = next;
  model = { name, mesh, cage };
  progress(1, 'done');
  return {
    name,
    description,
    // Copies: the worker keeps its own for exports.
    mesh: { positions: mesh.positions.slice(), indices: mesh.indices.slice() },
    cage: { positions: cage.positions.slice(), indices: cage.indices.slice() },
    restVolume: deformer.restVolume,
    bindMs: deformer.bindMs,
    vertexCount: deformer.vertexCount,
    check: report.text,
    exampleNames: exampleNames(solver),
    canGenerateCage: Object.keys(cageModules).length > 0,
  };
}

function frame(result) {
  return { result, positions: deformer.positions(), cage: deformer.cagePositions() };
}

function transferables(value) {
  if (!value || typeof value !== 'object') return [];
  const list = [];
  for (const key of ['positions', 'cage']) {
    if (ArrayBuffer.isView(value[key])) list.push(value[key].buffer);
  }
  for (const key of ['mesh', 'cage']) {
    const m = value[key];
    if (m && ArrayBuffer.isView(m.positions)) list.push(m.positions.buffer, m.indices.buffer);
  }
  return list;
}

self.onmessage = async (event) => {
  const { id, type, ...payload } = event.data;
  try {
    await ready;
    const handler = handlers[type];
    if (!handler) throw new Error(`unknown request '${type}'`);
    const result = await handler(payload);
    self.postMessage({ id, ok: true, result }, transferables(result));
  } catch (error) {
    self.postMessage({ id, ok: false, error: String(error?.message ?? error) });
  }
};
