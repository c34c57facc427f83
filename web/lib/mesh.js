// @ts-check
// Validated JS layer over the mesh bindings: reading, writing, checking and the built-in examples.
// A mesh on the JS side is { positions: Float64Array (xyz interleaved), indices: Uint32Array (3 per face) };
// assertMesh is the one shape check of it that every entry of the library uses before entering wasm.
import { InputError, callWasm } from './errors.js';
import { assertAttached } from './typed_arrays.js';

/** @typedef {import('./solver_module.js').SolverModule} SolverModule */
/** @typedef {{ positions: Float64Array, indices: Uint32Array }} MeshData */
/** @typedef {import('./errors.js').Finding} Finding */
/**
 * What a MeshLayout did to a mesh (cpp/core/mesh/mesh_layout.h): the file's and the solver's counts.
 * @typedef {object} LayoutStats
 * @property {number} fileVertices
 * @property {number} fileFaces
 * @property {number} solverVertices
 * @property {number} solverFaces
 * @property {number} welded file vertices merged into another at the same point
 * @property {number} unreferenced file vertices no solver face uses (carried along with the nearest triangle)
 * @property {number} collapsedFaces file faces whose corners are one point (left out of the solver)
 * @property {number} splitVertices solver vertices added by splitting non-manifold vertices and edges
 * @property {number} pairedEdges non-manifold edges split by pairing their faces
 */
/**
 * @typedef {object} MeshSummary
 * @property {number} vertices the file's
 * @property {number} faces the file's
 * @property {number} edges distinct undirected edges (of the welded mesh)
 * @property {number} components
 * @property {number} genus -1 unless manifold and one component
 * @property {number[]} bboxMin
 * @property {number[]} bboxMax
 * @property {number} volume signed; positive when outward oriented; an open mesh's with its holes capped
 * @property {number} holes boundary loops
 * @property {LayoutStats} layout
 */
/** @typedef {{ ok: boolean, summary: MeshSummary, findings: Finding[], text: string }} CheckReport */

export { MESH_EXTENSIONS } from './formats.js';

/**
 * Parses mesh file bytes (OBJ, OFF, PLY, STL; the format comes from the file name, else the content).
 * A file that cannot be parsed is an InputError with code 'parse_error' naming the file and line.
 * @param {SolverModule} solver module from loadSolver()
 * @param {Uint8Array|ArrayBuffer|string} bytes
 * @param {string} filename used for the format and in error messages
 * @returns {MeshData}
 */
export function readMesh(solver, bytes, filename) {
  assertAttached(bytes, 'readMesh: bytes');
  if (bytes instanceof ArrayBuffer) bytes = new Uint8Array(bytes);
  if (!(bytes instanceof Uint8Array) && typeof bytes !== 'string') {
    throw new InputError('readMesh: bytes must be a Uint8Array, ArrayBuffer or string');
  }
  if (typeof filename !== 'string') throw new InputError('readMesh: filename must be a string');
  // The C++ reader's messages already start with the file name.
  return callWasm(() => solver.readMesh(bytes, filename));
}

/**
 * Checks a mesh as the Deformer will take it. A mesh is checked as a model (cpp/core/mesh/mesh_check.h,
 * check_model): its split vertices welded, vertices no face uses left out, non-manifold vertices split
 * (docs/library.md, "Vertex layout"), open allowed (each hole capped for the volume); the findings then include
 * notes (severity 'note') on what that did, and summary.layout its counts. A cage is checked as it is: closed,
 * manifold, outward.
 * @param {SolverModule} solver
 * @param {MeshData} mesh
 * @param {string} [role] 'mesh' or 'cage': prefixes the findings' messages
 * @param {{ weldTolerance?: number }} [options] weldTolerance: relative to the bounding-box diagonal (default
 *   1e-6; 0: only equal positions)
 * @returns {CheckReport}
 */
export function checkMesh(solver, mesh, role = 'mesh', { weldTolerance } = {}) {
  assertMesh(mesh, role);
  if (role === 'cage') return callWasm(() => solver.checkMesh(mesh.positions, mesh.indices, role));
  return callWasm(() => solver.checkModel(mesh.positions, mesh.indices, { weldTolerance }));
}

/**
 * Checks mesh (as a model, as checkMesh) and cage, and that every mesh vertex is strictly inside the cage.
 * @param {SolverModule} solver
 * @param {MeshData} mesh
 * @param {MeshData} cage
 * @param {{ weldTolerance?: number }} [options]
 * @returns {CheckReport}
 */
export function checkPair(solver, mesh, cage, { weldTolerance } = {}) {
  assertMesh(mesh, 'mesh');
  assertMesh(cage, 'cage');
  return callWasm(() => solver.checkModelPair(mesh.positions, mesh.indices, cage.positions, cage.indices, { weldTolerance }));
}

/**
 * OBJ text of a mesh (full double precision).
 * @param {SolverModule} solver
 * @param {MeshData} mesh
 * @param {string} [comment] written as '# ' lines at the top
 * @returns {string}
 */
export function writeObj(solver, mesh, comment = '') {
  assertMesh(mesh, 'mesh');
  return callWasm(() => solver.writeObj(mesh.positions, mesh.indices, comment));
}

/**
 * Names of the built-in procedural examples, the default first.
 * @param {SolverModule} solver
 * @returns {string[]}
 */
export function exampleNames(solver) {
  return solver.exampleNames();
}

/**
 * @param {SolverModule} solver
 * @param {string} name
 * @returns {{ name: string, description: string, mesh: MeshData, cage: MeshData }}
 */
export function makeExample(solver, name) {
  if (typeof name !== 'string') throw new InputError('makeExample: name must be a string');
  return callWasm(() => solver.makeExample(name));
}

/**
 * The largest |coordinate| a mesh or cage may have (cpp/core/mesh/mesh_check.h, kMaxMeshCoordinate; beyond it
 * the check's error is coordinates_too_large): volumes are cubic and the solver squares them, so larger ones
 * overflow. Handle targets are held to it too.
 */
export const MAX_MESH_COORDINATE = 1e30;

/**
 * How a handle target beyond MAX_MESH_COORDINATE is refused, the same in a scene and in Deformer.setTargets.
 * @param {number} largest its largest |coordinate| @returns {string}
 */
export function beyondMeshCoordinates(largest) {
  return `a coordinate of ${largest.toPrecision(3)}, beyond the ${MAX_MESH_COORDINATE.toExponential().replace('+', '')} ` +
    'a mesh may have (volumes would overflow)';
}

/**
 * Throws an InputError naming the first finite value of `targets` beyond MAX_MESH_COORDINATE, as a scene refuses
 * it (else a solve overflows and ends in numerical_failure); non-finite values are left to the C++ check, which
 * names them. @param {Float64Array} targets @param {string} what the caller, e.g. 'setTargets'
 */
export function assertTargetsNear(targets, what) {
  const far = targets.findIndex((x) => Number.isFinite(x) && Math.abs(x) > MAX_MESH_COORDINATE);
  if (far < 0) return;
  throw new InputError(`${what}: target row ${Math.floor(far / 3)} has ${beyondMeshCoordinates(Math.abs(targets[far]))}: use a smaller target, or rescale the model`);
}

/** The fewest vertices the spectral basis takes (cpp/core/basis/spectral_basis.cpp: 1 to n - 5 modes). */
export const SPECTRAL_MIN_VERTICES = 6;
/** The fewest vertices an automatic volume partition takes (cpp/core/parts/auto_partition.cpp: 1 to n - 4 parts). */
export const AUTO_PARTS_MIN_VERTICES = 5;

/**
 * Throws an InputError "<what> needs a mesh of at least <least> vertices; this one has <n>" for a smaller mesh.
 * @param {MeshData} mesh checked by assertMesh @param {number} least @param {string} what
 */
export function assertMinVertices(mesh, least, what) {
  const n = mesh.positions.length / 3;
  if (n < least) throw new InputError(`${what} needs a mesh of at least ${least} vertices; this one has ${n}`);
}

/**
 * Throws an InputError naming the problem unless `positions` is a Float64Array of xyz triples.
 * @param {unknown} positions
 * @param {string} what e.g. 'mesh.positions'
 */
export function assertPositions(positions, what) {
  if (!(positions instanceof Float64Array)) throw new InputError(`${what} must be a Float64Array`);
  assertAttached(positions, what);
  if (positions.length % 3 !== 0) throw new InputError(`${what} length ${positions.length} is not a multiple of 3`);
}

/**
 * Throws an InputError naming the problem unless `mesh` has the MeshData shape with in-range indices.
 * @param {unknown} mesh
 * @param {string} [role] 'mesh' or 'cage', named in the messages
 * @param {string} [caller] the API call, prefixed to the messages (e.g. 'Deformer.create')
 * @returns {asserts mesh is MeshData}
 */
export function assertMesh(mesh, role = 'mesh', caller = '') {
  const at = caller ? `${caller}: ${role}` : role;
  if (!mesh || typeof mesh !== 'object') throw new InputError(`${at} must be { positions: Float64Array, indices: Uint32Array }`);
  const { positions, indices } = /** @type {{ positions?: unknown, indices?: unknown }} */ (mesh);
  assertPositions(positions, `${at}.positions`);
  if (!(indices instanceof Uint32Array)) throw new InputError(`${at}.indices must be a Uint32Array`);
  assertAttached(indices, `${at}.indices`);
  if (indices.length % 3 !== 0) throw new InputError(`${at}.indices length ${indices.length} is not a multiple of 3`);
  const vertexCount = /** @type {Float64Array} */ (positions).length / 3;
  for (let i = 0; i < indices.length; ++i) {
    if (indices[i] >= vertexCount) {
      throw new InputError(`${at}: face ${Math.floor(i / 3)} uses vertex ${indices[i]}, but there are only ${vertexCount} vertices`);
    }
  }
}
