// A cage split at seams. glTF exporters write a flat-shaded box with each face's own corners (24 vertices, 6
// separate quads), and a cage is taken as given, not welded (its vertices are W's columns): the check then calls
// it open, and adds the mesh's wording for several components, "each is deformed with the same cage", which
// means nothing for a cage. When cage vertices share points, that warning becomes the advice to weld the cage.
import { MeshError } from 'subspace-deform';

/**
 * The findings of a pair (or cage) check with a cage split at seams explained: the cage's components warning
 * replaced by an error, cage_split_vertices, saying to weld it. Unchanged when no two cage vertices share a point.
 * @param {import('subspace-deform').MeshData} cage
 * @param {import('subspace-deform').Finding[]} findings
 * @returns {import('subspace-deform').Finding[]}
 */
export function withCageSeamAdvice(cage, findings) {
  const shared = sharedPoints(cage.positions);
  if (!shared || findings.every((f) => f.severity !== 'error' || !f.message.startsWith('cage: '))) return findings;
  const advice = { severity: 'error', code: 'cage_split_vertices', message: `cage: ${shared} of its vertices are at the ` +
    'same point as another (split at seams, as glTF exporters write flat-shaded faces), so its faces do not join: a ' +
    'cage is taken as given; weld it (merge vertices by distance in the modeller) or export it as OBJ' };
  const kept = findings.filter((f) => !(f.code === 'components' && f.message.startsWith('cage: ')));
  return [...kept.filter((f) => f.severity === 'error'), advice, ...kept.filter((f) => f.severity !== 'error')];
}

/**
 * A MeshError from Deformer.create with the same advice (its message rebuilt from the findings, one
 * "severity: message" line each, as the core writes them); any other error unchanged.
 * @param {unknown} error
 * @param {import('subspace-deform').MeshData|null} cage
 */
export function cageSeamError(error, cage) {
  if (!(error instanceof MeshError) || !cage || !error.findings?.length) return error;
  const findings = withCageSeamAdvice(cage, error.findings);
  if (findings === error.findings) return error;
  return new MeshError(findings.map((f) => `${f.severity}: ${f.message}\n`).join(''), { code: error.code, findings });
}

/** How many vertices are at exactly the point of an earlier one. @param {Float64Array} positions */
function sharedPoints(positions) {
  const points = new Set();
  for (let v = 0; v < positions.length; v += 3) points.add(`${positions[v]} ${positions[v + 1]} ${positions[v + 2]}`);
  return positions.length / 3 - points.size;
}
