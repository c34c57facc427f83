// Formatting and goal checks for scripts/bench.mjs. Goals (docs/benchmarks.md), all in wasm at n ~ 50k:
// product <= 1.5x the floor (two y = W p passes; also reported against W's bytes over the read bandwidth),
// converged bend in <= 25 products, interactive step
// <= 16 ms, wasm <= 1.3x native, binding >= 20M point-triangle evaluations per second.

const fmt = (x, digits = 1) => (Number.isFinite(x) ? x.toFixed(digits) : '-');

/** Markdown table of the cases (wasm numbers, native in parentheses where measured). */
export function formatTable(cases) {
  const head = ['n', 'm', 'W', 'W MB', 'bind ms wasm (native)', 'M evals/s wasm', 'passMs wasm (native)',
    'productMs wasm (native)', 'product / floor', 'stepMs wasm (native)', 'solveMs wasm (native)', 'products (its)',
    'exact it ms', 'full it ms', 'ARAP it ms'];
  const rows = cases.map((c) => {
    const nat = c.native ?? {};
    const pair = (key, d = 1) => `${fmt(c[key], d)} (${fmt(nat[key], d)})`;
    return [c.n, c.m, c.float32 ? 'f32' : 'f64', fmt(c.wBytes / 1e6, 0), pair('bindMs', 0), fmt(c.bindEvalsPerSec / 1e6, 1), pair('passMs', 2),
      pair('productMs', 2), fmt(c.ratios.productOverFloor, 2) + 'x', `${pair('stepMs', 1)} [${c.stepPasses ?? '?'} passes]`, pair('solveMs', 0),
      `${c.products} (${c.solveIterations})`, fmt(c.exactIterationMs, 0), fmt(c.fullIterationMs, 0),
      fmt(c.arapIterationMs, 1)];
  });
  return [head, head.map(() => '---'), ...rows].map((r) => `| ${r.join(' | ')} |`).join('\n');
}

/** The float64 case closest to n = 50k with n >= 40k, else the largest. */
export function goalCase(cases) {
  const f64 = cases.filter((c) => !c.float32);
  if (f64.length) cases = f64;
  const big = cases.filter((c) => c.n >= 40000);
  const pool = big.length ? big : cases;
  return pool.reduce((best, c) => (Math.abs(c.n - 50000) < Math.abs(best.n - 50000) ? c : best), pool[0]);
}

/** [{ goal, met: true|false|null, detail, ratio }] for the case nearest n = 50k. */
export function evaluateGoals(cases) {
  if (cases.length === 0) return [];
  const c = goalCase(cases);
  const at = `at n = ${c.n}, m = ${c.m}`;
  const goals = [];
  const floor = 2 * c.passMs;
  goals.push({
    goal: 'productMs <= 1.5 x floor (2 x passMs)',
    met: c.productMs <= 1.5 * floor,
    ratio: c.productMs / floor,
    detail: `${fmt(c.productMs, 2)} ms vs floor ${fmt(floor, 2)} ms = ${fmt(c.productMs / floor, 2)}x ${at}`,
  });
  if (c.idealPassMs) {
    // The same against W's bytes over the measured read bandwidth: what a memory-bound kernel would reach.
    const ideal = 2 * c.idealPassMs;
    goals.push({
      goal: 'productMs <= 1.5 x bandwidth floor (W bytes / read bandwidth, twice)',
      met: c.productMs <= 1.5 * ideal,
      ratio: c.productMs / ideal,
      detail: `${fmt(c.productMs, 2)} ms vs ${fmt(ideal, 2)} ms = ${fmt(c.productMs / ideal, 2)}x ${at}`,
    });
  }
  goals.push({
    goal: 'converged fast bend in <= 25 products',
    met: c.products <= 25 && c.solveConverged === 1,
    ratio: c.products / 25,
    detail: `${c.products} products in ${c.solveIterations} iterations (${c.solveConverged ? 'converged' : 'not converged'}), ${fmt(c.solveMs, 0)} ms ${at}`,
  });
  // This goal names its size: judged from a 5k case (--cases without a 50k one) it read as met when it was not
  // measured at all, so a case outside 40k-60k leaves it unjudged.
  if (c.n >= 40000 && c.n <= 60000) {
    goals.push({
      goal: 'stepMs <= 16 at n = 50k',
      met: c.stepMs <= 16,
      ratio: c.stepMs / 16,
      detail: `${fmt(c.stepMs, 1)} ms (${c.stepProducts} products) ${at}`,
    });
  } else {
    goals.push({
      goal: 'stepMs <= 16 at n = 50k', met: null,
      detail: `not measured: no case near n = 50k (the goals are judged at n = ${c.n} instead; add --cases 50000:74)`,
    });
  }
  if (c.native) {
    const keys = ['bindMs', 'productMs', 'stepMs', 'solveMs'];
    const parts = keys.map((k) => `${k} ${fmt(c[k] / c.native[k], 2)}x`);
    const worst = Math.max(...keys.map((k) => c[k] / c.native[k]));
    goals.push({ goal: 'wasm <= 1.3 x native', met: worst <= 1.3, ratio: worst / 1.3, detail: `${parts.join(', ')} ${at}` });
  } else {
    goals.push({ goal: 'wasm <= 1.3 x native', met: null, detail: 'no native run' });
  }
  goals.push({
    goal: 'bind >= 20M point-triangle evaluations/s in wasm',
    met: c.bindEvalsPerSec >= 20e6,
    ratio: 20e6 / c.bindEvalsPerSec,
    detail: `${fmt(c.bindEvalsPerSec / 1e6, 1)}M/s (${fmt(c.bindMs, 0)} ms for ${c.n} x ${c.cageFaces} evaluations) ${at}`,
  });
  return goals;
}
