// Handle vertices drawn as dots on the deformed surface (fixed groups blue, moving groups orange as in the
// figures of docs/experiments, the gizmo's group brighter, the pending selection yellow) and one arrow per moving group
// from its rest centroid to its target centroid.
import { ArrowHelper, BufferAttribute, BufferGeometry, Color, Group, Points, PointsMaterial, Vector3 } from 'three';

export const HANDLE_COLORS = {
  fixed: new Color(0x2a6bd6),
  moving: new Color(0xf08a24),
  active: new Color(0xff3d00),
  selection: new Color(0xffd21f),
};

const _from = new Vector3();
const _to = new Vector3();
const _dir = new Vector3();

export class HandleView {
  constructor() {
    this.object = new Group();
    this.material = new PointsMaterial({ size: 5, sizeAttenuation: false, vertexColors: true });
    this.geometry = new BufferGeometry();
    this.points = new Points(this.geometry, this.material);
    this.points.raycast = () => {};
    this.points.frustumCulled = false;
    this.arrows = new Group();
    this.object.add(this.points, this.arrows);
    this.vertices = new Uint32Array(0);
    this.arrowScale = 1;
  }

  /**
   * Rebuilds the dot list from the handle groups and the pending selection.
   * @param {import('../interaction/handle_set.js').HandleSet} handles
   * @param {Iterable<number>} selection
   */
  setHandles(handles, selection) {
    const vertices = [];
    const colors = [];
    handles.groups.forEach((g, i) => {
      const color = !g.moving ? HANDLE_COLORS.fixed : i === handles.active ? HANDLE_COLORS.active : HANDLE_COLORS.moving;
      for (const v of g.vertices) {
        vertices.push(v);
        colors.push(color.r, color.g, color.b);
      }
    });
    for (const v of selection) {
      vertices.push(v);
      const c = HANDLE_COLORS.selection;
      colors.push(c.r, c.g, c.b);
    }
    this.vertices = Uint32Array.from(vertices);
    this.geometry.dispose();
    this.geometry = new BufferGeometry();
    this.geometry.setAttribute('position', new BufferAttribute(new Float32Array(3 * vertices.length), 3));
    this.geometry.setAttribute('color', new BufferAttribute(new Float32Array(colors), 3));
    this.points.geometry = this.geometry;
    this.setArrows(handles);
  }

  /**
   * One arrow per moving group: rest centroid -> target centroid. Called on every target change (each frame
   * of a gizmo drag), so the arrows are kept and only moved: creating and disposing ArrowHelpers per frame
   * disposes their materials, and three.js then deletes and recompiles the shader program, which costs a
   * software renderer (SwiftShader) tens of milliseconds per frame.
   */
  setArrows(handles) {
    let used = 0;
    handles.groups.forEach((g, i) => {
      if (!g.moving) return;
      _from.fromArray(g.center);
      _to.fromArray(g.translate);
      const length = _to.length();
      if (length < 1e-9) return;
      _dir.copy(_to).divideScalar(length);
      const head = Math.min(0.35 * length, 0.08 * this.arrowScale);
      let arrow = this.arrows.children[used];
      if (!arrow) {
        arrow = new ArrowHelper(_dir, _from, length, 0xf08a24, head, 0.5 * head);
        arrow.line.material.depthTest = false;
        arrow.cone.material.depthTest = false;
        arrow.renderOrder = 10;
        this.arrows.add(arrow);
      }
      arrow.visible = true;
      arrow.position.copy(_from);
      arrow.setDirection(_dir);
      arrow.setLength(length, head, 0.5 * head);
      arrow.setColor(i === handles.active ? 0xff3d00 : 0xf08a24);
      used++;
    });
    for (let k = used; k < this.arrows.children.length; ++k) this.arrows.children[k].visible = false;
  }

  /** Moves the dots onto the current surface (Float32 positions of the mesh view). */
  update(positions) {
    if (!positions) return;
    const out = this.geometry.attributes.position.array;
    const vertices = this.vertices;
    for (let k = 0; k < vertices.length; ++k) {
      const v = 3 * vertices[k];
      out[3 * k] = positions[v];
      out[3 * k + 1] = positions[v + 1];
      out[3 * k + 2] = positions[v + 2];
    }
    this.geometry.attributes.position.needsUpdate = true;
  }

  dispose() {
    this.geometry.dispose();
    this.material.dispose();
    // ArrowHelper.dispose() would also dispose the geometries all arrows share; only the materials are ours.
    for (const arrow of this.arrows.children) {
      arrow.line.material.dispose();
      arrow.cone.material.dispose();
    }
  }
}
