// The brush's outline under the pointer while a brush stroke paints: a circle of the brush's world radius
// at the depth of the surface under the pointer, so a finger (which hides what it touches) or a mouse shows
// how much one stroke takes. Drawn in the picker's SVG overlay.
export class BrushCursor {
  /** @param {SVGSVGElement} svg the overlay (sized as the canvas) */
  constructor(svg) {
    this.circle = document.createElementNS('http://www.w3.org/2000/svg', 'circle');
    this.circle.setAttribute('class', 'sd-brush-cursor');
    this.hide();
    svg.appendChild(this.circle);
  }

  /**
   * @param {{ x: number, y: number, h: number }} at pointer position and canvas height in CSS px
   * @param {number} radius world-space brush radius
   * @param {number} distance from the camera to the surface point
   * @param {import('three').PerspectiveCamera} camera
   */
  show(at, radius, distance, camera) {
    const halfHeight = distance * Math.tan((camera.fov * Math.PI) / 360);
    const px = (radius / halfHeight) * (at.h / 2);
    this.circle.setAttribute('cx', String(at.x));
    this.circle.setAttribute('cy', String(at.y));
    this.circle.setAttribute('r', String(Math.max(2, px)));
    this.circle.style.display = '';
  }

  hide() {
    this.circle.style.display = 'none';
  }
}
