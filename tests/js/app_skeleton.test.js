// The app's skeleton parts that need no page (web/app/skeleton/): where a bone-tool tap puts a joint (midway
// between the surface hit and the next hit along the view ray, carried back to the rest mesh), building chains of
// bones, deleting, picking on screen, undo in one timeline with the handle edits, the text of the numbers, the
// saved scene, and the Skeleton against stand-in workers (sent to every view, a refused skeleton taken back).
import { describe, expect, it } from 'vitest';
import { anchorPoint, anchoredPoint, jointOnRay, rayHits } from '../../web/app/skeleton/joint_placement.js';
import { SkeletonState } from '../../web/app/skeleton/skeleton_state.js';
import { UndoHistory } from '../../web/app/interaction/undo_history.js';
import { EditTimeline } from '../../web/app/interaction/edit_timeline.js';
import { HandleSet } from '../../web/app/interaction/handle_set.js';
import { boneNear, jointNear } from '../../web/app/skeleton/skeleton_picking.js';
import { bonesSummary, skeletonPanelText, skeletonStatsLine, skeletonTraceLines } from '../../web/app/skeleton/skeleton_text.js';
import { Skeleton } from '../../web/app/skeleton/skeleton.js';
import { BoneTool } from '../../web/app/skeleton/bone_tool.js';
import { SkeletonView, reportJoints } from '../../web/app/skeleton/skeleton_view.js';
import { PerspectiveCamera, Scene, Vector3 } from 'three';
import { savedScene, sceneText } from '../../web/app/loading/saved_scene.js';
import { decodePose, encodePose } from '../../web/app/loading/pose_link.js';
import { statsLine } from '../../web/app/stats_format.js';
import { traceLines } from '../../web/app/view/iteration_trace.js';

/** A closed box [-a, a] x [-b, b] x [-c, c]: 8 corners, 12 outward triangles. */
function box(a = 0.5, b = 0.5, c = 0.5) {
  const positions = [];
  for (let i = 0; i < 8; ++i) positions.push(i & 1 ? a : -a, i & 2 ? b : -b, i & 4 ? c : -c);
  const quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
  const indices = quads.flatMap(([p, q, r, s]) => [p, q, r, p, r, s]);
  return { positions: Float64Array.from(positions), indices: Uint32Array.from(indices) };
}

const close = (got, want, digits = 12) => want.forEach((w, d) => expect(got[d]).toBeCloseTo(w, digits));

describe('joint placement', () => {
  it('puts the joint midway between the surface hit and the next one along the ray', () => {
    const { positions, indices } = box();
    const placed = jointOnRay([0.3, 0.2, 5], [0, 0, -1], { shown: positions, rest: positions, indices });
    close(placed.rest, [0.3, 0.2, 0]);
    close(placed.shown, [0.3, 0.2, 0]);
    expect(placed.depth).toBeCloseTo(1, 12);
    // Any length of direction, from any side.
    close(jointOnRay([-4, 0.1, -0.2], [8, 0, 0], { shown: positions, rest: positions, indices }).rest, [0, 0.1, -0.2]);
  });

  it('casts the ray on the mesh as drawn and carries both hits back to the rest mesh through their triangles', () => {
    const rest = box();
    // Drawn: the box stretched to twice its size and moved by (1, 0, 0).
    const shown = rest.positions.map((x, i) => 2 * x + (i % 3 === 0 ? 1 : 0));
    const placed = jointOnRay([1.6, 0.4, 9], [0, 0, -1], { shown, rest: rest.positions, indices: rest.indices });
    close(placed.shown, [1.6, 0.4, 0]);
    close(placed.rest, [0.3, 0.2, 0]); // the same point of the rest box
    expect(placed.depth).toBeCloseTo(2, 12);
  });

  it('counts a crossing through an edge or a corner shared by triangles once', () => {
    const { positions, indices } = box();
    // x = y lies on the diagonal every face of +-z is split along: two triangles at the same depth.
    const hits = rayHits([0.1, 0.1, 3], [0, 0, -1], positions, indices);
    expect(hits.length).toBeGreaterThanOrEqual(3);
    close(jointOnRay([0.1, 0.1, 3], [0, 0, -1], { shown: positions, rest: positions, indices }).rest, [0.1, 0.1, 0]);
    close(jointOnRay([0.5, 0.5, 3], [0, 0, -1], { shown: positions, rest: positions, indices }).rest, [0.5, 0.5, 0], 9); // a corner
  });

  it('says why no joint is placed: beside the mesh, or no surface behind the one tapped', () => {
    const { positions, indices } = box();
    expect(jointOnRay([3, 3, 3], [0, 0, -1], { shown: positions, rest: positions, indices })).toEqual({ rest: null, reason: 'the tap is not on the mesh' });
    const sheet = { positions: Float64Array.from([0, 0, 0, 1, 0, 0, 0, 1, 0]), indices: Uint32Array.from([0, 1, 2]) };
    expect(jointOnRay([0.2, 0.2, 1], [0, 0, -1], { shown: sheet.positions, rest: sheet.positions, indices: sheet.indices }).reason).toMatch(/open/);
    // Behind the eye counts for nothing.
    expect(rayHits([0.1, 0.3, 0.4], [0, 0, 1], positions, indices)).toHaveLength(1);
  });
});

describe('joints the solver does not place', () => {
  it('are carried by the drawn mesh between the surface points around them on the thinnest axis', () => {
    const rest = box(2, 0.5, 0.5);
    const anchor = anchorPoint([0.3, 0.2, 0.1], rest.positions, rest.indices);
    expect(anchor.s).toBeCloseTo(0.7, 12); // along y (x is 4 long): 0.7 of the way from y = -0.5 to y = 0.5
    close(anchoredPoint(anchor, rest.positions, rest.indices), [0.3, 0.2, 0.1]);
    // The box stretched to twice its size and moved by (1, 0, 0): the point goes with it.
    const shown = rest.positions.map((x, i) => 2 * x + (i % 3 === 0 ? 1 : 0));
    close(anchoredPoint(anchor, shown, rest.indices), [1.6, 0.4, 0.2]);
    expect(anchorPoint([5, 0, 0], rest.positions, rest.indices)).toBe(null); // outside: nothing on one side
  });
});

describe('skeleton state', () => {
  it('joins consecutive joints by bones, continues from a tapped joint and ends a chain on its tip', () => {
    const s = new SkeletonState();
    expect(s.addJoint([-2, 0, 0])).toBe(0);
    s.addJoint([0, 0, 0]);
    s.addJoint([2, 0, 0]);
    expect(s.bones).toEqual([[0, 1], [1, 2]]);
    expect(s.tip).toBe(2);
    s.continueFrom(1); // a branch from the middle joint
    s.addJoint([0, 1, 0]);
    expect(s.bones).toEqual([[0, 1], [1, 2], [1, 3]]);
    s.continueFrom(3); // the tip again: the chain ends
    expect(s.tip).toBe(-1);
    s.addJoint([5, 5, 5]); // a new chain's first joint: no bone yet
    expect(s.bones).toHaveLength(3);
    s.newChain();
    expect(s.tip).toBe(-1);
  });

  it('sends only the joints bones use, renumbered, with the map back; null without bones', () => {
    const s = new SkeletonState();
    expect(s.value()).toEqual({ value: null, map: [] });
    s.addJoint([9, 9, 9]); // lone
    s.newChain();
    s.addJoint([0, 0, 0]);
    s.addJoint([1, 0, 0]);
    expect(s.value()).toEqual({ value: { joints: [[0, 0, 0], [1, 0, 0]], bones: [[0, 1]] }, map: [1, 2] });
  });

  it('deletes the selected bone, or the tip joint with its bones, and the joints left without bones', () => {
    const s = new SkeletonState();
    for (const x of [0, 1, 2, 3]) s.addJoint([x, 0, 0]);
    s.selectBone(1); // [1, 2]
    expect(s.tip).toBe(-1);
    expect(s.deleteSelected()).toBe(true);
    expect(s.bones).toEqual([[0, 1], [2, 3]]);
    expect(s.joints).toHaveLength(4);
    s.selectBone(1);
    s.deleteSelected(); // [2, 3] goes, and joints 2 and 3 with it
    expect(s.joints).toEqual([[0, 0, 0], [1, 0, 0]]);
    s.continueFrom(1);
    s.addJoint([1, 1, 0]);
    s.continueFrom(1);
    expect(s.deleteSelected()).toBe(true); // joint 1 and both its bones; joints 0 and 2 are left alone
    expect(s.bones).toEqual([]);
    expect(s.joints).toEqual([]);
    expect(s.deleteSelected()).toBe(false);
  });

  it('takes a scene\'s skeleton, refusing bones that name no joint', () => {
    const s = new SkeletonState();
    s.fromValue({ joints: [[-2, 0, 0], [0, 0, 0], [2, 0, 0]], bones: [[0, 1], [1, 2]] });
    expect(s.value().value).toEqual({ joints: [[-2, 0, 0], [0, 0, 0], [2, 0, 0]], bones: [[0, 1], [1, 2]] });
    expect(() => s.fromValue({ joints: [[0, 0, 0]], bones: [[0, 1]] })).toThrow(/bone 0 must be two different joint indices below 1/);
    expect(() => s.fromValue({ joints: [[0, 0, NaN]], bones: [] })).toThrow(/joint 0 must be \[x, y, z\]/);
    expect(() => s.addJoint([0, 0])).toThrow(/a joint must be/);
  });
});

describe('screen picking', () => {
  const points = [{ x: 10, y: 10 }, { x: 110, y: 10 }, null];
  it('finds the nearest joint within the radius, else the nearest stick', () => {
    expect(jointNear(points, 14, 12, 12)).toBe(0);
    expect(jointNear(points, 60, 10, 12)).toBe(-1);
    expect(boneNear(points, [[0, 1], [1, 2]], 60, 16, 8)).toBe(0);
    expect(boneNear(points, [[0, 1]], 60, 30, 8)).toBe(-1);
    expect(boneNear(points, [[1, 2]], 110, 10, 8)).toBe(-1); // a joint behind the camera: no stick
  });
});

describe('the bone tool\'s taps', () => {
  // A 400 x 300 view of a box 4 long in x, seen from +z; the joints of a bone along its axis drawn at x = -1, 1.
  const rest = box(2, 0.5, 0.5);
  const camera = new PerspectiveCamera(40, 4 / 3, 0.1, 100);
  camera.position.set(0, 0, 8);
  camera.lookAt(0, 0, 0);
  const canvas = { getBoundingClientRect: () => ({ left: 10, top: 20, width: 400, height: 300 }), addEventListener() {} };
  const view = {
    model: { mesh: rest },
    viewport: { canvas, camera, meshView: { positions: Float32Array.from(rest.positions) } },
    skeletonView: { points: [[-1, 0, 0], [1, 0, 0]], bones: [[0, 1]] },
    gizmo: { hitTest: () => false },
  };
  const tool = new BoneTool(view, { active: () => true, tap: () => {} });
  const screen = (x, y, z) => {
    const p = new Vector3(x, y, z).project(camera);
    return [10 + ((p.x + 1) / 2) * 400, 20 + ((1 - p.y) / 2) * 300];
  };

  it('picks a joint, else a bone, else places a joint midway through the mesh, else lets go', () => {
    expect(tool.at(...screen(1, 0.02, 0))).toEqual({ joint: 1 });
    expect(tool.at(...screen(0, 0.03, 0))).toEqual({ bone: 0 });
    // A point of the front face (z = 0.5): the ray from the eye leaves by the back face (z = -0.5) further out.
    const placed = tool.at(...screen(1.6, 0.3, 0.5));
    const back = 8.5 / 7.5; // the back face's x and y grow by this along the ray from the eye (0, 0, 8)
    close(placed.place.rest, [1.6 * (1 + back) / 2, 0.3 * (1 + back) / 2, 0], 5);
    expect(placed.place.depth).toBeCloseTo(Math.hypot(1.6, 0.3, 7.5) * (back - 1), 5);
    expect(tool.at(...screen(0, 1.5, 0))).toEqual({ empty: true });
    // A finger's radius is larger than a mouse's.
    expect(tool.at(...screen(0, 0.25, 0), 'mouse')).not.toEqual({ bone: 0 });
    expect(tool.at(...screen(0, 0.25, 0), 'touch')).toEqual({ bone: 0 });
  });
});

describe('the sticks', () => {
  it('follow each report in place (no new objects per frame), red where a bone strains, orange in hand', () => {
    const viewport = { scene: new Scene(), meshView: { positions: null, geometry: null }, invalidate() {} };
    const view = new SkeletonView(viewport);
    view.show({ shown: [[-2, 0, 0], [0, 0, 0], [2, 0, 0]], bones: [[0, 1], [1, 2]], tip: 2, selectedBone: -1, map: [0, 1, 2] });
    const meshes = [...view.object.children];
    expect(meshes).toHaveLength(5);
    const bones = [{ lengthError: 0, straightnessError: 1e-3, straightHard: true }, { lengthError: 2e-6, straightnessError: 0, straightHard: true }];
    view.follow({ joints: Float64Array.from([-2, 0, 0, 0, -1, 0, 1, -2, 0]), bones });
    expect(view.object.children).toEqual(meshes);
    expect(view.points[2]).toEqual([1, -2, 0]);
    expect(view.sticks[0].position.toArray()).toEqual([-1, -0.5, 0]);
    expect(view.sticks[0].material.color.getHex()).toBe(0x0f766e);
    expect(view.sticks[1].material.color.getHex()).toBe(0xd62828); // 2e-6 longer than at rest
    expect(view.balls[2].material.color.getHex()).toBe(0xf08a24); // the chain's tip
    view.show({ shown: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]], tip: -1, selectedBone: 0, map: [0, 1] });
    expect(view.object.children).toHaveLength(3);
    expect(view.sticks[0].material.color.getHex()).toBe(0xf08a24); // selected
    view.dispose();
    expect(view.object.children).toHaveLength(0);
  });
});

describe('undo in one timeline with the handle edits', () => {
  // A history and its state as the timeline sees them: `name` edits record the state before, undo and redo swap it.
  const tracked = (timeline, name, log) => {
    const history = new UndoHistory(timeline);
    const t = { state: `${name}0`, history, edit(to) { history.record(t.state); t.state = to; } };
    const travel = (way) => () => { if (!history[way === 'undo' ? 'canUndo' : 'canRedo']) return false; t.state = history[way](t.state); log.push(`${name}:${t.state}`); return true; };
    timeline.join({ history, undo: travel('undo'), redo: travel('redo') });
    return t;
  };

  it('takes back whichever was edited last, and redoes in the same order', () => {
    const timeline = new EditTimeline();
    const log = [];
    const [h, s] = [tracked(timeline, 'H', log), tracked(timeline, 'S', log)];
    h.edit('H1');
    s.edit('S1');
    h.edit('H2');
    for (let k = 0; k < 4; ++k) timeline.undo(); // the fourth finds nothing
    expect(log).toEqual(['H:H1', 'S:S0', 'H:H0']);
    log.length = 0;
    for (let k = 0; k < 4; ++k) timeline.redo();
    expect(log).toEqual(['H:H1', 'S:S1', 'H:H2']);
    expect([timeline.canUndo, timeline.canRedo]).toEqual([true, false]);
  });

  it('forgets every redo at a new edit of any kind: an undone bone does not come back over a later handle edit', () => {
    const timeline = new EditTimeline();
    const log = [];
    const [h, s] = [tracked(timeline, 'H', log), tracked(timeline, 'S', log)];
    s.edit('S1');
    timeline.undo();
    h.edit('H1'); // a new edit after the undo
    expect(timeline.canRedo).toBe(false);
    expect(timeline.redo()).toBe(false);
    expect(s.state).toBe('S0');
    // The other way: a handle edit undone, then a skeleton edit.
    timeline.undo();
    expect(h.state).toBe('H0');
    s.edit('S2');
    expect(timeline.redo()).toBe(false);
    expect(h.state).toBe('H0');
  });

  it('gives the undo to a history whose edit is on its way, and forgets a refused edit', () => {
    const timeline = new EditTimeline();
    const history = new UndoHistory(timeline);
    const handles = new UndoHistory(timeline);
    let busy = false;
    const track = { history, undo: () => true, redo: () => true, busy: () => busy };
    timeline.join(track);
    timeline.join({ history: handles, undo: () => true, redo: () => true });
    history.record('a');
    handles.record('h');
    expect(timeline.first('undo').history).toBe(handles);
    busy = true; // a skeleton edit waits for its workers: it is the newest
    expect(timeline.first('undo')).toBe(track);
    busy = false;
    handles.clear(); // a new model
    expect(timeline.first('undo')).toBe(track);
    history.drop();
    expect(timeline.first('undo')).toBe(null);
  });

  it('does nothing while a gizmo drag is under way: the drag stays one step, and no pose from its middle comes back', () => {
    const timeline = new EditTimeline();
    const handles = new HandleSet(timeline);
    handles.setRest(new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0]));
    handles.setGroups([[0], [1]], [1]);
    const translate = () => handles.groups[1].translate;
    handles.setTransform(1, [0, 0.3, 0], null, true); // a first edit (the API's drag)
    handles.beginTransform(); // the gizmo is pressed
    handles.setTransform(1, [0, 0.5, 0]);
    expect([timeline.undo(), timeline.redo()]).toEqual([false, false]);
    expect(translate()).toEqual([0, 0.5, 0]);
    handles.setTransform(1, [0, 0.7, 0]);
    handles.endTransform(); // released
    expect(timeline.undo()).toBe(true);
    expect(translate()).toEqual([0, 0.3, 0]);
    timeline.undo();
    expect(translate()).toEqual([0, 0, 0]);
    timeline.redo();
    timeline.redo();
    expect(translate()).toEqual([0, 0.7, 0]);
  });
});

const report = {
  joints: [[-2, 0, 0], [0, -0.1, 0], [1.9, -0.5, 0]],
  bones: [{ lengthError: 3e-11, straightnessError: -2e-3, lambda: 0.125, straightHard: true },
    { lengthError: -1e-10, straightnessError: 4e-3, lambda: [-2.5, 0.1], straightHard: false }],
};

describe('the numbers as text', () => {
  it('gives the largest errors and multiplier in the stats, each bone in the step-through and the panel row', () => {
    expect(bonesSummary(report)).toEqual({ count: 2, length: 1e-10, straightness: 4e-3, lambda: 2.5, soft: 1 });
    expect(skeletonStatsLine(report)).toBe('bones 2: length error 1.0e-10   straightness 4.0e-3   |\u03bb| 2.5, 1 straight only softly');
    expect(skeletonStatsLine(null)).toBe('');
    // Under ARAP (kept false) the line says the bones are only measured: no multiplier, no "softly".
    const arap = { ...report, kept: false, bones: report.bones.map((b) => ({ ...b, lambda: 0, straightHard: false })) };
    expect(skeletonStatsLine(arap)).toBe('bones 2: not kept by this method   length error 1.0e-10   straightness 4.0e-3');
    expect(skeletonTraceLines(report)).toEqual([
      'bone 0: multiplier 0.125   length error 3.0e-11   straightness 2.0e-3',
      'bone 1: multiplier -2.5, 0.1   length error 1.0e-10   straightness 4.0e-3 (soft)',
    ]);
    expect(skeletonPanelText(report, { bones: 2, enabled: true })).toBe('len 1.0e-10 str 4.0e-3');
    expect(skeletonPanelText(null, { bones: 0, enabled: true })).toMatch(/bone tool/);
    expect(skeletonPanelText(report, { bones: 2, enabled: false })).toBe('2 bones, not kept');
    expect(skeletonPanelText(null, { bones: 1, enabled: false })).toBe('1 bone, not kept'); // not "1 bones"
    expect(skeletonPanelText(null, { bones: 1, enabled: true })).toBe('1 bone');
  });

  it('reads a report\'s joints flat (the library\'s Float64Array) or one [x, y, z] each', () => {
    expect(reportJoints({ joints: Float64Array.from([1, 2, 3, 4, 5, 6]), bones: [] })).toEqual([[1, 2, 3], [4, 5, 6]]);
    expect(reportJoints(report)).toEqual(report.joints);
    expect(reportJoints(null)).toEqual([]);
  });

  it('adds the bones to a view\'s stats and to a Gauss-Newton step\'s trace', () => {
    const stats = { iterations: 4, merit: 1, energy: 1, lambda: 0, volumeRelError: 0, msPerIteration: 2, state: 'converged', skeleton: report, warnings: [] };
    expect(statsLine(stats, { loaded: true, requestSize: 1 }).numbers.split('\n')[2]).toMatch(/^bones 2: length error/);
    const s = { iteration: 1, merit: 1, energy: 1, laplacianEnergy: 1, positionEnergy: 0, volume: 1, volumeRelError: 0, lambda: 0, step: 0.1, lineSearchTrials: 1 };
    const lines = traceLines({ kind: 'iteration', method: 'subspace', stats: s, result: { converged: false }, skeleton: report });
    expect(lines.slice(-2)).toEqual(skeletonTraceLines(report));
    // With straightnessWeight the energy has a third part, and the trace's sum names it.
    const stiff = traceLines({ kind: 'iteration', method: 'subspace', stats: { ...s, energy: 1.2, straightnessEnergy: 0.2 }, result: { converged: false } });
    expect(stiff.join('\n')).toMatch(/energy E = Laplacian 1 \+ position 0 \+ bone straightness 0\.2 = 1\.2/);
  });
});

describe('saved scenes', () => {
  it('write the skeleton the solvers keep at the top level, each joint on one line', () => {
    const skeleton = { joints: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]] };
    const scene = savedScene({ name: 'bar', source: { example: 'bar' } }, [], { method: 'subspace' }, null, skeleton);
    expect(scene.skeleton).toEqual(skeleton);
    expect(sceneText(scene)).toContain('[-2, 0, 0]');
    expect(savedScene({ name: 'bar', source: { example: 'bar' } }, [], {})).not.toHaveProperty('skeleton');
  });

  it('travel in a link to a pose as they are', async () => {
    const scene = savedScene({ name: 'bar', source: { example: 'bar' } }, [{ vertices: [0, 1, 2] }], { method: 'subspace' }, null,
      { joints: [[-2, 0.125, 0], [0, 0, 0], [1.5, 0, 1e-3]], bones: [[0, 1], [1, 2]] });
    expect(await decodePose(await encodePose(scene))).toEqual(scene);
  });
});

/**
 * A view with a stand-in worker: setSkeleton answers with a report, or refuses joints with |x| > 2.5, and with |y| > 2.5
 * as the solver words a bone through the air (its message begins with "skeleton:").
 */
function standInView(log) {
  return {
    session: {
      client: {},
      async request(type, { skeleton }) {
        log.push(skeleton);
        if (skeleton?.joints.some((p) => Math.abs(p[0]) > 2.5)) throw Object.assign(new Error('joint 1 is outside the mesh'), { code: 'invalid_skeleton' });
        if (skeleton?.joints.some((p) => Math.abs(p[1]) > 2.5)) {
          throw Object.assign(new Error('skeleton: bone 1 (from joint 1 to joint 2) leaves the mesh between its joints'), { code: 'invalid_skeleton' });
        }
        return { skeleton: skeleton && { joints: skeleton.joints, bones: skeleton.bones.map(() => ({ lengthError: 0, straightnessError: 0, lambda: 0, straightHard: true })) } };
      },
      partsChanged() {},
    },
    skeletonView: { report: null, bones: [], show(s) { this.bones = s.bones; }, follow(r) { this.report = r; } },
  };
}

describe('Skeleton (stand-in workers)', () => {
  const make = () => {
    const log = [];
    const views = [standInView(log), standInView(log)];
    const banner = { text: '', show(text) { this.text = text; } };
    const events = [];
    const skeleton = new Skeleton({ views: { list: views }, banner, dispatch: (e) => events.push(e) });
    return { skeleton, log, views, banner, events };
  };
  // The skeleton and the handle groups on one timeline.
  const withHandles = () => {
    const timeline = new EditTimeline();
    const handles = new HandleSet(timeline);
    handles.setRest(new Float64Array(18));
    handles.setGroups([[0], [5]], [1]);
    const skeleton = new Skeleton({ views: { list: [standInView([])] }, banner: { show() {} }, timeline, dispatch() {} });
    return { skeleton, timeline, handles };
  };

  it('sends every edit to every view, each view following its report, and undoes and redoes them', async () => {
    const { skeleton, log, views, events } = make();
    await skeleton.addJoint([-2, 0, 0]);
    expect(log).toEqual([]); // one joint, no bone: nothing to keep yet
    await skeleton.addJoint([0, 0, 0]);
    expect(log).toEqual([{ joints: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]] }, { joints: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]] }]);
    expect(views[1].skeletonView.report.bones).toHaveLength(1);
    expect(skeleton.sceneSpec).toEqual({ joints: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]] });
    expect(events.at(-1)).toMatchObject({ type: 'skeleton', joints: 2, bones: 1, tip: 1 });
    expect(skeleton.undo()).toBe(true);
    expect(skeleton.bones).toBe(0);
    expect(skeleton.redo()).toBe(true);
    expect(skeleton.bones).toBe(1);
    await skeleton.setEnabled(false);
    expect(log.at(-1)).toBe(null);
    expect(skeleton.sceneSpec).toBe(null);
  });

  it('a scene\'s skeleton is kept even after "use bones" was unticked (the skeleton lesson\'s restart)', async () => {
    const { skeleton, log } = make();
    const two = { joints: [[-2, 0, 0], [0, 0, 0], [2, 0, 0]], bones: [[0, 1], [1, 2]] };
    await skeleton.use(two);
    await skeleton.setEnabled(false);
    expect(log.at(-1)).toBe(null);
    await skeleton.use(two);
    expect(skeleton.enabled).toBe(true);
    expect(log.at(-1)).toEqual(two);
  });

  it('an undo and a redo at once leave every worker with the redone skeleton', async () => {
    const { skeleton, log, views } = make();
    const two = { joints: [[-2, 0, 0], [0, 0, 0], [2, 0, 0]], bones: [[0, 1], [1, 2]] };
    await skeleton.use(two);
    log.length = 0;
    expect(skeleton.undo()).toBe(true); // its send is still on its way when the redo comes
    expect(skeleton.redo()).toBe(true);
    await new Promise((resolve) => setTimeout(resolve, 0));
    expect(log.at(-1)).toEqual(two);
    for (const view of views) expect(view.skeletonView.report.bones).toHaveLength(2);
  });

  it('an undo pressed while a refused edit waits for its answer takes back only that edit, once', async () => {
    const { skeleton, banner } = make();
    await skeleton.use({ joints: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]] });
    skeleton.continueFrom(1);
    const refused = skeleton.addJoint([3, 0, 0]);
    expect(skeleton.undo()).toBe(true); // the joint's edit is the last: the undo is the skeleton's
    await expect(refused).rejects.toThrow(/outside the mesh/);
    await new Promise((resolve) => setTimeout(resolve, 0));
    expect(banner.text).toBe('skeleton: joint 1 is outside the mesh');
    expect(skeleton.sceneSpec).toEqual({ joints: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]] });
    expect(skeleton.history.undoStack).toHaveLength(1); // the use() only
    expect(skeleton.canRedo).toBe(false); // the refused joint cannot come back
  });

  it('takes back an edit a worker refuses, names it in the banner, and keeps no undo step for it', async () => {
    const { skeleton, banner } = make();
    await skeleton.use({ joints: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]] });
    skeleton.continueFrom(1);
    await expect(skeleton.addJoint([3, 0, 0])).rejects.toThrow(/outside the mesh/);
    expect(banner.text).toBe('skeleton: joint 1 is outside the mesh');
    // A refusal the solver words itself says it is the skeleton's once (the banner read "skeleton: skeleton: ...").
    await expect(skeleton.addJoint([1, 3, 0])).rejects.toThrow(/leaves the mesh/);
    expect(banner.text).toBe('skeleton: bone 1 (from joint 1 to joint 2) leaves the mesh between its joints');
    expect(skeleton.bones).toBe(1);
    expect(skeleton.history.undoStack).toHaveLength(1); // the use() only
  });

  it('keeps the handles\' redo over a joint the workers refuse (an edit that never happened)', async () => {
    const { skeleton, timeline, handles } = withHandles();
    await skeleton.use({ joints: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]] });
    handles.setTransform(1, [0, 1, 0], null, true);
    timeline.undo();
    skeleton.continueFrom(1);
    await expect(skeleton.addJoint([3, 0, 0])).rejects.toThrow(/outside the mesh/);
    expect(timeline.canRedo).toBe(true);
    expect(timeline.redo()).toBe(true);
    expect(handles.groups[1].translate).toEqual([0, 1, 0]);
  });

  it('gives a redo pressed while a skeleton edit waits to the handles, when that edit changes nothing', async () => {
    const { skeleton, timeline, handles } = withHandles();
    handles.setTransform(1, [0, 1, 0], null, true);
    timeline.undo();
    const cleared = skeleton.clear(); // no skeleton to clear: no step, but busy until its turn comes
    expect(timeline.redo()).toBe(true);
    await cleared;
    expect(handles.groups[1].translate).toEqual([0, 1, 0]);
  });

  it('takes edits one at a time: a refused joint tapped before the last answer came takes back only itself', async () => {
    const { skeleton } = make();
    await skeleton.addJoint([-2, 0, 0]);
    const edits = [skeleton.addJoint([0, 0, 0]), skeleton.addJoint([3, 0, 0]), skeleton.addJoint([2, 0, 0])];
    const outcomes = await Promise.allSettled(edits);
    expect(outcomes.map((o) => o.status)).toEqual(['fulfilled', 'rejected', 'fulfilled']);
    expect(skeleton.sceneSpec).toEqual({ joints: [[-2, 0, 0], [0, 0, 0], [2, 0, 0]], bones: [[0, 1], [1, 2]] });
    expect(skeleton.history.undoStack).toHaveLength(3);
  });

  it('forgets the bones for a new mesh and sends them again for the same one', async () => {
    const { skeleton, log } = make();
    await skeleton.use({ joints: [[-2, 0, 0], [0, 0, 0]], bones: [[0, 1]] });
    log.length = 0;
    await skeleton.onLoad({}, true);
    expect(log).toHaveLength(2); // new workers get them
    await skeleton.onLoad({}, false);
    expect(skeleton.joints).toBe(0);
    expect(skeleton.canUndo).toBe(false);
  });
});
