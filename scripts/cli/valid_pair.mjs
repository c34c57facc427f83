// The mesh and cage checks `weights` runs before binding. The binding computes W for any cage it is given,
// but on an open cage, or one with a stray far vertex, mean value coordinates no longer reproduce the mesh
// (W * cage != mesh) and nothing says so: the pair is checked as `check` and `deform` check it, and
// refused with every error finding, each naming the file it is about. A vertex no face uses passes the check
// (the layout carries it along) but still gets a row of W: one outside the cage is refused by name.
import { MeshError, checkPair } from 'subspace-deform';
import { unusedOutside, unusedOutsideText } from './unused_outside.mjs';
import { withCageSeamAdvice } from './cage_seams.mjs';

// Findings that mean "a vertex is not strictly inside", which computeWeights reports as mesh_outside_cage.
const OUTSIDE_CODES = new Set(['outside_cage', 'on_cage']);

/**
 * Throws a MeshError (code mesh_outside_cage when every error is about vertices not strictly inside the cage,
 * invalid_mesh otherwise) unless checkPair finds the pair valid.
 * @param {import('subspace-deform').SolverModule} solver
 * @param {{ mesh: import('subspace-deform').MeshData, name: string }} mesh
 * @param {{ mesh: import('subspace-deform').MeshData, name: string }} cage
 * @param {import('subspace-deform').CoordinatesChoice} [choice] the coordinates W will have (the unused vertices
 *   are bound with them)
 */
export function requireValidPair(solver, mesh, cage, choice = {}) {
  const report = checkPair(solver, mesh.mesh, cage.mesh);
  if (report.ok) {
    requireUnusedInside(solver, mesh, cage, choice);
    return;
  }
  const names = { mesh: mesh.name, cage: cage.name };
  const findings = withCageSeamAdvice(cage.mesh, report.findings);
  const errors = findings.filter((f) => f.severity === 'error');
  // "mesh: ..." / "cage: ..." become "mesh m.obj: ...": the command was given two files.
  const text = errors.map((f) => `error: ${f.message.replace(/^(mesh|cage): /, (_, role) => `${role} ${names[role]}: `)}\n`).join('');
  const code = errors.every((f) => OUTSIDE_CODES.has(f.code)) ? 'mesh_outside_cage' : 'invalid_mesh';
  throw new MeshError(text, { code, findings });
}

// The check's layout carries a vertex no face uses, so it did not test it; W has its row all the same.
function requireUnusedInside(solver, mesh, cage, choice) {
  const found = unusedOutside(solver, mesh.mesh, cage.mesh, choice);
  if (!found) return;
  const message = `mesh ${mesh.name}: ${unusedOutsideText(found)}: W has a row for every vertex of the file, and ` +
    'cage coordinates exist only strictly inside the cage (deform carries such a vertex along with its nearest ' +
    'triangle instead); remove the unused vertices from the file or enlarge the cage';
  throw new MeshError(`error: ${message}\n`, { code: 'mesh_outside_cage',
    findings: [{ severity: 'error', code: 'unused_outside_cage', message }] });
}
