// A pose in a link (web/app/loading/pose_link.js; issue 31, item 4): vertex runs both ways, a scene through
// ?pose= and back unchanged (and still a scene the parser takes), the text short for runs of neighbouring
// vertices, and links that were cut short or changed refused with a message that says so.
import { describe, expect, it } from 'vitest';
import { decodePose, encodePose, fromRuns, toRuns } from '../../web/app/loading/pose_link.js';
import { parseScene } from '../../web/lib/scene.js';
import { InputError } from '../../web/lib/errors.js';

const range = (a, b) => Array.from({ length: b - a }, (_, i) => a + i);

describe('vertex runs', () => {
  it('writes neighbouring numbers as runs, in the list order, and reads them back', () => {
    expect(toRuns([0, 1, 2, 3, 7, 9, 10])).toBe('0-3,7,9-10');
    expect(toRuns([5, 4, 3])).toBe('5,4,3');
    for (const list of [[0], [3, 4], range(0, 1000), [10, 2, 3, 4, 99, 100, 7]]) expect(fromRuns(toRuns(list))).toEqual(list);
  });

  it('refuses text that is no list of runs', () => {
    for (const bad of ['', '1-', 'a', '3-1', '1,,2', '-1', 7]) expect(() => fromRuns(bad)).toThrow(InputError);
  });
});

describe('encodePose / decodePose', () => {
  const scene = {
    example: 'bar',
    handles: [{ vertices: range(0, 300) }, { vertices: [...range(4700, 5042)], translate: [0.1, -0.25, 1e-17],
      rotate: { axis: [0, 0, 1], angle: 0.6, center: [1, 0, 0] } }, { vertices: [307, 309] }],
    solver: { method: 'subspace', jacobian: 'exact', positionWeight: 2.5, volume: true },
    subspace: { basis: 'spectral', modes: 40 },
    volumeParts: { vertices: [range(0, 10), [20, 30, 40, 50]] },
    view: { compare: ['subspace', 'arap'], direction: [1, -0.3, -0.5], paused: true },
  };

  it('gives back the same scene, one the scene parser takes', async () => {
    const text = await encodePose(scene);
    expect(text).toMatch(/^1\.[\w-]+$/);
    const back = await decodePose(text);
    expect(back).toEqual(scene);
    expect(() => parseScene(back)).not.toThrow();
  });

  it('is short for runs of neighbouring vertices: 642 handle vertices in about a hundred characters', async () => {
    const text = await encodePose({ example: 'bar', handles: scene.handles.slice(0, 2) });
    expect(text.length).toBeLessThan(200);
  });

  it('says when a link was cut short or changed', async () => {
    const text = await encodePose(scene);
    for (const bad of [text.slice(0, 20), `2.${text.slice(2)}`, '1.', 'nonsense', `${text.slice(0, -3)}!!!`]) {
      const error = await decodePose(bad).then(() => null, (e) => e);
      expect(error, bad).toBeInstanceOf(InputError);
      expect(error.message).toMatch(/^pose: this link's pose (cannot be read|is not one the app reads)/);
    }
    const notAScene = await encodePose([1, 2, 3]);
    await expect(decodePose(notAScene)).rejects.toThrow('pose: this link holds no scene');
  });
});
