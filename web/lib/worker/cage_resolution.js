// @ts-check
// The one decision every load of the solver worker makes (loadExample, loadFiles, loadMeshes; protocol.js): which
// cage the model binds with. The cage given (a cage file, the example's own, the page's), unless a generated one
// replaces it; without one, none for the spectral basis (subspace.js), a generated one when asked, or a refusal
// that says how to get one. Cages are generated here, in the worker, reporting progress.
import { generateCage } from '../cage.js';
import { InputError, MeshError } from '../errors.js';
import { checkMesh } from '../mesh.js';
import { isSpectral } from '../subspace.js';

/** @typedef {import('../mesh.js').MeshData} MeshData */
/** @typedef {(fraction: number, phase: string) => void} PostProgress posts a Progress message (protocol.js) */
/**
 * What a load binds: the cage (null: none, the spectral basis), its name in messages, the model's description,
 * and the generated cage's result (its statistics go into the Model) when it was generated here.
 * @typedef {{ cage: MeshData|null, cageName: string, description: string,
 *             generated: import('../cage.js').CageResult|null }} ResolvedCage
 */

/**
 * A progress callback that posts at most one message per percent (the cage generator calls back thousands of
 * times).
 * @param {PostProgress} post
 * @param {string} [phase]
 * @returns {(fraction: number) => void}
 */
export function cageProgress(post, phase = 'generating the cage') {
  let shown = -1;
  post(0, phase);
  return (fraction) => {
    const percent = Math.floor(100 * fraction);
    if (percent !== shown) {
      shown = percent;
      post(fraction, phase);
    }
  };
}

/**
 * Generates a cage for `mesh`, reporting progress. The mesh is checked first, so an open or broken mesh gets the
 * checker's findings rather than a generator error.
 * @param {import('../solver_module.js').SolverModule} solver
 * @param {PostProgress} post
 * @param {MeshData} mesh
 * @param {{ vertices?: number }} options
 * @param {string} name the model's, for messages
 */
function makeCage(solver, post, mesh, { vertices = 120 }, name) {
  const report = checkMesh(solver, mesh, 'mesh');
  if (!report.ok) throw new MeshError(`${name} cannot get a cage:\n${report.text}`, { findings: report.findings });
  return generateCage(solver, mesh, { vertices, onProgress: cageProgress(post, `generating a ${vertices}-vertex cage`) });
}

/**
 * A lone mesh with neither a cage to make nor the spectral basis: a MeshError with the findings when no cage could
 * help it until it is fixed, else an InputError with code 'no_cage' (what the app answers with its offers).
 * @param {import('../solver_module.js').SolverModule} solver
 * @param {MeshData} mesh
 * @param {string} name
 * @returns {never}
 */
function refuseWithoutCage(solver, mesh, name) {
  const report = checkMesh(solver, mesh, 'mesh');
  if (!report.ok) {
    throw new MeshError(`${name} has no cage, and it cannot get a generated one until these are fixed:\n${report.text}`,
      { findings: report.findings });
  }
  throw new InputError(`${name} has no cage. Drop the mesh together with its cage (two files), or use "Generate cage".`,
    { code: 'no_cage' });
}

/**
 * The cage a load binds with, in this order: a generated one when asked and either `regenerate` (it replaces the
 * given one: an example with generateCage) or there is neither a cage given nor the spectral basis; the cage given;
 * none with the spectral basis; else a refusal (refuseWithoutCage).
 * @param {{ solver: import('../solver_module.js').SolverModule, post: PostProgress }} worker
 * @param {{ name: string, mesh: MeshData, given: { cage: MeshData, cageName: string, description: string }|null,
 *           generate?: { vertices: number }|null, regenerate?: boolean, subspace?: import('../subspace.js').Subspace|null,
 *           description?: string }} load description: what the page calls the model, for a mesh bound without a cage
 * @returns {ResolvedCage}
 */
export function resolveCage({ solver, post }, { name, mesh, given, generate = null, regenerate = false, subspace = null, description }) {
  if (generate && (regenerate || (!given && !isSpectral(subspace)))) {
    const cage = makeCage(solver, post, mesh, generate, name);
    return { cage, cageName: 'generated cage', description: `${name} in a generated ${cage.positions.length / 3}-vertex cage`, generated: cage };
  }
  if (given) return { cage: given.cage, cageName: given.cageName, description: given.description, generated: null };
  if (isSpectral(subspace)) {
    return { cage: null, cageName: 'no cage', description: description ?? `${name} in its spectral basis (${subspace.modes} modes)`, generated: null };
  }
  return refuseWithoutCage(solver, mesh, name);
}
