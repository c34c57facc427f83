// The session's state machine (web/app/session_state.js, issue 33 item 2): its table checked cell by cell against
// the rules it is meant to follow, what is ignored and what is refused, when the session counts as settled, and
// a Session against a stand-in worker going through the phases the way the app drives it.
import { describe, expect, it } from 'vitest';
import { EVENTS, PHASES, PHASE_TABLE, SessionState, nextPhase } from '../../web/app/session_state.js';
import { Session } from '../../web/app/session.js';

/** The ends of a solve: each leads from solving to the phase of its name, and is ignored in every other phase. */
const ENDS = ['converged', 'stopped', 'convergedOnSamples', 'stoppedOnSamples'];

/** The rules the table writes out: what `event` should do in `phase` ('-': ignored, the phase stays). */
function expected(phase, event) {
  if (event === 'load' || event === 'clear') return 'idle';
  if (event === 'change') return 'solving';
  if (event === 'failed') return 'failed';
  return phase === 'solving' ? event : '-';
}

describe('the phase table', () => {
  it('has the phases and events the session uses, one row per phase and one cell per event', () => {
    expect(PHASES).toEqual(['idle', 'solving', 'converged', 'stopped', 'convergedOnSamples', 'stoppedOnSamples', 'failed']);
    expect(EVENTS).toEqual(['load', 'change', 'clear', ...ENDS, 'failed']);
    expect(Object.keys(PHASE_TABLE)).toEqual(PHASES);
    for (const phase of PHASES) expect(PHASE_TABLE[phase]).toHaveLength(EVENTS.length);
  });

  describe.each(PHASES)('in %s', (phase) => {
    it.each(EVENTS)('%s leads where the rules say', (event) => {
      const rule = expected(phase, event);
      expect(PHASE_TABLE[phase][EVENTS.indexOf(event)]).toBe(rule);
      expect(nextPhase(phase, event)).toBe(rule === '-' ? phase : rule);
    });
  });

  it('ignores only the ends of a solve that come when it is not solving (answers queued behind the end)', () => {
    const ignored = PHASES.flatMap((p) => EVENTS.filter((e, k) => PHASE_TABLE[p][k] === '-').map((e) => `${p}:${e}`));
    expect(ignored).toHaveLength((PHASES.length - 1) * ENDS.length);
    expect(ignored.every((cell) => ENDS.includes(cell.split(':')[1]) && !cell.startsWith('solving:'))).toBe(true);
  });

  it('refuses a phase or an event that does not exist', () => {
    expect(() => nextPhase('solving', 'settle')).toThrow(TypeError);
    expect(() => nextPhase('paused', 'change')).toThrow(/no phase 'paused'/);
    expect(() => new SessionState().send('converge')).toThrow(/no event 'converge'/);
  });

  it('reaches every phase from idle', () => {
    const reached = new Set(['idle']);
    for (let round = 0; round < PHASES.length; ++round) {
      for (const phase of [...reached]) for (const event of EVENTS) reached.add(nextPhase(phase, event));
    }
    expect([...reached].sort()).toEqual([...PHASES].sort());
  });
});

describe('SessionState', () => {
  /** A state in `phase` with `inFlight` requests out, paused or not. */
  function state(phase, { inFlight = 0, paused = false } = {}) {
    const s = new SessionState();
    s.phase = phase;
    for (let i = 0; i < inFlight; ++i) s.requestSent();
    s.setPaused(paused);
    return s;
  }

  it('settles in idle at once, in converged, stopped and failed once no request is out, never while solving or on samples', () => {
    const settled = (phase, options) => state(phase, options).settled;
    expect(PHASES.filter((p) => settled(p))).toEqual(['idle', 'converged', 'stopped', 'failed']);
    expect(PHASES.filter((p) => settled(p, { inFlight: 1 }))).toEqual(['idle']);
  });

  it('paused, settles whenever no request is out, whatever the phase', () => {
    expect(PHASES.every((p) => state(p, { paused: true }).settled)).toBe(true);
    expect(PHASES.some((p) => state(p, { paused: true, inFlight: 1 }).settled)).toBe(false);
  });

  it('asks for steps only while solving and not paused', () => {
    expect(PHASES.filter((p) => state(p).wantsSteps)).toEqual(['solving']);
    expect(state('solving', { paused: true }).wantsSteps).toBe(false);
  });

  it('reports the words of the stats; paused shows "paused" only for a solve waiting for its step', () => {
    expect(PHASES.map((p) => state(p).reported)).toEqual(['idle', 'solving', 'converged', 'stopped', 'converged', 'stopped', 'error']);
    expect(PHASES.map((p) => state(p, { paused: true }).shown))
      .toEqual(['idle', 'paused', 'converged', 'stopped', 'converged', 'stopped', 'error']);
  });

  it('send() says whether the phase changed; dropRequests() forgets the requests of a worker that went', () => {
    const s = state('solving', { inFlight: 2 });
    expect(s.send('converged')).toBe(true);
    expect(s.send('stopped')).toBe(false);
    expect(s.phase).toBe('converged');
    expect(s.settled).toBe(false);
    s.dropRequests();
    expect(s.settled).toBe(true);
  });
});

/**
 * A stand-in worker: each step answers `k` iterations of `ms` ms (reported, not waited) and converges on the `convergeAt`-th iteration
 * since the last setTargets/setHandles/setOptions (later ones go on without converging); after hold(), step
 * answers wait for release(n), which lets the next n through.
 */
function standInWorker({ convergeAt = 3, ms = 1 } = {}) {
  const log = [];
  let since = 0;
  const held = [];
  let holding = false;
  const answer = (payload) => {
    const iterations = [];
    let converged = false;
    for (let i = 0; i < payload.iterations && !converged; ++i) {
      since++;
      iterations.push({ merit: 1 / since, energy: 1, volumeRelError: 0, ms, samples: 0 });
      converged = since === convergeAt;
    }
    return { result: { iterations, converged, stop: converged ? 'merit' : 'iteration_limit', stopReason: '' } };
  };
  return {
    log,
    hold() { holding = true; },
    release(n = held.length) { for (const r of held.splice(0, n)) r(); },
    request(type, payload) {
      log.push(type === 'setOptions' ? `setOptions:${payload.options.integration ?? ''}` : type);
      if (['setTargets', 'setHandles', 'setOptions'].includes(type)) since = 0;
      if (type !== 'step') return Promise.resolve(type === 'resultWarnings' ? [] : {});
      if (!holding) return Promise.resolve(answer(payload));
      return new Promise((resolve) => held.push(() => resolve(answer(payload))));
    },
    terminate() {},
  };
}

const tick = () => new Promise((resolve) => setTimeout(resolve, 0));

/** A session bound to `worker` on a one-triangle model of `vertexCount` vertices, pumped like the frame loop. */
function boundSession(worker, { method = 'subspace', vertexCount = 3, dragIntegration = 'auto', maxIterations = 100 } = {}) {
  const session = new Session({ method, onFrame() {}, onError() {} });
  session.adopt(worker, { vertexCount, mesh: { positions: new Float64Array(9), indices: new Uint32Array([0, 1, 2]) } });
  session.applySettings({ options: {}, maxIterations, iterationsPerStep: 1, dragIntegration });
  return session;
}

async function pumpUntil(session, done, frames = 200) {
  for (let frame = 0; frame < frames && !done(); ++frame) {
    session.pump();
    await tick();
  }
}

describe('a Session through its phases', () => {
  it('solves a change, converges and settles; a change without handles goes back to idle', async () => {
    const session = boundSession(standInWorker());
    expect(session.state).toBe('idle');
    session.setHandles([[0]], new Float64Array(3));
    expect(session.state).toBe('solving');
    const settled = session.settled();
    await pumpUntil(session, () => session.state !== 'solving');
    await expect(settled).resolves.toBe('converged');
    expect(session.totalIterations).toBe(3);
    session.setHandles([], new Float64Array(0));
    expect(session.state).toBe('idle');
    await expect(session.settled()).resolves.toBe('idle');
  });

  it('stops at the iteration cap since the last change', async () => {
    const session = boundSession(standInWorker({ convergeAt: Infinity }), { maxIterations: 4 });
    session.setHandles([[0]], new Float64Array(3));
    await pumpUntil(session, () => session.state !== 'solving');
    expect(session.state).toBe('stopped');
    expect(session.stopReason).toBe('not converged after 4 iterations');
    expect(session.totalIterations).toBe(4);
  });

  it('settles only once the answers queued behind the converged one are in, which change nothing', async () => {
    const worker = standInWorker({ convergeAt: 1 });
    const session = boundSession(worker);
    session.applySettings({ options: {}, maxIterations: 100, iterationsPerStep: 'auto', dragIntegration: 'auto' });
    session.setHandles([[0]], new Float64Array(3));
    await pumpUntil(session, () => session.state !== 'solving'); // measures 1 ms per iteration: two requests out
    session.setTargets(new Float64Array(3));
    worker.hold();
    const steps = worker.log.filter((t) => t === 'step').length;
    session.pump();
    session.pump();
    expect(worker.log.filter((t) => t === 'step').length).toBe(steps + 2);
    let resolved = false;
    session.settled().then(() => { resolved = true; });
    worker.release(1); // converges
    await tick();
    expect(session.state).toBe('converged');
    expect(resolved).toBe(false); // one answer still out
    worker.release(1); // iterates on without converging: queued behind the end, it changes nothing
    await tick();
    expect(session.state).toBe('converged');
    expect(resolved).toBe(true);
    session.pump();
    expect(worker.log.filter((t) => t === 'step').length).toBe(steps + 2); // settled: no more requests
  });

  it('a solve that converges on the drag\'s samples is provisional: it solves on with the full integration at rest', async () => {
    const worker = standInWorker();
    const session = boundSession(worker, { dragIntegration: 'reduced' });
    session.setHandles([[0]], new Float64Array(3));
    let settledAs = null;
    session.settled().then((state) => { settledAs = state; });
    await pumpUntil(session, () => session.state !== 'solving');
    expect(session.state).toBe('converged'); // reported as converged, but not settled: the full answer is due
    expect(worker.log).toContain('setOptions:reduced');
    await new Promise((resolve) => setTimeout(resolve, 350)); // the targets rest (RESTING_MS)
    expect(settledAs).toBe(null);
    await pumpUntil(session, () => settledAs !== null);
    expect(settledAs).toBe('converged');
    expect(worker.log.indexOf('setOptions:full')).toBeGreaterThan(worker.log.indexOf('setOptions:reduced'));
    expect(session.totalIterations).toBe(6); // three on samples, three with every vertex
  });

  it('paused, only single steps iterate; it reads "paused" and settles with nothing out', async () => {
    const worker = standInWorker();
    const session = boundSession(worker);
    session.setPaused(true);
    session.setHandles([[0]], new Float64Array(3));
    await pumpUntil(session, () => false, 5);
    expect(worker.log).not.toContain('step');
    expect(session.status).toBe('paused');
    await expect(session.settled()).resolves.toBe('solving');
    await session.stepOnce();
    expect(session.totalIterations).toBe(1);
    session.setPaused(false);
    expect(session.status).toBe('solving');
    await pumpUntil(session, () => session.state !== 'solving');
    expect(session.state).toBe('converged');
  });

  it('counts an answer once though the page\'s frame handler throws: paused, it still settles with nothing out', async () => {
    const errors = [];
    const session = new Session({ method: 'subspace', onFrame() { throw new Error('drawing failed'); }, onError: (e) => errors.push(e.message) });
    session.adopt(standInWorker(), { vertexCount: 3, mesh: { positions: new Float64Array(9), indices: new Uint32Array([0, 1, 2]) } });
    session.applySettings({ options: {}, maxIterations: 100, iterationsPerStep: 1, dragIntegration: 'auto' });
    session.setHandles([[0]], new Float64Array(3));
    session.pump();
    await expect(session.settled()).resolves.toBe('error');
    expect(errors).toEqual(['drawing failed']);
    // Counted twice, the requests out would be -1: paused, the session would then never settle.
    session.setPaused(true);
    session.setTargets(new Float64Array(3));
    await expect(Promise.race([session.settled(), new Promise((r) => setTimeout(() => r('never'), 500))])).resolves.toBe('solving');
  });

  it('in compare mode a slow view waits while the handles move, and solves again as soon as the drag is released', async () => {
    const worker = standInWorker({ convergeAt: Infinity, ms: 400 }); // slower than SLOW_REQUEST_MS (step_pacing.js)
    const session = boundSession(worker);
    session.shareCores(true);
    const steps = () => worker.log.filter((type) => type === 'step').length;
    session.setHandles([[0]], new Float64Array(3));
    await pumpUntil(session, () => steps() === 1, 1);
    await tick(); // the answer: 400 ms per iteration measured
    session.setTargets(new Float64Array(3));
    session.pump();
    expect(steps()).toBe(1); // held: the targets changed just now
    session.released();
    session.pump();
    expect(steps()).toBe(2);
  });

  it('a failed request is the error state, settled; the next change solves again', async () => {
    const worker = standInWorker();
    const failing = { ...worker, request: (type, p) => (type === 'step' ? Promise.reject(new Error('boom')) : worker.request(type, p)) };
    const errors = [];
    const session = new Session({ method: 'arap', onFrame() {}, onError: (e) => errors.push(e.message) });
    session.adopt(failing, { mesh: { positions: new Float64Array(9), indices: new Uint32Array([0, 1, 2]) } });
    session.setHandles([[0]], new Float64Array(3));
    session.pump();
    await expect(session.settled()).resolves.toBe('error');
    expect(errors).toEqual(['boom']);
    expect(session.stopReason).toBe('boom');
    session.setTargets(new Float64Array(3));
    expect(session.state).toBe('solving');
  });
});
