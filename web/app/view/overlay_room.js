// Framing around the stats and the plot drawn over the bottom of a tall view. On a phone (one portrait view) they
// cover the lower 40% of it, and a model framed in the middle of the whole view sat under them while the top stayed
// empty (a tester's skeleton lesson at 390 x 844). A portrait view is therefore framed in the part above them: the
// box is fitted to that part (a smaller vertical field) and the projection is shifted (three's view offset) so the
// camera's axis, the orbit centre, is that part's centre; orbiting and picking go through the same projection.

const MAX_COVERED = 0.5; // never frame into less than half of the view
const PORTRAIT = 0.8; // width / height below which the overlays cover a view's bottom across the model

/**
 * The fraction of `element`'s height under the top of `overlay` (the stats box, the plot below it), for a portrait
 * view whose overlay sits in its lower half; 0 otherwise (a wide view has room beside them).
 * @param {HTMLElement} element
 * @param {HTMLElement} overlay
 */
export function coveredBelow(element, overlay) {
  const view = element.getBoundingClientRect();
  if (!view.height || view.width / view.height >= PORTRAIT || !overlay.offsetParent) return 0;
  const top = overlay.getBoundingClientRect().top - view.top;
  if (top < view.height / 2) return 0;
  return Math.min(MAX_COVERED, Math.max(0, (view.height - top) / view.height));
}

/** The camera that the part above the covered fraction is: the same horizontal field, a smaller vertical one. */
export function cameraAbove(camera, covered) {
  if (!covered) return camera;
  const tan = Math.tan((camera.fov * Math.PI) / 360) * (1 - covered);
  return { fov: (360 / Math.PI) * Math.atan(tan), aspect: camera.aspect / (1 - covered), up: camera.up };
}

/** Shifts the projection so that the camera's axis is at the centre of the part above `covered` (none: no shift). */
export function shiftProjection(camera, covered, width, height) {
  if (covered > 0) camera.setViewOffset(width, height, 0, (covered * height) / 2, width, height);
  else if (camera.view) camera.clearViewOffset();
}
