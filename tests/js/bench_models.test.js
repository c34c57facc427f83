// The real-model benchmark (scripts/bench/models.mjs): its drag scene, and one model run end to end in wasm when
// ../shared/data is present.
import { describe, expect, it } from 'vitest';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { loadSolver, makeExample } from 'subspace-deform';
import { availableModels, dragHandles, formatModels, runModels } from '../../scripts/bench/models.mjs';

const sharedData = new URL('../../../shared/data', import.meta.url).pathname;

describe('bench models', () => {
  it('fixes one end of the longest axis and pulls the other 8% of the diagonal sideways, turned 20 degrees', async () => {
    const solver = await loadSolver();
    const { mesh } = makeExample(solver, 'bar'); // a bar along x
    const p = mesh.positions, n = p.length / 3;
    const [fixed, moved] = dragHandles(mesh);
    expect(fixed.vertices.length).toBeGreaterThan(0);
    expect(moved.vertices.length).toBeGreaterThan(0);
    const xs = Array.from({ length: n }, (_, i) => p[3 * i]);
    const lo = Math.min(...xs), hi = Math.max(...xs);
    expect(fixed.vertices.every((i) => p[3 * i] < lo + 0.05 * (hi - lo))).toBe(true);
    expect(moved.vertices.every((i) => p[3 * i] > hi - 0.05 * (hi - lo))).toBe(true);
    const extent = [0, 1, 2].map((a) => {
      const v = Array.from({ length: n }, (_, i) => p[3 * i + a]);
      return Math.max(...v) - Math.min(...v);
    });
    expect(Math.hypot(...moved.translate)).toBeCloseTo(0.08 * Math.hypot(...extent), 10);
    expect(moved.rotate.angle).toBeCloseTo((20 * Math.PI) / 180, 12);
    expect(Math.hypot(...moved.rotate.axis)).toBe(1);
    expect(moved.rotate.axis[0]).toBe(0); // about an axis across the bar, not along it
  });

  it("gives the native reduced solve's distance from the full shape in the reduced row", () => {
    const wasm = { iterations: 3, converged: true, solveMs: 10, msPerIteration: 1, productsPerIteration: 2, passesPerIteration: 5, reliable: true };
    const nat = { iterations: 3, solveMs: 5, msPerIteration: 1 };
    const row = { name: 'x', n: 10, m: 4, wasm: { full: wasm, reduced: wasm }, native: { full: nat, reduced: nat, reducedVsFull: 2.06e-6 } };
    const [, , full, reduced] = formatModels([row]).split('\n');
    expect(reduced).toMatch(/\| reduced \|.*\| yes \| 2\.1e-6 \|$/);
    expect(full).toMatch(/\| full \|/);
    expect(full.endsWith('|  |  |')).toBe(true); // no rule and no distance for full integration
  });

  it('finds no model where there is no data', () => {
    expect(availableModels('/nonexistent')).toEqual([]);
  });

  it.skipIf(!existsSync(join(sharedData, 'gargoyle.obj')))(
    'runs the gargoyle in its cage with full and reduced integration (skipped without ../shared/data)', async () => {
      const solver = await loadSolver();
      const rows = await runModels({ solver, nativeBin: null, dataDir: sharedData, names: ['gargoyle'], log: () => {} });
      expect(rows).toHaveLength(1);
      const { wasm } = rows[0];
      expect(wasm.full.converged).toBe(true);
      expect(wasm.full.productsPerIteration).toBeGreaterThan(0);
      expect(wasm.reduced.iterations).toBeGreaterThan(0);
      expect(formatModels(rows)).toMatch(/\| gargoyle \| 2674 x - \| full \| \d+, yes/);
    }, 120000);
});
