// The mesh and cage checks `weights` runs before binding. The binding computes W for any cage it is given,
// but on an open cage, or one with a stray far vertex, mean value coordinates no longer reproduce the mesh
// (W * cage != mesh) and nothing says so: the pair is checked as `check` and `deform` check it, and
// refused with every error finding, each naming the file it is about.
import { MeshError, checkPair } from 'subspace-deform';

// Findings that mean "a vertex is not strictly inside", which computeWeights reports as mesh_outside_cage.
const OUTSIDE_CODES = new Set(['outside_cage', 'on_cage']);

/**
 * Throws a MeshError (code mesh_outside_cage when every error is about vertices not strictly inside the cage,
 * invalid_mesh otherwise) unless checkPair finds the pair valid.
 * @param {import('subspace-deform').SolverModule} solver
 * @param {{ mesh: import('subspace-deform').MeshData, name: string }} mesh
 * @param {{ mesh: import('subspace-deform').MeshData, name: string }} cage
 */
export function requireValidPair(solver, mesh, cage) {
  const report = checkPair(solver, mesh.mesh, cage.mesh);
  if (report.ok) return;
  const names = { mesh: mesh.name, cage: cage.name };
  const errors = report.findings.filter((f) => f.severity === 'error');
  // "mesh: ..." / "cage: ..." become "mesh m.obj: ...": the command was given two files.
  const text = errors.map((f) => `error: ${f.message.replace(/^(mesh|cage): /, (_, role) => `${role} ${names[role]}: `)}\n`).join('');
  const code = errors.every((f) => OUTSIDE_CODES.has(f.code)) ? 'mesh_outside_cage' : 'invalid_mesh';
  throw new MeshError(text, { code, findings: report.findings });
}
