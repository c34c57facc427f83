// Mesh vertices that no face uses and that lie outside the cage. The layout carries such a vertex along with its
// nearest triangle, so the pair check (check, deform) does not test it against the cage and deform moves it
// fine; but `weights` gives every vertex of the file a row of W, and cage coordinates exist only strictly
// inside the cage, so the binding refuses it. `weights` names these vertices plainly (binding them with the
// coordinates it was asked for), and `check` warns (with mean value coordinates, weights' default: check has no
// --coordinates, and another type may judge a point near the cage otherwise).
import { computeWeights } from 'subspace-deform';

// Rows probed per binding: W of a block stays small (256 x m float32) whatever the number of unused vertices.
const BLOCK = 256;
// The binding's message: "...: N of M mesh vertices are outside the cage (first: a, b, ...)" in block rows. It is
// the C++'s wording: where it does not read so, the vertices are reported without a count (never an error).
const OUTSIDE = /: (\d+) of \d+ mesh vertices (?:is|are) outside the cage \(first: ([\d, ]+)/;
const LISTED = 8;

/**
 * The unused vertices outside the cage: how many and the first few (file numbers); null when there are none;
 * count null (and no first ones) when the binding's message did not say which. The pair must have passed
 * checkPair (a valid cage), and only the unused vertices are bound, with the coordinates `choice` names.
 * @param {import('subspace-deform').SolverModule} solver
 * @param {import('subspace-deform').MeshData} mesh
 * @param {import('subspace-deform').MeshData} cage
 * @param {import('subspace-deform').CoordinatesChoice} [choice] weights' --coordinates (default: mean value)
 * @returns {{ count: number|null, first: number[] }|null}
 */
export function unusedOutside(solver, mesh, cage, choice = {}) {
  const unused = unusedVertices(mesh);
  let count = 0;
  const first = [];
  for (let b = 0; b < unused.length; b += BLOCK) {
    const block = unused.slice(b, b + BLOCK);
    const outside = outsideOf(solver, blockPositions(mesh.positions, block), cage, choice);
    if (!outside) continue;
    if (outside.count === null) return { count: null, first: [] };
    count += outside.count;
    first.push(...outside.rows.map((row) => block[row]).slice(0, LISTED - first.length));
  }
  return count ? { count, first } : null;
}

/**
 * "N vertices used by no face are outside the cage (first: ...)".
 * @param {{ count: number|null, first: number[] }} found
 */
export function unusedOutsideText({ count, first }) {
  if (count === null) return 'vertices used by no face are outside the cage';
  const which = count === 1 ? '1 vertex used by no face is' : `${count} vertices used by no face are`;
  return `${which} outside the cage (first: ${first.join(', ')}${count > first.length ? ', ...' : ''})`;
}

/** @param {import('subspace-deform').MeshData} mesh @returns {number[]} the vertices no triangle lists */
function unusedVertices(mesh) {
  const used = new Uint8Array(mesh.positions.length / 3);
  for (const v of mesh.indices) used[v] = 1;
  const unused = [];
  for (let v = 0; v < used.length; ++v) if (!used[v]) unused.push(v);
  return unused;
}

/** @param {Float64Array} positions @param {number[]} vertices */
function blockPositions(positions, vertices) {
  const out = new Float64Array(3 * vertices.length);
  vertices.forEach((v, k) => out.set(positions.subarray(3 * v, 3 * v + 3), 3 * k));
  return out;
}

// The binding of the points: null when it succeeds, else how many rows are outside and the first ones it names
// (count null: the message did not say).
function outsideOf(solver, positions, cage, choice) {
  try {
    computeWeights(solver, { positions }, cage, { ...choice, float32: true });
    return null;
  } catch (error) {
    if (error?.code !== 'mesh_outside_cage') throw error;
    return outsideRows(error.message);
  }
}

/** @param {string} message a mesh_outside_cage message @returns {{ count: number|null, rows: number[] }} */
export function outsideRows(message) {
  const match = OUTSIDE.exec(message);
  return match ? { count: Number(match[1]), rows: match[2].split(', ').map(Number) } : { count: null, rows: [] };
}
