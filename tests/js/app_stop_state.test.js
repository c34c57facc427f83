// The app's word for how a solve ended (issue 31, item 4: "ARAP says converged when it stopped at the iteration
// limit of the call"): a view's session against a stand-in worker whose every step ends at the iteration limit
// of the call, as ARAP's do until its stopping rule fires. Reaching the cap must read "stopped: not converged
// after N iterations" in the stats line and the panel, never "converged"; only a converged stop code does.
import { describe, expect, it } from 'vitest';
import { Session } from '../../web/app/session.js';
import { panelStats, statsLine } from '../../web/app/stats_format.js';

/** A worker that answers each step with `k` iterations and `stop` (converging on the `convergeAt`-th one). */
function standInWorker({ convergeAt = Infinity } = {}) {
  let iteration = 0;
  return {
    request(type, payload) {
      if (type !== 'step') return Promise.resolve({});
      const iterations = [];
      let stop = 'iteration_limit';
      for (let i = 0; i < payload.iterations; ++i) {
        iteration++;
        iterations.push({ iteration, merit: 1 / iteration, energy: 1 / iteration, volumeRelError: 0.01, ms: 1 });
        if (iteration >= convergeAt) { stop = 'arap_energy'; break; }
      }
      const converged = stop === 'arap_energy';
      const stopReason = converged ? 'converged: ARAP energy stopped decreasing' : 'iteration limit of this call';
      return Promise.resolve({ result: { iterations, converged, stop, stopReason } });
    },
    terminate() {},
  };
}

/** Runs an ARAP session with the cap `maxIterations` until it settles; its stats as the app shows them. */
async function settle(worker, maxIterations) {
  const session = new Session({ method: 'arap', onFrame() {}, onError(error) { throw error; } });
  session.adopt(worker, { mesh: { positions: new Float64Array(9), indices: new Uint32Array([0, 1, 2]) } });
  session.applySettings({ options: {}, maxIterations, iterationsPerStep: 3, dragIntegration: 'auto' });
  session.setHandles([[0]], new Float64Array(3));
  const settled = session.settled();
  for (let frame = 0; frame < 100 && session.state === 'solving'; ++frame) {
    session.pump();
    await new Promise((resolve) => setTimeout(resolve, 0));
  }
  await settled;
  const last = session.last;
  const stats = { state: session.state, stopReason: session.stopReason, merit: last.merit, energy: last.energy,
    volumeRelError: last.volumeRelError, iterations: session.totalIterations, msPerIteration: 1, fps: 60 };
  return { stats, line: statsLine(stats, { loaded: true, requestSize: 3 }), panel: panelStats(stats) };
}

describe('how a solve ended, in the stats', () => {
  it('an ARAP solve at its iteration cap is "stopped: not converged after N iterations"', async () => {
    const { stats, line, panel } = await settle(standInWorker(), 7);
    expect(stats).toMatchObject({ state: 'stopped', stopReason: 'not converged after 7 iterations', iterations: 7 });
    expect(line).toMatchObject({ label: 'stopped', reason: ': not converged after 7 iterations' });
    expect(panel.status).toBe('stopped: not converged after 7 iterations');
    expect(`${line.numbers}${line.label}${panel.status}`).not.toMatch(/converged(?! after)/);
  });

  it('one whose stopping rule fires says converged', async () => {
    const { stats, line, panel } = await settle(standInWorker({ convergeAt: 5 }), 100);
    expect(stats).toMatchObject({ state: 'converged', iterations: 5 });
    expect(line).toMatchObject({ label: 'converged', reason: '' });
    expect(panel.status).toBe('converged');
  });
});
