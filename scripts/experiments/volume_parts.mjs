// Global volume against volume kept per part (docs/method.md section 16; the report's future work and its
// figure 1, where the neck root shrinks while the head elongates) on a neck pull: the lower body fixed, the
// head pulled forward. Each basis (cage, spectral with k + 4 = m, full space) runs from rest with the one global
// volume and with automatic parts; ARAP (no volume constraint) runs for reference. Every final shape's part
// volumes are measured with the same partition.
import { Deformer, volumeParts } from 'subspace-deform';
import { bounds, point, verticesBelow, verticesNear } from './scenes.mjs';
import { runSeries } from './series.mjs';
import { renderViews } from './render.mjs';
import { Timer } from '../lib/timer.mjs';

export const NECK_PULL = {
  id: 'neck_pull',
  title: 'Neck pull (report fig. 1, future work): one global volume against the volume of each part',
  model: { name: 'armadillo', mesh: 'armadillo.obj', cage: 'armadillo_cage.obj' },
  fallback: { example: 'bar' },
  view: { yaw: -Math.PI * 0.6 },  // from the side and a little from the front
  build(positions, real) {
    const b = bounds(positions);
    if (real) {
      // Armadillo stands along +y facing -z, arms out to the sides; its snout is the most forward (lowest z)
      // point of the top 30% within the middle fifth of the width (the hands reach further forward).
      const body = verticesBelow(positions, 1, b.lo[1] + 0.45 * b.size[1]);
      const midX = (b.lo[0] + b.hi[0]) / 2;
      let front = -1;
      for (let i = 0; i < positions.length / 3; ++i) {
        const inHead = positions[3 * i + 1] > b.lo[1] + 0.7 * b.size[1] && Math.abs(positions[3 * i] - midX) < 0.1 * b.size[0];
        if (inHead && (front < 0 || positions[3 * i + 2] < positions[3 * front + 2])) front = i;
      }
      const head = verticesNear(positions, point(positions, front), 0.06 * b.diagonal);
      return {
        parts: 8,
        handles: [{ vertices: body }, { vertices: head, translate: [0, 0.04 * b.diagonal, -0.12 * b.diagonal] }],
        query: `fixed: the lowest 45% of the height (${body.length} vertices); moved: within 0.06 D of the most forward ` +
          `(lowest z) point of the top 30% in the middle fifth of the width (the snout, ${head.length} vertices), forward by ` +
          `0.12 D and up by 0.04 D; ` +
          '8 automatic parts',
      };
    }
    const left = verticesBelow(positions, 0, b.lo[0] + 0.06 * b.size[0]);
    const right = verticesNear(positions, point(positions, b.argHi[0]), 0.08 * b.diagonal);
    return {
      parts: 3,
      handles: [{ vertices: left }, { vertices: right, translate: [0.25 * b.size[0], -0.1 * b.size[0], 0] }],
      query: `fixed: the left 6% of the bar (${left.length} vertices); moved: within 0.08 D of the right tip ` +
        `(${right.length} vertices), pulled away and down; 3 automatic parts`,
    };
  },
};

const PALETTE = [[230, 80, 80], [80, 160, 230], [90, 200, 110], [240, 200, 60], [180, 100, 220], [250, 140, 60],
  [100, 220, 220], [200, 200, 200], [150, 90, 60], [240, 120, 190]];

// Each part's volume change (%) at the session's current positions, measured with `parts`.
function partChanges(d, parts, hadParts) {
  if (!hadParts) d.setVolumeParts(parts);
  const rest = d.restPartVolumes(), now = d.partVolumes();
  if (!hadParts) d.setVolumeParts(null);
  return Array.from(now, (v, k) => (100 * (v - rest[k])) / Math.abs(rest[k]));
}

function run(ctx, model, parts, { basis, kind, withParts, label }) {
  const m = model.cage.positions.length / 3;
  const options = basis === 'spectral' ? { basis, modes: m - 4 } : {};
  const d = Deformer.create(ctx.solver, model.mesh, basis === 'spectral' ? null : model.cage, options);
  try {
    if (withParts) d.setVolumeParts(parts);
    d.setHandles(ctx.groups);
    const s = runSeries({ ...ctx, d }, kind);
    s.label = label;
    s.method = `${basis}-${kind}-${withParts ? 'parts' : 'global'}`;
    s.volumeParts = withParts;
    s.final.partChangePercent = partChanges(d, parts, withParts);
    return s;
  } finally {
    d.dispose();
  }
}

/** Runs the neck pull; returns { parts, restPartVolumes, series, image } for results.json. */
export function runVolumeParts(ctx, model, K, out, log) {
  const parts = volumeParts(ctx.solver, model.mesh, { auto: K });
  const m = model.cage.positions.length / 3;
  const plan = [
    { basis: 'cage', kind: 'subspace-fast', withParts: false, label: 'cage subspace, global volume' },
    { basis: 'cage', kind: 'subspace-fast', withParts: true, label: 'cage subspace, volume per part' },
    { basis: 'spectral', kind: 'subspace-fast', withParts: false, label: `spectral (k = ${m - 4}), global volume` },
    { basis: 'spectral', kind: 'subspace-fast', withParts: true, label: `spectral (k = ${m - 4}), volume per part` },
    { basis: 'cage', kind: 'full-fast', withParts: false, label: 'full space, global volume' },
    { basis: 'cage', kind: 'full-fast', withParts: true, label: 'full space, volume per part' },
    { basis: 'cage', kind: 'arap', withParts: false, label: 'ARAP (no volume constraint)' },
  ];
  const series = [];
  for (const entry of plan) {
    const timer = new Timer();
    const s = run(ctx, model, parts, entry);
    series.push(s);
    const worst = Math.max(...s.final.partChangePercent.map(Math.abs));
    log(`${NECK_PULL.id} ${s.label}: ${s.iterations.length} iterations, energy ${s.final.energy.toExponential(3)}, ` +
      `largest part change ${worst.toFixed(3)}%, ${s.stopReason} (${timer.seconds().toFixed(1)} s)`);
  }
  const d = Deformer.create(ctx.solver, model.mesh, model.cage);
  d.setVolumeParts(parts);
  const restPartVolumes = Array.from(d.restPartVolumes());
  d.dispose();
  const faceColors = Array.from(parts, (p) => PALETTE[p % PALETTE.length]);
  const image = renderViews(out, NECK_PULL.id, model.mesh, series.filter((s) => s.method !== 'cage-arap-global'), ctx,
    { yaw: model.real ? NECK_PULL.view.yaw : 0, faceColors, restLabel: 'rest pose, coloured by part (target of the head in red)' });
  return { parts: K, restPartVolumes, series, image };
}
