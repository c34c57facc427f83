// Issue 32, item 7: a mesh URL without a model extension (an API endpoint) is read by its content, as the
// library and the CLI read it; it used to be taken for no model, or the cage for the mesh ("... has no cage").
import assert from 'node:assert/strict';
import { appReady } from './app_probe.mjs';

const app = 'globalThis.subspaceDeformer';

const bannerText = (page) => page.evaluate(() => {
  const banner = document.querySelector('.sd-banner');
  return banner && !banner.hidden ? banner.querySelector('.sd-message').textContent : '';
});

export default [
  {
    name: '?mesh=api/model/17&cage=api/cage/17: extensionless URLs load by their content; an HTML answer is named',
    timeout: 90000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const [mesh, cage] = await page.evaluate(`Promise.all([${app}.exportObj('mesh'), ${app}.exportObj('cage')])`);
      await page.route('**/api/model/17', (route) => route.fulfill({ contentType: 'application/octet-stream', body: mesh }));
      await page.route('**/api/cage/17', (route) => route.fulfill({ contentType: 'application/octet-stream', body: cage }));
      await page.route('**/api/model/18', (route) => route.fulfill({ contentType: 'text/html', body: '<!doctype html><p>sign in</p>' }));
      await page.goto(`${t.url}index.html?mesh=api/model/17&cage=api/cage/17`);
      await appReady(page);
      const got = await page.evaluate(() => ({ name: globalThis.subspaceDeformer.model?.name, vertices: globalThis.subspaceDeformer.restPositions()?.length / 3 }));
      assert.equal(got.name, '17.obj');
      assert.equal(got.vertices, mesh.split('\n').filter((l) => l.startsWith('v ')).length);
      assert.equal(await bannerText(page), '');
      const error = await page.evaluate(`${app}.loadUrls('api/model/18').then(() => null, (e) => e.message)`);
      assert.match(error, /api\/model\/18 is no model the app reads/);
      assert.match(await bannerText(page), /api\/model\/18 is no model the app reads[^]*The previous model is kept/);
      assert.equal(await page.evaluate(`${app}.model.name`), '17.obj');
      assert.deepEqual(page.errors, []);
    },
  },
];
