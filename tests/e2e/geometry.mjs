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
