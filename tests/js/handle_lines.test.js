// Handle lines, the projection constraint (web/lib/handle_lines.js, Deformer.setHandleLines): a group held only
// across a view's lines, its depth left to the energy. Checked through the library, scenes, the worker's protocol
// and the CLI, on the built-in bar (a 5k-vertex capsule in a 28-vertex cage).
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Vector3 } from 'three';
import {
  Deformer, InputError, checkHandleLine, handleLineWarnings, handleTargets, lineOfCamera, loadSolver, makeExample, parseScene,
  parseSceneHandles, writeObj,
} from 'subspace-deform';
import { HandleSet } from '../../web/app/interaction/handle_set.js';
import { barEnds, endTargets } from './support/bar_ends.js';
import { thrown } from './support/thrown.js';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
let solver, bar, ends;

beforeAll(async () => {
  solver = await loadSolver();
  bar = makeExample(solver, 'bar');
  ends = barEnds(bar.mesh);
});

// The right end pulled down and towards the viewer on +z (which a line along z does not see).
const PULL = [0, -0.8, 0.6];

describe('checkHandleLine', () => {
  it('accepts along, from and null, and copies the vector', () => {
    const along = [0, 0, -1];
    const line = checkHandleLine({ along }, 'x');
    along[2] = 5;
    expect(line).toEqual({ along: [0, 0, -1] });
    expect(checkHandleLine({ from: [1, 2, 3] }, 'x')).toEqual({ from: [1, 2, 3] });
    expect(checkHandleLine(null, 'x')).toBeNull();
  });

  it('names what is wrong', () => {
    for (const [line, message] of [
      [{ along: [0, 0, 0] }, /x\.along must not be zero/],
      [{ along: [0, NaN, 1] }, /x\.along must be an array of 3 finite numbers/],
      [{ from: [1, 2] }, /x\.from must be an array of 3 finite numbers/],
      [{ along: [0, 0, 1], from: [0, 0, 5] }, /exactly one of "along" .* or "from"/],
      [{ towards: [0, 0, 1] }, /exactly one of "along"/],
      [[0, 0, 1], /x must be \{ along/],
      ['z', /x must be \{ along/],
    ]) {
      const error = thrown(() => checkHandleLine(line, 'x'));
      expect(error).toBeInstanceOf(InputError);
      expect(error.message).toMatch(message);
    }
  });

  it('takes a camera\'s line: its direction when orthographic, its eye when perspective', () => {
    const ortho = { isOrthographicCamera: true, position: { x: 0, y: 0, z: 9 }, getWorldDirection: (v) => v.set(0, 0, -1) };
    expect(lineOfCamera(ortho, Vector3)).toEqual({ along: [0, 0, -1] });
    const perspective = { position: { x: 1, y: 2, z: 9 }, getWorldDirection: (v) => v.set(0, 0, -1) };
    expect(lineOfCamera(perspective, Vector3)).toEqual({ from: [1, 2, 9] });
  });
});

describe('Deformer.setHandleLines', () => {
  let d;
  beforeAll(() => {
    d = Deformer.create(solver, bar.mesh, bar.cage);
    d.setHandles([ends.left, ends.right]);
  });
  afterAll(() => d.dispose());

  // The handle term is soft: freeing the depth moves the balance between it and the Laplacian term a little either
  // way (measured 0.97-1.03 of the point target's distance on this bar), while the energy always drops.
  it('holds the group on its lines about as well as a point target (within 5%), with less energy, keeping the volume', () => {
    d.reset();
    d.setTargets(endTargets(bar.mesh, [ends.left, ends.right], PULL));
    const point = d.solve();
    expect(point.converged).toBe(true);
    const pointDistance = Math.max(...d.handleDistances()), pointEnergy = point.iterations.at(-1).energy;
    d.setHandleLines([null, { along: [0, 0, -2] }]);
    const line = d.solve();
    expect(line.converged).toBe(true);
    const last = line.iterations.at(-1);
    expect(Math.max(...d.handleDistances())).toBeLessThanOrEqual(pointDistance * 1.05);
    expect(last.energy).toBeLessThan(0.9 * pointEnergy); // the depth it was asked for cost energy
    expect(Math.abs(last.volumeRelError)).toBeLessThanOrEqual(1e-9);
    d.setHandleLines(null); // point targets again
  });

  it('gives the same shape whatever depth the targets have on their lines', () => {
    d.setHandleLines([null, { from: [0.5, 0, 12] }]);
    d.reset();
    const targets = endTargets(bar.mesh, [ends.left, ends.right], PULL);
    d.setTargets(targets);
    d.setHandleLines([null, { from: [0.5, 0, 12] }]);
    expect(d.solve().converged).toBe(true);
    const first = d.positions();
    const slid = Float64Array.from(targets);
    for (let r = ends.left.length; r < slid.length / 3; ++r) {
      const t = slid.subarray(3 * r, 3 * r + 3), eye = [0.5, 0, 12];
      const dir = [t[0] - eye[0], t[1] - eye[1], t[2] - eye[2]], length = Math.hypot(...dir);
      for (let a = 0; a < 3; ++a) t[a] += (0.7 * dir[a]) / length;
    }
    d.reset();
    d.setTargets(slid);
    expect(d.solve().converged).toBe(true);
    const second = d.positions();
    let worst = 0;
    for (let i = 0; i < first.length; ++i) worst = Math.max(worst, Math.abs(first[i] - second[i]));
    expect(worst).toBeLessThan(1e-4);
    d.setHandleLines(null);
  });

  it('refuses bad lines with named errors and keeps the old ones', () => {
    d.setHandleLines([null, { along: [0, 0, 1] }]);
    expect(thrown(() => d.setHandleLines([null])).message).toMatch(/1 lines for 2 handle groups/);
    expect(thrown(() => d.setHandleLines([null, { along: [0, 0, 0] }])).message).toMatch(/lines\[1\]\.along must not be zero/);
    expect(thrown(() => d.setHandleLines('along z')).message).toMatch(/lines must be an array/);
    d.setHandles([ends.left, ends.right]); // a new handle set clears them
    d.setHandleLines(null);
  });
});

describe('scenes and the CLI', () => {
  let dir;
  beforeAll(() => {
    dir = mkdtempSync(join(tmpdir(), 'sd-lines-'));
    writeFileSync(join(dir, 'bar.obj'), writeObj(solver, bar.mesh));
    writeFileSync(join(dir, 'bar_cage.obj'), writeObj(solver, bar.cage));
  });
  afterAll(() => rmSync(dir, { recursive: true, force: true }));

  const scene = (line, method = 'subspace') => ({
    mesh: 'bar.obj', cage: 'bar_cage.obj', solver: { method },
    handles: [{ vertices: ends.left }, { vertices: ends.right, translate: PULL, ...line }],
  });

  it('parses "along" and "from" into each handle\'s line, and refuses both at once', () => {
    const parsed = parseScene(scene({ along: [0, 0, -1] }));
    expect(parsed.handles.map((h) => h.line)).toEqual([null, { along: [0, 0, -1] }]);
    expect(handleTargets(bar.mesh.positions, parsed.handles).lines).toEqual([null, { along: [0, 0, -1] }]);
    expect(thrown(() => parseScene(scene({ along: [0, 0, 1], from: [0, 0, 9] }))).message)
      .toMatch(/scene: handles\[1\] needs at most one of "along" or "from"/);
    expect(thrown(() => parseScene(scene({ from: [0, 0] }))).message).toMatch(/scene: handles\[1\]\.from must be an array of 3/);
  });

  // The CLI holds a fixed group on its "along" as well (the bar's scene differs with and without it), so the app's
  // saved scene must keep it there too.
  it('the app saves every group\'s line, a fixed group\'s as well as a moving one\'s', () => {
    const handles = new HandleSet();
    handles.setRest(new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]));
    const lines = [{ along: [0, 0, 1] }, { from: [0, 0, 10] }];
    handles.fromScene(parseSceneHandles([{ vertices: [0], ...lines[0] }, { vertices: [1], translate: [0, 0, 0.5], ...lines[1] }]));
    const saved = handles.toScene();
    expect(saved[0]).toEqual({ vertices: [0], along: [0, 0, 1] });
    expect(saved[0]).not.toHaveProperty('translate'); // still a fixed group when read back
    expect(parseSceneHandles(saved).map((h) => h.line)).toEqual(lines);
  });

  it('deform solves with the lines and reports each group\'s distance from them', () => {
    const report = (name, line, method) => {
      writeFileSync(join(dir, `${name}.json`), JSON.stringify(scene(line, method)));
      const r = spawnSync(process.execPath, [cli, 'deform', join(dir, `${name}.json`), '--report', join(dir, `${name}_r.json`)],
        { encoding: 'utf8', timeout: 120000 });
      expect(r.stderr).toBe('');
      expect(r.status).toBe(0);
      return JSON.parse(readFileSync(join(dir, `${name}_r.json`), 'utf8'));
    };
    const point = report('point', {});
    const line = report('line', { from: [0, 0, 10] });
    expect(line.handleLines).toEqual([null, { from: [0, 0, 10] }]);
    expect(line.handleDistances).toHaveLength(2);
    expect(line.handleMaxError).toBeLessThanOrEqual(point.handleMaxError * 1.05);
    expect(line.energy).toBeLessThan(point.energy);
    expect(line.warnings.map((w) => w.code)).not.toContain('handle_lines_ignored');
    const arap = report('arap', { from: [0, 0, 10] }, 'arap');
    expect(arap.warnings.map((w) => w.code)).toContain('handle_lines_ignored');
    // In the words the app's ARAP view shows (its stats' warnings come from the same function).
    expect(arap.warnings).toContainEqual(handleLineWarnings('arap', [null, { from: [0, 0, 10] }])[0]);
    expect(handleLineWarnings('subspace', [null, { from: [0, 0, 10] }])).toEqual([]);
    expect(handleLineWarnings('arap', [null, null])).toEqual([]);
  });
});
