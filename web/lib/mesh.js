// Validated JS layer over the mesh bindings: reading, writing, checking and the built-in examples.
// A mesh on the JS side is { positions: Float64Array (xyz interleaved), indices: Uint32Array (3 per face) }.

/** @typedef {{ positions: Float64Array, indices: Uint32Array }} MeshData */
/** @typedef {{ severity: 'error'|'warning', code: string, message: string }} Finding */
/** @typedef {{ ok: boolean, summary: object, findings: Finding[], text: string }} CheckReport */

export const MESH_EXTENSIONS = ['obj', 'off', 'ply', 'stl'];

/**
 * Parses mesh file bytes (OBJ, OFF, PLY, STL; the format comes from the file name, else the content).
 * @param {object} solver module from loadSolver()
 * @param {Uint8Array|ArrayBuffer|string} bytes
 * @param {string} filename used for the format and in error messages
 * @returns {MeshData}
 */
export function readMesh(solver, bytes, filename) {
  if (bytes instanceof ArrayBuffer) bytes = new Uint8Array(bytes);
  if (!(bytes instanceof Uint8Array) && typeof bytes !== 'string') {
    throw new TypeError('readMesh: bytes must be a Uint8Array, ArrayBuffer or string');
  }
  if (typeof filename !== 'string') throw new TypeError('readMesh: filename must be a string');
  // The C++ reader's messages already start with the file name.
  return solver.readMesh(bytes, filename);
}

/**
 * @param {MeshData} mesh
 * @returns {CheckReport}
 */
export function checkMesh(solver, mesh, role = 'mesh') {
  assertMesh(mesh, role);
  return solver.checkMesh(mesh.positions, mesh.indices, role);
}

/** Checks mesh and cage, and that every mesh vertex is strictly inside the cage. */
export function checkPair(solver, mesh, cage) {
  assertMesh(mesh, 'mesh');
  assertMesh(cage, 'cage');
  return solver.checkPair(mesh.positions, mesh.indices, cage.positions, cage.indices);
}

/** OBJ text of a mesh (full double precision). */
export function writeObj(solver, mesh, comment = '') {
  assertMesh(mesh, 'mesh');
  return solver.writeObj(mesh.positions, mesh.indices, comment);
}

/** Names of the built-in procedural examples, the default first. */
export function exampleNames(solver) {
  return solver.exampleNames();
}

/** @returns {{ name: string, description: string, mesh: MeshData, cage: MeshData }} */
export function makeExample(solver, name) {
  if (typeof name !== 'string') throw new TypeError('makeExample: name must be a string');
  return solver.makeExample(name);
}

/** Throws a TypeError naming the problem unless `mesh` has the MeshData shape with in-range indices. */
export function assertMesh(mesh, role = 'mesh') {
  if (!mesh || !(mesh.positions instanceof Float64Array)) {
    throw new TypeError(`${role}: positions must be a Float64Array`);
  }
  if (!(mesh.indices instanceof Uint32Array)) throw new TypeError(`${role}: indices must be a Uint32Array`);
  if (mesh.positions.length % 3 !== 0) throw new TypeError(`${role}: positions length is not a multiple of 3`);
  if (mesh.indices.length % 3 !== 0) throw new TypeError(`${role}: indices length is not a multiple of 3`);
  const vertexCount = mesh.positions.length / 3;
  for (let i = 0; i < mesh.indices.length; ++i) {
    if (mesh.indices[i] >= vertexCount) {
      throw new RangeError(`${role}: face ${Math.floor(i / 3)} uses vertex ${mesh.indices[i]}, but there are only ${vertexCount} vertices`);
    }
  }
}
