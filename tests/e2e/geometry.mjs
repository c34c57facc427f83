// Geometry the browser tests compute themselves, independently of the solver they check.

/** The bar for the hard volume constraint (relative). */
export const VOLUME_TOLERANCE = 1e-6;

/** Enclosed volume 1/6 sum (a x b) . c (docs/method.md section 5) of xyz positions and triangle indices. */
export function volume(p, f) {
  let s = 0;
  for (let t = 0; t < f.length; t += 3) {
    const a = 3 * f[t];
    const b = 3 * f[t + 1];
    const c = 3 * f[t + 2];
    s += p[a] * (p[b + 1] * p[c + 2] - p[b + 2] * p[c + 1]) -
      p[a + 1] * (p[b] * p[c + 2] - p[b + 2] * p[c]) +
      p[a + 2] * (p[b] * p[c + 1] - p[b + 1] * p[c]);
  }
  return s / 6;
}

/** [lowest, highest] coordinate along `axis` (0 = x) of xyz positions. */
export function extentAlong(p, axis = 0) {
  let lo = Infinity;
  let hi = -Infinity;
  for (let i = axis; i < p.length; i += 3) {
    lo = Math.min(lo, p[i]);
    hi = Math.max(hi, p[i]);
  }
  return [lo, hi];
}

/**
 * A closed ellipsoid (radii 2, 0.6, 0.6) as OBJ text: a UV sphere with single pole vertices, faces counter-
 * clockwise seen from outside. 2 + 20 * 9 = 182 vertices: small, so the cage is quick to generate.
 */
export function ellipsoidObj(slices = 20, stacks = 10) {
  const lines = ['# ellipsoid for the browser tests'];
  const v = [[0, 0, 0.6]];
  for (let i = 1; i < stacks; ++i) {
    const theta = (Math.PI * i) / stacks;
    for (let j = 0; j < slices; ++j) {
      const phi = (2 * Math.PI * j) / slices;
      v.push([2 * Math.sin(theta) * Math.cos(phi), 0.6 * Math.sin(theta) * Math.sin(phi), 0.6 * Math.cos(theta)]);
    }
  }
  v.push([0, 0, -0.6]);
  const ring = (i, j) => 2 + (i - 1) * slices + (j % slices); // 1-based OBJ index of ring i (1..stacks-1)
  const f = [];
  for (let j = 0; j < slices; ++j) f.push([1, ring(1, j), ring(1, j + 1)]);
  for (let i = 1; i < stacks - 1; ++i) {
    for (let j = 0; j < slices; ++j) {
      f.push([ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)], [ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)]);
    }
  }
  const south = v.length;
  for (let j = 0; j < slices; ++j) f.push([south, ring(stacks - 1, j + 1), ring(stacks - 1, j)]);
  for (const p of v) lines.push(`v ${p.map((x) => x.toFixed(9)).join(' ')}`);
  for (const t of f) lines.push(`f ${t.join(' ')}`);
  return `${lines.join('\n')}\n`;
}
