// A model of two components with handles on one, deformed with the spectral basis in the app (docs/method.md
// section 5.3): the other component stays where it is, the solve converges, and no banner follows. Before, the
// app reported "converged" with the other ellipsoid 34 units away, or showed an unrelated banner.
import assert from 'node:assert/strict';
import { ellipsoidObj } from './geometry.mjs';
import { appReady } from './app_probe.mjs';

// Two ellipsoids (2 x 0.6 x 0.6 half-axes) side by side in y, as one OBJ: separate components.
function twoEllipsoids() {
  const one = ellipsoidObj();
  const vertices = one.split('\n').filter((l) => l.startsWith('v ')).length;
  const shifted = one.split('\n').map((l) => {
    if (l.startsWith('v ')) {
      const [x, y, z] = l.slice(2).split(' ').map(Number);
      return `v ${x} ${y + 2} ${z}`;
    }
    if (l.startsWith('f ')) return `f ${l.slice(2).split(' ').map((i) => Number(i) + vertices).join(' ')}`;
    return l;
  });
  return { obj: `${one}${shifted.join('\n')}`, vertices };
}

export default [
  {
    name: 'two components with the spectral basis: the one without handles stays put',
    timeout: 60000,
    async run(t) {
      const page = await t.page('index.html?noCage=spectral'); // a lone mesh is deformed without a cage at once
      await appReady(page);
      const { obj, vertices } = twoEllipsoids();
      const result = await page.evaluate(async ({ obj, vertices }) => {
        const app = globalThis.subspaceDeformer;
        await app.loadFiles([new File([obj], 'two.obj')]).catch(() => {}); // no cage: bound again with the spectral basis
        for (let k = 0; k < 400 && app.model?.mesh.positions.length !== 6 * vertices; ++k) await new Promise((r) => setTimeout(r, 50));
        if (app.model?.basis !== 'spectral') return { state: `not bound spectrally: ${app.model?.name} ${app.model?.basis}` };
        const rest = app.model.mesh.positions.slice();
        // The first ellipsoid's ends: x < -1.8 fixed, x > 1.8 moving.
        const left = [], right = [];
        for (let i = 0; i < vertices; ++i) {
          if (rest[3 * i] < -1.8) left.push(i);
          if (rest[3 * i] > 1.8) right.push(i);
        }
        app.setHandles([left, right], { moving: [1] });
        const stats = await app.drag(1, [0, -0.5, 0.3]);
        const text = await app.exportObj('mesh');
        const moved = text.split('\n').filter((l) => l.startsWith('v ')).map((l) => l.slice(2).split(' ').map(Number));
        let other = 0, first = 0;
        moved.forEach((p, i) => {
          const d = Math.hypot(p[0] - rest[3 * i], p[1] - rest[3 * i + 1], p[2] - rest[3 * i + 2]);
          if (i >= vertices) other = Math.max(other, d);
          else first = Math.max(first, d);
        });
        return { state: stats.state, stopReason: stats.stopReason, other, first, banner: app.banner.text };
      }, { obj, vertices });
      assert.equal(result.state, 'converged', `${result.state}: ${result.stopReason}`);
      assert.ok(result.first > 0.3, `the dragged ellipsoid moved ${result.first}`);
      assert.ok(result.other < 0.05, `the ellipsoid without handles moved ${result.other} (model about 4.4 wide)`);
      assert.doesNotMatch(result.banner ?? '', /targets:|handle vertices/);
      assert.deepEqual(page.errors, []);
    },
  },
];
