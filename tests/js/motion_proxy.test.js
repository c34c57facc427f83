// The motion proxy (web/app/view/motion_proxy.js): a coarse stand-in for large meshes on software renderers.
// Checked on the built-in examples: it only references the mesh's own vertices, lands near its triangle
// target, has no degenerate or repeated triangles, keeps the orientation (each directed edge at most once,
// positive volume) and stays close to the shape (volume and area within a few percent, every proxy vertex on
// the mesh by construction, every mesh vertex near a proxy vertex).
import { beforeAll, describe, expect, it } from 'vitest';
import { loadNodeSolver } from '../../web/lib/node.js';
import { makeExample } from '../../web/lib/mesh.js';
import { PROXY_MIN_TRIANGLES, PROXY_TARGET_TRIANGLES, proxyIndices } from '../../web/app/view/motion_proxy.js';
import { volume } from '../e2e/geometry.mjs';
import { Timer } from '../../scripts/lib/timer.mjs';

let solver;
beforeAll(async () => {
  solver = await loadNodeSolver();
});

function area(P, F) {
  let s = 0;
  for (let f = 0; f < F.length; f += 3) {
    const [i, j, k] = [3 * F[f], 3 * F[f + 1], 3 * F[f + 2]];
    const u = [0, 1, 2].map((a) => P[j + a] - P[i + a]), v = [0, 1, 2].map((a) => P[k + a] - P[i + a]);
    s += 0.5 * Math.hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
  }
  return s;
}

describe('motion proxy', () => {
  it('is not made for meshes of up to PROXY_MIN_TRIANGLES triangles, whatever the target', () => {
    for (const name of ['bar', 'sphere']) {
      const { mesh } = makeExample(solver, name);
      expect(mesh.indices.length / 3).toBeLessThanOrEqual(PROXY_MIN_TRIANGLES);
      expect(proxyIndices(mesh.positions, mesh.indices)).toBeNull();
      expect(proxyIndices(mesh.positions, mesh.indices, 1000)).toBeNull();
    }
  });

  it('is a coarse, consistently oriented surface close to bar-fine, on its own vertices', () => {
    const { mesh } = makeExample(solver, 'bar-fine');
    const P = mesh.positions, F = mesh.indices, n = P.length / 3;
    const timer = new Timer();
    const proxy = proxyIndices(P, F);
    const ms = timer.ms();
    const triangles = proxy.length / 3;
    // Near the target (the clustering corrects its cell size until within -30% / +40%).
    expect(triangles).toBeGreaterThan(0.7 * PROXY_TARGET_TRIANGLES);
    expect(triangles).toBeLessThan(1.4 * PROXY_TARGET_TRIANGLES);
    const directed = new Set();
    const used = new Set();
    for (let t = 0; t < proxy.length; t += 3) {
      const tri = [proxy[t], proxy[t + 1], proxy[t + 2]];
      for (const v of tri) {
        expect(v).toBeLessThan(n);
        used.add(v);
      }
      expect(new Set(tri).size).toBe(3);
      for (let e = 0; e < 3; ++e) {
        const key = `${tri[e]}>${tri[(e + 1) % 3]}`;
        expect(directed.has(key)).toBe(false); // the same directed edge twice: a flipped or repeated triangle
        directed.add(key);
      }
    }
    // Shape: volume and area within 5% of the full mesh's (it is drawn in motion, at half resolution).
    expect(Math.abs(volume(P, proxy) / volume(P, F) - 1)).toBeLessThan(0.05);
    expect(Math.abs(area(P, proxy) / area(P, F) - 1)).toBeLessThan(0.05);
    // Every mesh vertex is within two cell sizes of some proxy vertex (no large part missing).
    const cell = Math.sqrt(area(P, F) / (PROXY_TARGET_TRIANGLES / 2));
    const reps = [...used];
    for (let i = 0; i < n; i += 97) {
      let nearest = Infinity;
      for (const r of reps) nearest = Math.min(nearest, Math.hypot(P[3 * i] - P[3 * r], P[3 * i + 1] - P[3 * r + 1], P[3 * i + 2] - P[3 * r + 2]));
      expect(nearest).toBeLessThan(2 * cell);
    }
    console.log(`bar-fine proxy: ${F.length / 3} -> ${triangles} triangles, ${used.size} vertices, ${ms.toFixed(0)} ms`);
  });
});
