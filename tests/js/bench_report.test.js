// scripts/bench/report.mjs: the goals are stated at n ~ 50k; one stated at that size is not judged from a case
// far from it.
import { describe, expect, it } from 'vitest';
import { evaluateGoals } from '../../scripts/bench/report.mjs';

const at = (n) => ({ n, m: 100, cageFaces: 196, passMs: 1, productMs: 2, products: 10, solveConverged: 1, solveIterations: 3,
  solveMs: 20, stepMs: 4, stepProducts: 2, bindMs: 10, bindEvalsPerSec: 5e7, ratios: {} });
const stepGoal = (cases) => evaluateGoals(cases).find((g) => g.goal.startsWith('stepMs'));

describe('bench goals', () => {
  it('says the n = 50k step goal is not measured when no case is near 50k', () => {
    const goal = stepGoal([at(5000)]);
    expect(goal.met).toBeNull();
    expect(goal.detail).toMatch(/^not measured: no case near n = 50k \(the goals are judged at n = 5000 instead; add --cases 50000:74\)/);
    // It names the case the goals are judged at, which need not be the largest (it said 'the largest has n = 30000').
    expect(stepGoal([{ ...at(30000), float32: true }, at(20000)]).detail).toMatch(/judged at n = 20000 instead/);
  });

  it('judges it on a case near 50k', () => {
    expect(stepGoal([at(5000), at(50000)])).toMatchObject({ met: true, detail: expect.stringMatching(/at n = 50000/) });
    expect(stepGoal([{ ...at(51000), stepMs: 17 }]).met).toBe(false);
  });
});
