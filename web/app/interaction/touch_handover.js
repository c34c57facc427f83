// Handing a finger to OrbitControls after the fact. A brush or lasso stroke keeps its finger from the camera
// controls (the picker takes it in the capture phase), and so does a gizmo drag (handle_gizmo.js); when a second
// finger lands the user wants to zoom or pan, and OrbitControls must track both fingers to do so. It has never
// seen the first one, so it gets a synthetic pointerdown for it at its current position (marked, so that the
// picker and the gizmo let it through), and then the second finger's own pointerdown: from there on both
// fingers' moves reach it as usual.
const HANDED_OVER = Symbol('handed over to OrbitControls');

/** Whether a pointer event is such a synthetic press (the picker ignores it). */
export function isHandedOver(event) {
  return event[HANDED_OVER] === true;
}

/**
 * Dispatches a synthetic touch pointerdown for `pointerId` at `position` on `canvas` (OrbitControls listens there).
 * @param {HTMLCanvasElement} canvas
 * @param {number} pointerId a touch pointer that is still down
 * @param {{ clientX: number, clientY: number }} position where it is now
 */
export function handOverToOrbit(canvas, pointerId, position) {
  const event = new PointerEvent('pointerdown', {
    pointerId, pointerType: 'touch', isPrimary: true, button: 0, buttons: 1, bubbles: true, cancelable: true,
    clientX: position.clientX, clientY: position.clientY,
  });
  event[HANDED_OVER] = true;
  canvas.dispatchEvent(event);
}
