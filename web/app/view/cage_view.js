// The cage as a wireframe (its unique edges) with its vertices as dots. It follows the subspace solve: the
// worker sends the current cage P with every frame. Full space and ARAP do not move it (the worker sends
// the rest cage): there it is drawn dimmed, as the rest cage it is (setFollows(false)).
import { BufferAttribute, BufferGeometry, DynamicDrawUsage, Group, LineBasicMaterial, LineSegments, Points, PointsMaterial } from 'three';

export class CageView {
  constructor() {
    this.object = new Group();
    this.lineMaterial = new LineBasicMaterial({ color: 0x2f6f4f, transparent: true, opacity: 0.75 });
    this.pointMaterial = new PointsMaterial({ color: 0x2f6f4f, size: 5, sizeAttenuation: false });
    this.geometry = null;
    this.follows = true;
    // One cage vertex marked (the influence view's): a larger dot drawn over the others.
    this.highlight = -1;
    this.markGeometry = new BufferGeometry();
    this.markGeometry.setAttribute('position', new BufferAttribute(new Float32Array(3), 3));
    this.mark = new Points(this.markGeometry, new PointsMaterial({ color: 0x1a2f9c, size: 13, sizeAttenuation: false, depthTest: false }));
    this.mark.frustumCulled = false;
    this.mark.renderOrder = 2;
    this.mark.visible = false;
    this.mark.raycast = () => {};
    this.object.add(this.mark);
  }

  /** Marks cage vertex j (-1: none). */
  setHighlight(j) {
    this.highlight = this.geometry && j >= 0 && j < this.geometry.attributes.position.count ? j : -1;
    this.#placeMark();
  }

  #placeMark() {
    this.mark.visible = this.highlight >= 0;
    if (!this.mark.visible) return;
    const from = this.geometry.attributes.position.array, to = this.markGeometry.attributes.position;
    to.array.set(from.subarray(3 * this.highlight, 3 * this.highlight + 3));
    to.needsUpdate = true;
  }

  /** Whether the cage moves with the solve (subspace) or stays at rest (full space, ARAP: drawn dimmed). */
  setFollows(follows) {
    this.follows = follows;
    this.lineMaterial.color.set(follows ? 0x2f6f4f : 0x7d8794);
    this.lineMaterial.opacity = follows ? 0.75 : 0.3;
    this.pointMaterial.color.set(follows ? 0x2f6f4f : 0x7d8794);
    this.pointMaterial.size = follows ? 5 : 3;
    this.pointMaterial.transparent = !follows;
    this.pointMaterial.opacity = follows ? 1 : 0.5;
  }

  /** Whether a cage is drawn (none for a lone mesh, or with the spectral basis). */
  get shown() {
    return this.geometry !== null;
  }

  /** @param {{ positions: Float64Array, indices: Uint32Array }} cage no faces: nothing is drawn */
  setCage(cage) {
    this.dispose();
    if (!cage.indices.length) return;
    const edges = new Set();
    const list = [];
    const f = cage.indices;
    for (let t = 0; t < f.length; t += 3) {
      for (let e = 0; e < 3; ++e) {
        const a = f[t + e];
        const b = f[t + ((e + 1) % 3)];
        const key = a < b ? `${a},${b}` : `${b},${a}`;
        if (!edges.has(key)) {
          edges.add(key);
          list.push(a, b);
        }
      }
    }
    const geometry = new BufferGeometry();
    const position = new BufferAttribute(new Float32Array(cage.positions), 3);
    position.setUsage(DynamicDrawUsage);
    geometry.setAttribute('position', position);
    geometry.setIndex(list);
    this.geometry = geometry;
    this.lines = new LineSegments(geometry, this.lineMaterial);
    this.points = new Points(geometry, this.pointMaterial);
    // The cage moves with the subspace solve: never cull on (stale) bounds, never recompute them per frame.
    this.lines.frustumCulled = false;
    this.points.frustumCulled = false;
    this.lines.raycast = () => {};
    this.points.raycast = () => {};
    this.object.add(this.lines, this.points);
  }

  /** @param {Float32Array} positions the cage from the worker (taken as the attribute array, no copy) */
  update(positions) {
    if (!this.geometry || !positions || positions.length !== this.geometry.attributes.position.array.length) return;
    this.geometry.attributes.position.array = positions;
    this.geometry.attributes.position.needsUpdate = true;
    this.#placeMark();
  }

  dispose() {
    if (this.lines) this.object.remove(this.lines, this.points);
    this.geometry?.dispose();
    this.geometry = null;
    this.highlight = -1;
    this.mark.visible = false;
    this.lines = null;
    this.points = null;
  }
}
