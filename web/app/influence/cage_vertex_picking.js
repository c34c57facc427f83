// The cage vertex under a click: the drawn cage vertex nearest to the pointer on screen, within a radius (larger
// for touch), in one viewport. Cage vertices float around the mesh, where a ray would hit nothing, so picking is
// by screen distance rather than by ray.
import { Vector3 } from 'three';

const _p = new Vector3();

/**
 * @param {import('../view/viewport.js').Viewport} viewport
 * @param {{ clientX: number, clientY: number }} point
 * @param {number} radius in CSS pixels
 * @returns {number} the cage vertex, or -1 when none is within the radius (or no cage is drawn)
 */
export function cageVertexAt(viewport, { clientX, clientY }, radius) {
  const geometry = viewport.cageView.geometry;
  if (!geometry) return -1;
  const positions = geometry.attributes.position.array;
  const rect = viewport.canvas.getBoundingClientRect();
  const x = clientX - rect.left, y = clientY - rect.top;
  let best = -1, bestDistance = radius * radius;
  viewport.camera.updateMatrixWorld();
  for (let j = 0; j < positions.length / 3; ++j) {
    _p.set(positions[3 * j], positions[3 * j + 1], positions[3 * j + 2]).project(viewport.camera);
    if (_p.z < -1 || _p.z > 1) continue; // behind the camera or clipped
    const dx = ((_p.x + 1) / 2) * rect.width - x, dy = ((1 - _p.y) / 2) * rect.height - y;
    const d = dx * dx + dy * dy;
    if (d < bestDistance) {
      bestDistance = d;
      best = j;
    }
  }
  return best;
}
