// The app's choice of integration (web/app/integration_policy.js): reduced while the handles move on large
// models, the settled integration once they rest, with "rest" measured against the drag's own pace.
import { describe, expect, it } from 'vitest';
import { AUTO_REDUCED_VERTICES, IntegrationPolicy, MAX_RESTING_MS, RESTING_MS } from '../../web/app/integration_policy.js';

const big = { vertexCount: AUTO_REDUCED_VERTICES };
const small = { vertexCount: AUTO_REDUCED_VERTICES - 1 };

describe('IntegrationPolicy', () => {
  it('samples a large model while its handles move and goes back to the settled integration once they rest', () => {
    const policy = new IntegrationPolicy();
    expect(policy.wanted('subspace', big, 'full', 0)).toBe('full'); // nothing moved yet
    policy.moved(1000);
    expect(policy.wanted('subspace', big, 'full', 1000 + RESTING_MS - 1)).toBe('reduced');
    expect(policy.wanted('subspace', big, 'full', 1000 + RESTING_MS)).toBe('full');
    expect(policy.wanted('subspace', small, 'full', 1001)).toBe('full'); // a full iteration is cheap there
    expect(policy.wanted('arap', big, 'full', 1001)).toBe('full'); // only the subspace method samples
  });

  it('counts a pause as a rest only after three of the drag\'s own intervals (a slow renderer\'s frames)', () => {
    const policy = new IntegrationPolicy();
    // Targets changing every 600 ms, one per slow frame: 600 ms without a change is not a rest.
    for (let t = 0; t <= 3000; t += 600) policy.moved(t);
    expect(policy.wanted('subspace', big, 'full', 3000 + 600)).toBe('reduced');
    expect(policy.wanted('subspace', big, 'full', 3000 + 3 * 600 - 1)).toBe('reduced');
    expect(policy.wanted('subspace', big, 'full', 3000 + 3 * 600)).toBe('full');
  });

  it('waits at most MAX_RESTING_MS, and keeps the drag\'s pace across a pause', () => {
    const policy = new IntegrationPolicy();
    policy.moved(0);
    policy.moved(2900); // very slow frames: three intervals would be 8.7 s
    expect(policy.wanted('subspace', big, 'full', 2900 + MAX_RESTING_MS - 1)).toBe('reduced');
    expect(policy.wanted('subspace', big, 'full', 2900 + MAX_RESTING_MS)).toBe('full');
    // The first change of the next drag, after a minute: its pace is not known yet, the last drag's is.
    policy.moved(60000);
    expect(policy.wanted('subspace', big, 'full', 60000 + 2000)).toBe('reduced');
    // A fast drag resets the pace: rest after RESTING_MS again.
    policy.moved(60016);
    expect(policy.wanted('subspace', big, 'full', 60016 + RESTING_MS)).toBe('full');
  });

  it('rests at once when the drag ends (a pointer release), and the next drag samples again at its old pace', () => {
    const policy = new IntegrationPolicy();
    for (let t = 0; t <= 600; t += 200) policy.moved(t); // a slow drag: a pause of 3 x 200 ms would be a rest
    expect(policy.wanted('subspace', big, 'full', 601)).toBe('reduced');
    policy.released();
    expect(policy.wanted('subspace', big, 'full', 601)).toBe('full');
    policy.moved(5000); // the next drag: moving again, and a pause is judged by the last drag's pace
    expect(policy.wanted('subspace', big, 'full', 5000 + 3 * 200 - 1)).toBe('reduced');
    expect(policy.wanted('subspace', big, 'full', 5000 + 3 * 200)).toBe('full');
  });

  it('tells the worker only changes, and marks a switch after the first choice', () => {
    const policy = new IntegrationPolicy();
    policy.moved(performance.now());
    expect(policy.next('subspace', big, 'full')).toEqual({ integration: 'reduced', switched: false });
    expect(policy.next('subspace', big, 'full')).toBeNull();
    policy.whileMoving = 'full';
    expect(policy.next('subspace', big, 'full')).toEqual({ integration: 'full', switched: true });
  });

  it('keeps full integration for a model whose reduced rule failed its test, says why, and forgets it on a new model', () => {
    const policy = new IntegrationPolicy();
    policy.checkFit({ reliable: true, testError: 0.03 });
    expect(policy.notice).toBeNull();
    policy.moved(1000);
    expect(policy.wanted('subspace', big, 'full', 1001)).toBe('reduced');
    policy.checkFit({ reliable: false, testError: 0.66 });
    expect(policy.notice.code).toBe('reduced_integration_inaccurate');
    expect(policy.notice.severity).toBe('warning'); // as every warning in the stats (embed/index.d.ts ViewStats)
    expect(policy.notice.message).toMatch(/0\.66/);
    expect(policy.wanted('subspace', big, 'full', 1001)).toBe('full');
    policy.whileMoving = 'reduced'; // asked for explicitly: still reduced
    expect(policy.wanted('subspace', big, 'full', 1001)).toBe('reduced');
    policy.whileMoving = 'auto';
    policy.newModel();
    expect(policy.notice).toBeNull();
    expect(policy.wanted('subspace', big, 'full', 1001)).toBe('reduced');
  });
});
