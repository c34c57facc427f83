// Text of the numbers the app shows: each view's stats line, the fps line and the panel's stats folder.
// Input: the stats object of the scripting API (DeformerApp.viewStats, docs/embed.md).

const STATE_LABELS = { converged: 'converged', solving: 'solving\u2026', stopped: 'stopped', error: 'error', idle: 'no handles' };

/** The reason shown after the state, for states that end a solve without converging. */
function reasonOf(stats) {
  return stats.state === 'stopped' || stats.state === 'error' ? stats.stopReason : '';
}

/**
 * A view's stats line: the numbers (two lines), the state word (styled by its state) and the reason.
 * @param {object} stats
 * @param {{ loaded: boolean, requestSize: number }} context requestSize: iterations per step request
 * @returns {{ numbers: string, state: string, label: string, reason: string }}
 */
export function statsLine(stats, { loaded, requestSize }) {
  const numbers = stats.iterations
    ? `merit ${stats.merit.toExponential(3)}   volume change ${(100 * stats.volumeRelError).toFixed(6)}%\n` +
      `iterations ${stats.iterations}   ${stats.msPerIteration.toFixed(1)} ms/iteration   k=${requestSize}/request`
    : loaded ? `${stats.vertexCount} vertices, bind ${stats.bindMs.toFixed(0)} ms` : 'loading\u2026';
  const reason = reasonOf(stats);
  return { numbers, state: stats.state, label: STATE_LABELS[stats.state] ?? stats.state, reason: reason ? `: ${reason}` : '' };
}

/** The line at the bottom right: animation frames and redraws per second. */
export function fpsLine(fps, renderFps) {
  return `${fps.toFixed(0)} fps \u00b7 ${renderFps.toFixed(0)} redraws/s`;
}

/** The panel's stats folder, one string per row. */
export function panelStats(stats) {
  const reason = reasonOf(stats);
  return {
    status: reason ? `${stats.state}: ${reason}` : stats.state,
    merit: stats.merit.toExponential(3),
    volume: `${(100 * stats.volumeRelError).toFixed(6)} %`,
    iterations: String(stats.iterations),
    msPerIteration: stats.msPerIteration.toFixed(2),
    fps: stats.fps.toFixed(0),
  };
}
