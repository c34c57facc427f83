// Mesh vertices that no face uses and that lie outside the cage. The layout carries such a vertex along with its
// nearest triangle, so the pair check (check, deform) does not test it against the cage and deform moves it
// fine; but `weights` gives every vertex of the file a row of W, and cage coordinates exist only strictly
// inside the cage, so the binding refuses it. `weights` names these vertices plainly, and `check` warns.
import { computeWeights } from 'subspace-deform';

// Rows probed per binding: W of a block stays small (256 x m float32) whatever the number of unused vertices.
const BLOCK = 256;
// The binding's message: "...: N of M mesh vertices are outside the cage (first: a, b, ...)" in block rows.
const OUTSIDE = /: (\d+) of \d+ mesh vertices (?:is|are) outside the cage \(first: ([\d, ]+)/;
const LISTED = 8;

/**
 * The unused vertices outside the cage: how many and the first few (file numbers); null when there are none.
 * The pair must have passed checkPair (a valid cage), and only the unused vertices are bound, with the same
 * binding `weights` runs, so the two cannot disagree.
 * @param {import('subspace-deform').SolverModule} solver
 * @param {import('subspace-deform').MeshData} mesh
 * @param {import('subspace-deform').MeshData} cage
 * @returns {{ count: number, first: number[] }|null}
 */
export function unusedOutside(solver, mesh, cage) {
  const unused = unusedVertices(mesh);
  let count = 0;
  const first = [];
  for (let b = 0; b < unused.length; b += BLOCK) {
    const block = unused.slice(b, b + BLOCK);
    const outside = outsideOf(solver, blockPositions(mesh.positions, block), cage);
    if (!outside) continue;
    count += outside.count;
    first.push(...outside.rows.map((row) => block[row]).slice(0, LISTED - first.length));
  }
  return count ? { count, first } : null;
}

/**
 * "N vertices used by no face are outside the cage (first: ...)".
 * @param {{ count: number, first: number[] }} found
 */
export function unusedOutsideText({ count, first }) {
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

// The binding of the points: null when it succeeds, else how many rows are outside and the first ones it names.
function outsideOf(solver, positions, cage) {
  try {
    computeWeights(solver, { positions }, cage, { float32: true });
    return null;
  } catch (error) {
    const match = error?.code === 'mesh_outside_cage' ? OUTSIDE.exec(error.message) : null;
    if (!match) throw error;
    return { count: Number(match[1]), rows: match[2].split(', ').map(Number) };
  }
}
