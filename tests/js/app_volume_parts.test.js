// The app's page-free parts of the spectral basis and the volume parts: the painter's parts and colours, the
// basis settings, the saved scene's "subspace" and "volumeParts", the stats row, and VolumeParts against a
// stand-in worker (a scene's parts painted, strokes and "default parts" in the one undo timeline).
import { describe, expect, it } from 'vitest';
import { PartsPainter, PART_COLORS } from '../../web/app/parts/parts_painter.js';
import { AppSettings, touchesSolver } from '../../web/app/settings.js';
import { savedScene } from '../../web/app/loading/saved_scene.js';
import { panelStats } from '../../web/app/stats_format.js';
import { InputError } from '../../web/lib/errors.js';
import { parseScene } from '../../web/lib/scene.js';
import { VolumeParts, partCount } from '../../web/app/parts/volume_parts.js';
import { EditTimeline } from '../../web/app/interaction/edit_timeline.js';
import { HandleSet } from '../../web/app/interaction/handle_set.js';

describe('PartsPainter', () => {
  it('paints vertex parts and describes them as vertex lists; unpainted vertices are the rest', () => {
    const painter = new PartsPainter();
    painter.reset(6);
    expect(painter.description()).toBeNull();
    expect(painter.colors()).toBeNull();
    painter.current = 2;
    painter.paint([0, 1]);
    painter.current = 0;
    painter.paint([4, 5]);
    painter.paint([5], 'remove');
    expect(painter.description()).toEqual({ vertices: [[4], [0, 1]] });
    const colors = painter.colors();
    expect(Array.from(colors.slice(0, 3))).toEqual(PART_COLORS[2].map(Math.fround));
    expect(colors).toHaveLength(18);
  });

  it('takes a partition per triangle (auto parts) as vertex parts', () => {
    const painter = new PartsPainter();
    painter.reset(4);
    painter.fromTriangles(new Int32Array([0, 1]), new Uint32Array([0, 1, 2, 1, 3, 2]));
    expect(Array.from(painter.vertexPart)).toEqual([0, 1, 1, 1]);
  });
});

describe('basis and parts settings', () => {
  it('checks the basis, its modes and the auto parts; none of them concerns the solvers', () => {
    const settings = new AppSettings({ basis: 'spectral', spectralModes: 60 });
    expect(settings.values).toMatchObject({ basis: 'spectral', spectralModes: 60, autoParts: 6 });
    expect(() => settings.update({ basis: 'wavelets' })).toThrow(InputError);
    expect(() => settings.update({ spectralModes: 0 })).toThrow(/spectralModes must be an integer from 1 to 300/);
    expect(() => settings.update({ autoParts: 1 })).toThrow(/autoParts must be an integer from 2 to 16/);
    expect(touchesSolver({ basis: 'cage', spectralModes: 10, autoParts: 3 })).toBe(false);
    expect(settings.solverOptions('subspace')).not.toHaveProperty('basis');
  });

  it('saves the spectral basis and the parts in the scene, which parses back', () => {
    const model = { name: 'bar', basis: 'spectral', basisSize: 44, source: { example: 'bar' } };
    const scene = savedScene(model, [], { method: 'subspace' }, { auto: 5 });
    expect(scene).toMatchObject({ example: 'bar', subspace: { basis: 'spectral', modes: 40 }, volumeParts: { auto: 5 } });
    expect(parseScene(scene)).toMatchObject({ subspace: { basis: 'spectral', modes: 40 }, volumeParts: { kind: 'auto', parts: 5 } });
    expect(savedScene({ ...model, basis: 'cage' }, [], {})).not.toHaveProperty('subspace');
  });

  it('shows the parts in the stats: how many and the largest change, or the global volume', () => {
    const base = { state: 'converged', stopReason: '', merit: 1, volumeRelError: 0, iterations: 3, msPerIteration: 1, fps: 60 };
    expect(panelStats({ ...base, partVolumeChange: null }).parts).toBe('global volume');
    expect(panelStats({ ...base, partVolumeChange: [1e-15, -3e-15, 2e-16] }).parts).toBe('3, max 3.0e-13 %');
  });
});

// A view whose worker answers setVolumeParts with a partition of `triangles` triangles (one part per list and the
// rest, dealt round; none for the default parts), logging what it was sent. `worker.delay`: the answer waits that many
// ms; `worker.refuse`: the next request is refused.
function standInViews(log, triangles = 4, worker = {}) {
  const view = {
    session: {
      request: async (type, { parts }) => {
        log.push(parts);
        if (worker.delay) await new Promise((resolve) => setTimeout(resolve, worker.delay));
        if (worker.refuse) {
          worker.refuse = false;
          throw new Error('volumeParts: refused');
        }
        const lists = parts?.vertices ?? parts?.lists;
        return { parts: lists ? Int32Array.from({ length: triangles }, (_, f) => f % (lists.length + 1)) : new Int32Array(0) };
      },
      partsChanged() {},
    },
    colors: null,
    showParts(colors) { this.colors = colors; },
  };
  return { list: [view] };
}

describe('VolumeParts: the paint, the kept parts and their undo', () => {
  // Six vertices, four triangles.
  const make = (timeline = new EditTimeline(), worker = {}) => {
    const log = [];
    const banner = { text: '', show(text) { this.text = text; } };
    const parts = new VolumeParts({ views: standInViews(log, 4, worker), banner, timeline });
    parts.onLoad({ mesh: { positions: new Float64Array(18), indices: new Uint32Array([0, 1, 2, 2, 3, 4, 3, 4, 5, 0, 2, 4]) }, volumePartCount: 1 }, false);
    return { parts, log, banner, timeline, worker };
  };
  const painted = (parts) => Array.from(parts.painter.vertexPart);
  // The parts on one timeline with the handles, a moving group moved by (0, 1, 0).
  const withMovedHandle = () => {
    const timeline = new EditTimeline();
    const handles = new HandleSet(timeline);
    handles.setRest(new Float64Array(18));
    handles.setGroups([[0], [5]], [1]);
    handles.setTransform(1, [0, 1, 0], null, true);
    return { ...make(timeline), handles };
  };

  it('paints a saved scene\'s parts (list k as part k), so that a further stroke adds to them', async () => {
    const { parts, log } = make();
    await parts.use({ kind: 'vertices', lists: [[0, 1], [4]] }); // a scene's, as parseScene gives it
    expect(painted(parts)).toEqual([0, 0, -1, -1, 1, -1]);
    expect(parts.unkeptPaint).toBe(false);
    parts.setCurrent(5);
    parts.paint([2]);
    expect(parts.unkeptPaint).toBe(true); // a saved scene would not hold it
    expect(await parts.apply()).toBe(4);
    expect(log.at(-1)).toEqual({ vertices: [[0, 1], [4], [2]] }); // the scene's parts and the new one
    await parts.use({ vertices: [[5]] }); // a script's lists: painted the same way
    expect(painted(parts)).toEqual([-1, -1, -1, -1, -1, 0]);
  });

  it('counts the parts of a partition of 300k triangles (Math.max(...parts) overflowed the stack)', async () => {
    const log = [];
    const parts = new VolumeParts({ views: standInViews(log, 300000), banner: { show() {} } });
    parts.onLoad({ mesh: { positions: new Float64Array(18), indices: new Uint32Array([0, 1, 2]) }, volumePartCount: 1 }, false);
    expect(await parts.use({ vertices: [[0], [1], [2]] })).toBe(4);
    expect(partCount(new Int32Array(0))).toBe(0);
  });

  it('keeps the painter\'s part numbers when the paint is kept', async () => {
    const { parts } = make();
    parts.setCurrent(3);
    parts.paint([1, 2]);
    await parts.apply();
    expect(painted(parts)).toEqual([-1, 3, 3, -1, -1, -1]);
  });

  it('makes a stroke one undo step in the timeline, a cancelled one none, and redoes it', () => {
    const { parts, timeline } = make();
    parts.saveStroke();
    parts.paint([0]);
    parts.paint([1, 2]);
    parts.endStroke();
    parts.paint([0]); // a tap on paint already there: no step
    parts.paint([5]); // a tap outside a stroke: a step of its own
    expect(parts.history.undoStack).toHaveLength(2);
    const saved = parts.saveStroke();
    parts.paint([3]);
    parts.restoreStroke(saved); // a second finger: the stroke never happened
    expect(parts.history.undoStack).toHaveLength(2);
    expect(timeline.undo()).toBe(true);
    expect(painted(parts)).toEqual([0, 0, 0, -1, -1, -1]);
    expect(timeline.undo()).toBe(true);
    expect(painted(parts)).toEqual([-1, -1, -1, -1, -1, -1]);
    expect(timeline.undo()).toBe(false);
    expect(timeline.redo()).toBe(true);
    expect(painted(parts)).toEqual([0, 0, 0, -1, -1, -1]);
  });

  it('keeps every redo of the timeline over a stroke cancelled by a second finger (an edit that never happened)', () => {
    const { parts, handles, timeline } = withMovedHandle();
    timeline.undo(); // the handle move
    expect(timeline.canRedo).toBe(true);
    const saved = parts.saveStroke();
    parts.paint([3]);
    parts.restoreStroke(saved);
    expect(timeline.canRedo).toBe(true);
    expect(timeline.redo()).toBe(true);
    expect(handles.groups[1].translate).toEqual([0, 1, 0]);
    // A stroke that is made does end it.
    timeline.undo();
    parts.saveStroke();
    parts.paint([3]);
    parts.endStroke();
    expect(timeline.canRedo).toBe(false);
  });

  it('takes back "default parts": the paint and the parts the solvers kept come back', async () => {
    const { parts, log, timeline } = make();
    parts.paint([0, 1]);
    await parts.apply();
    await parts.clear();
    expect(painted(parts)).toEqual([-1, -1, -1, -1, -1, -1]);
    expect(log.at(-1)).toBe(null);
    expect(timeline.undo()).toBe(true);
    await new Promise((resolve) => setTimeout(resolve, 0));
    expect(painted(parts)).toEqual([0, 0, -1, -1, -1, -1]);
    expect(log.at(-1)).toEqual({ vertices: [[0, 1]] }); // the solvers keep them again
    expect(parts.count).toBe(2);
  });

  it('keeps the paint that was sent, not a stroke made while the workers answer, and undoes that stroke first', async () => {
    const { parts, log, timeline } = make(new EditTimeline(), { delay: 5 });
    parts.paint([0]);
    const kept = parts.apply();
    parts.setCurrent(1);
    parts.paint([5]); // while "keep painted parts" waits for the workers
    expect(await kept).toBe(2);
    expect(log.at(-1)).toEqual({ vertices: [[0]] });
    expect(painted(parts)).toEqual([0, -1, -1, -1, -1, 1]);
    expect(parts.unkeptPaint).toBe(true); // the stroke on 5 is not kept, and "save scene" says so
    expect(parts.sceneSpec).toEqual({ vertices: [[0]] });
    timeline.undo(); // the stroke on 5, made last
    expect(painted(parts)).toEqual([0, -1, -1, -1, -1, -1]);
    expect(parts.sceneSpec).toEqual({ vertices: [[0]] });
    timeline.undo(); // the kept parts
    await new Promise((resolve) => setTimeout(resolve, 10));
    expect(parts.sceneSpec).toBe(null);
    expect(painted(parts)).toEqual([0, -1, -1, -1, -1, -1]);
    timeline.redo();
    await new Promise((resolve) => setTimeout(resolve, 10));
    expect(parts.sceneSpec).toEqual({ vertices: [[0]] });
    timeline.redo();
    expect(painted(parts)).toEqual([0, -1, -1, -1, -1, 1]);
  });

  it('waits for the workers before an undo of kept parts, and drops a refused change without ending the redo', async () => {
    const { parts, timeline, worker, banner } = make(new EditTimeline(), { delay: 5 });
    parts.paint([0, 1]);
    await parts.apply();
    parts.paint([2]);
    timeline.undo(); // the stroke on 2: a redo to keep
    worker.refuse = true;
    await expect(parts.apply()).rejects.toThrow(/refused/);
    expect(banner.text).toMatch(/refused/);
    expect(parts.history.undoStack).toHaveLength(2); // the first stroke and the kept parts
    expect(timeline.canRedo).toBe(true);
    const auto = parts.auto(2);
    parts.paint([4]); // the answer replaces the paint: the brush waits
    expect(timeline.undo()).toBe(true); // meant for the auto parts: taken once they are kept
    await auto;
    await new Promise((resolve) => setTimeout(resolve, 10));
    expect(parts.sceneSpec).toEqual({ vertices: [[0, 1]] });
    expect(painted(parts)).toEqual([0, 0, -1, -1, -1, -1]);
  });

  it('describes the parts the solvers keep when an undo\'s parts are refused', async () => {
    const { parts, timeline, worker, banner } = make();
    parts.paint([0, 1]);
    await parts.apply();
    await parts.clear();
    worker.refuse = true;
    timeline.undo();
    await new Promise((resolve) => setTimeout(resolve, 0));
    expect(banner.text).toMatch(/refused/);
    expect(parts.sceneSpec).toBe(null); // the solvers still keep the default parts
    expect(parts.count).toBe(0);
  });

  it('shares the timeline with the handles: Ctrl+Z after a stroke takes back the stroke, not an earlier handle edit', () => {
    const { parts, handles, timeline } = withMovedHandle();
    parts.saveStroke();
    parts.paint([2, 3]);
    parts.endStroke();
    timeline.undo();
    expect(painted(parts)).toEqual([-1, -1, -1, -1, -1, -1]);
    expect(handles.groups[1].translate).toEqual([0, 1, 0]);
    timeline.undo();
    expect(handles.groups[1].translate).toEqual([0, 0, 0]);
  });

  it('starts a new mesh without paint or undo steps, and a scene with its own model without a step back', async () => {
    const { parts } = make();
    parts.paint([0]);
    await parts.use({ vertices: [[1]] }, { freshHistory: true });
    expect(parts.history.undoStack).toHaveLength(0);
    parts.onLoad({ mesh: { positions: new Float64Array(9), indices: new Uint32Array([0, 1, 2]) }, volumePartCount: 1 }, false);
    expect(painted(parts)).toEqual([-1, -1, -1]);
    expect(parts.history.canUndo).toBe(false);
  });
});
