// The built-in bar's two end caps as handle groups, and targets that keep the left end and move the right.
export function barEnds(mesh) {
  const left = [], right = [];
  for (let i = 0; i < mesh.positions.length / 3; ++i) {
    if (mesh.positions[3 * i] < -2.2) left.push(i);
    if (mesh.positions[3 * i] > 2.2) right.push(i);
  }
  return { left, right };
}

// Rest positions of the groups' vertices, groups in order, the last group moved by `move`.
export function endTargets(mesh, groups, move = [0, 0, 0]) {
  const targets = new Float64Array(3 * groups.flat().length);
  let row = 0;
  groups.forEach((group, g) => {
    for (const v of group) {
      for (let a = 0; a < 3; ++a) targets[3 * row + a] = mesh.positions[3 * v + a] + (g === groups.length - 1 ? move[a] : 0);
      ++row;
    }
  });
  return targets;
}
