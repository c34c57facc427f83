// The skeleton drawn in one viewport: a sphere per joint and a stick (cylinder) per bone, drawn over the mesh
// (no depth test), so that joints and bones inside it always show; while the bone tool is on the mesh is also
// drawn translucent (setXray). Joints of bones are drawn where the solver's last report puts them (they
// follow the deformed mesh every frame); the others (a chain's first joint, every joint while the solvers do not
// keep the bones) are carried by the drawn mesh between the two surface points they are anchored to
// (joint_placement.js), so with "use bones" off the sticks show what the mesh alone does to the limbs. The chain's
// tip and the selected bone are orange; a bone the solver reports longer or shorter than its rest length by
// more than 1e-6 of it, sagging by more than 2% of it (the hard samples hold a quarter, half and three quarters
// along; between them a bent limb may bow a little), or kept straight only softly, is red.
import { Color, CylinderGeometry, Group, Mesh, MeshBasicMaterial, Quaternion, SphereGeometry, Vector3 } from 'three';
import { anchoredPoint } from './joint_placement.js';
import { STRAINED } from './skeleton_text.js';

const COLORS = { joint: 0x1d4ed8, bone: 0x0f766e, chosen: 0xf08a24, strained: 0xd62828 };
const _a = new Vector3();
const _b = new Vector3();
const _up = new Vector3(0, 1, 0);
const _q = new Quaternion();

/** A report's deformed joints as [x, y, z] each (the library gives them flat, 3 numbers per joint, in a Float64Array). */
export function reportJoints(report) {
  const joints = report?.joints ?? [];
  if (!ArrayBuffer.isView(joints)) return joints.map((p) => [...p]);
  return Array.from({ length: joints.length / 3 }, (_, k) => [joints[3 * k], joints[3 * k + 1], joints[3 * k + 2]]);
}

export class SkeletonView {
  /** @param {import('../view/viewport.js').Viewport} viewport */
  constructor(viewport) {
    this.viewport = viewport;
    this.object = new Group();
    this.object.renderOrder = 20;
    viewport.scene.add(this.object);
    this.sphere = new SphereGeometry(1, 16, 12);
    this.cylinder = new CylinderGeometry(1, 1, 1, 10, 1);
    this.radius = 0.01;
    /** Drawn joint positions (deformed space), one per joint of the state. */
    this.points = [];
    this.bones = [];
    this.tip = -1;
    this.selectedBone = -1;
    this.map = [];
    this.anchors = [];
    this.report = null;
    this.xray = false;
    this.sticks = []; // one mesh per bone, kept and moved
    this.balls = []; // one per joint
  }

  /** Sizes the joints and sticks for the mesh drawn (its bounding box's diagonal). */
  fit() {
    const box = this.viewport.meshView.geometry?.boundingBox;
    this.radius = 0.009 * (box ? box.max.distanceTo(box.min) : 1);
    this.#draw();
  }

  /**
   * The skeleton's structure (skeleton.js): drawn positions of new joints, bones, what is in hand, `map` (the
   * solver's joint k is joint map[k] here) and each joint's anchor in the mesh (or null).
   */
  show({ shown, bones, tip, selectedBone, map, anchors = [] }) {
    this.points = shown.map((p) => [...p]);
    this.anchors = anchors;
    this.bones = bones.map((b) => [...b]);
    this.tip = tip;
    this.selectedBone = selectedBone;
    this.map = map;
    this.follow(this.report);
  }

  /** A solver report (or null): joints where it puts them, bones coloured by their errors. */
  follow(report) {
    if (!report && !this.report && !this.points.length) return; // no skeleton: nothing to move
    this.report = report ?? null;
    const joints = reportJoints(this.report);
    const reported = new Set();
    if (this.report && joints.length === this.map.length) {
      joints.forEach((p, k) => {
        this.points[this.map[k]] = p;
        reported.add(this.map[k]);
      });
    }
    const { positions } = this.viewport.meshView;
    const indices = this.viewport.meshView.geometry?.index?.array;
    this.anchors.forEach((anchor, j) => {
      if (anchor && !reported.has(j) && positions && indices) this.points[j] = anchoredPoint(anchor, positions, indices);
    });
    this.#draw();
  }

  /** The mesh translucent (the bone tool is on) or as it was. */
  setXray(on) {
    if (this.xray === !!on) return;
    this.xray = !!on;
    const material = this.viewport.meshView.material;
    material.transparent = this.xray;
    material.opacity = this.xray ? 0.45 : 1;
    material.depthWrite = !this.xray;
    material.needsUpdate = true;
    this.viewport.invalidate();
  }

  // Moves (and colours) the sticks and balls in place: a solver frame costs no new objects, only transforms.
  #draw() {
    const r = this.radius;
    const strained = (k) => {
      const e = this.report?.bones?.[k];
      return !!e && (Math.abs(e.lengthError) > STRAINED.length || Math.abs(e.straightnessError) > STRAINED.straightness || e.straightHard === false);
    };
    this.#pool(this.sticks, this.bones.length, this.cylinder, 0.85);
    this.bones.forEach(([a, b], k) => {
      const stick = this.sticks[k];
      stick.visible = !!this.points[a] && !!this.points[b];
      if (!stick.visible) return;
      _a.fromArray(this.points[a]);
      _b.fromArray(this.points[b]);
      const length = _a.distanceTo(_b);
      stick.visible = length > 0;
      stick.material.color.setHex(k === this.selectedBone ? COLORS.chosen : strained(k) ? COLORS.strained : COLORS.bone);
      stick.scale.set(r, length, r);
      stick.position.copy(_a).add(_b).multiplyScalar(0.5);
      if (length > 0) stick.quaternion.copy(_q.setFromUnitVectors(_up, _b.sub(_a).normalize()));
    });
    this.#pool(this.balls, this.points.length, this.sphere, 0.95);
    this.points.forEach((p, j) => {
      const ball = this.balls[j];
      ball.material.color.setHex(j === this.tip ? COLORS.chosen : COLORS.joint);
      ball.scale.setScalar(j === this.tip ? 2.6 * r : 2 * r);
      ball.position.fromArray(p);
    });
    this.viewport.invalidate();
  }

  // `count` meshes of `geometry` in `list` (added to or removed from the group as needed).
  #pool(list, count, geometry, opacity) {
    while (list.length > count) {
      const mesh = list.pop();
      mesh.material.dispose();
      this.object.remove(mesh);
    }
    while (list.length < count) {
      const material = new MeshBasicMaterial({ color: new Color(COLORS.joint), depthTest: false, depthWrite: false, transparent: true, opacity });
      const mesh = new Mesh(geometry, material);
      mesh.renderOrder = 20;
      mesh.raycast = () => {}; // picked by screen distance (skeleton_picking.js)
      this.object.add(mesh);
      list.push(mesh);
    }
  }

  dispose() {
    this.points = [];
    this.bones = [];
    this.#draw();
    this.viewport.scene.remove(this.object);
    this.sphere.dispose();
    this.cylinder.dispose();
  }
}
