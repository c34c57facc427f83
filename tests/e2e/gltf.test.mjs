// glTF in the app, in real Chromium: a textured model whose sphere is split at its UV seam (three's
// SphereGeometry, written with glTF-Transform and a generated PNG texture) is dropped with a cage, drawn with
// its own material and texture, said to be welded, deformed, and exported as .glb in its own vertex layout with
// its material, texture and UVs. The files go through the browser's file chooser (the panel's open button) and
// the export through the panel's download button, as a user does it.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { deflateSync } from 'node:zlib';
import { Document, WebIO } from '@gltf-transform/core';
import { SphereGeometry } from 'three';
import { appReady, appShown } from './app_probe.mjs';

// A PNG of width x height RGB pixels from `color(x, y)` (uncompressed rows through zlib, CRC per chunk).
function png(width, height, color) {
  const crcTable = Array.from({ length: 256 }, (_, n) => {
    let c = n;
    for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    return c >>> 0;
  });
  const crc = (bytes) => {
    let c = 0xffffffff;
    for (const b of bytes) c = crcTable[(c ^ b) & 0xff] ^ (c >>> 8);
    return (c ^ 0xffffffff) >>> 0;
  };
  const chunk = (type, data) => {
    const body = Buffer.concat([Buffer.from(type), data]);
    const out = Buffer.alloc(8 + data.length + 4);
    out.writeUInt32BE(data.length, 0);
    body.copy(out, 4);
    out.writeUInt32BE(crc(body), 8 + data.length);
    return out;
  };
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header[8] = 8; // bit depth
  header[9] = 2; // RGB
  const rows = [];
  for (let y = 0; y < height; ++y) rows.push(Buffer.from([0, ...Array.from({ length: width }, (_, x) => color(x, y)).flat()]));
  return Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), chunk('IHDR', header),
    chunk('IDAT', deflateSync(Buffer.concat(rows))), chunk('IEND', Buffer.alloc(0))]);
}

// A UV sphere with a red / blue checker texture, as a .glb.
async function texturedSphere() {
  const geometry = new SphereGeometry(1, 24, 16);
  const document = new Document();
  const buffer = document.createBuffer();
  const accessor = (type, array) => document.createAccessor().setType(type).setArray(array).setBuffer(buffer);
  const texture = document.createTexture('checker').setMimeType('image/png')
    .setImage(png(8, 8, (x, y) => ((x + y) % 2 ? [220, 30, 30] : [30, 30, 220])));
  const material = document.createMaterial('checker').setBaseColorTexture(texture).setRoughnessFactor(0.8);
  material.getBaseColorTextureInfo().setMagFilter(9728).setMinFilter(9728); // NEAREST: crisp squares
  const primitive = document.createPrimitive()
    .setAttribute('POSITION', accessor('VEC3', geometry.getAttribute('position').array))
    .setAttribute('NORMAL', accessor('VEC3', geometry.getAttribute('normal').array))
    .setAttribute('TEXCOORD_0', accessor('VEC2', geometry.getAttribute('uv').array))
    .setIndices(accessor('SCALAR', Uint32Array.from(geometry.getIndex().array)))
    .setMaterial(material);
  document.createScene().addChild(document.createNode('sphere').setMesh(document.createMesh('sphere').addPrimitive(primitive)));
  return { bytes: Buffer.from(await new WebIO().writeBinary(document)), vertices: geometry.getAttribute('position').count };
}

// The same sphere as a .gltf whose buffer and texture are files of their own ("Separate" exports), with the
// texture in a sub-folder under a name that needs escaping.
async function separateSphere() {
  const io = new WebIO();
  const document = await io.readBinary(new Uint8Array((await texturedSphere()).bytes));
  document.getRoot().listBuffers().forEach((b) => b.setURI('sphere.bin'));
  document.getRoot().listTextures().forEach((t) => t.setURI('textures/checker skin.png'));
  const { json, resources } = await io.writeJSON(document);
  return { json, resources };
}

// A box cage around the unit sphere, as OBJ.
const CAGE = 'v -1.5 -1.5 -1.5\nv 1.5 -1.5 -1.5\nv 1.5 1.5 -1.5\nv -1.5 1.5 -1.5\nv -1.5 -1.5 1.5\nv 1.5 -1.5 1.5\nv 1.5 1.5 1.5\nv -1.5 1.5 1.5\n' +
  'f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n';

// The share of the app's screenshot pixels that are clearly red or clearly blue (the checker texture; the
// plain material is grey-blue, far from both).
function checkerShare(page) {
  return page.evaluate(async () => {
    const img = new Image();
    img.src = globalThis.subspaceDeformer.screenshot();
    await img.decode();
    const c = Object.assign(document.createElement('canvas'), { width: img.width, height: img.height });
    const ctx = c.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const data = ctx.getImageData(0, 0, c.width, c.height).data;
    let red = 0, blue = 0;
    for (let i = 0; i < data.length; i += 16) {
      if (data[i] > data[i + 2] + 60) red++;
      if (data[i + 2] > data[i] + 60) blue++;
    }
    const n = data.length / 16;
    return { red: red / n, blue: blue / n };
  });
}

export default [
  {
    name: 'a textured glTF with a UV seam loads with its look, welds, deforms and exports in its own layout',
    async run(t) {
      const { bytes, vertices } = await texturedSphere();
      const page = await t.page('index.html');
      await appReady(page);
      // Through the browser's file chooser, opened by the panel's button; the picker lists glTF files.
      const accept = await page.locator('.sd-app input[type=file]').getAttribute('accept');
      assert.ok(accept.split(',').includes('.glb') && accept.split(',').includes('.gltf'), `accept: ${accept}`);
      const [chooser] = await Promise.all([page.waitForEvent('filechooser'),
        page.locator('.lil-gui button', { hasText: 'open mesh + cage / scene' }).click()]);
      assert.ok(chooser.isMultiple(), 'mesh and cage in one pick');
      await chooser.setFiles([
        { name: 'checker.glb', mimeType: 'model/gltf-binary', buffer: bytes },
        { name: 'cage.obj', mimeType: 'text/plain', buffer: Buffer.from(CAGE) },
      ]);
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.name === 'checker.glb');
      const model = await page.evaluate(() => {
        const m = globalThis.subspaceDeformer.model;
        const note = document.querySelector('.sd-model-note');
        const modelNote = () => ({ text: note.textContent, title: note.title, box: note.getBoundingClientRect().toJSON(),
          status: document.querySelector('.sd-status').getBoundingClientRect().toJSON() });
        return { vertices: m.mesh.positions.length / 3, layout: { ...m.layout, solverOfFile: undefined }, notes: m.notes.map((n) => n.code),
          look: m.look?.parts.length ?? 0, bannerShown: !document.querySelector('.sd-banner').hidden, note: modelNote() };
      });
      assert.equal(model.vertices, vertices, 'the file\'s own vertices');
      assert.equal(model.layout.solverVertices, 24 * 15 + 2, `welded points: ${JSON.stringify(model.layout)}`);
      assert.ok(model.notes.includes('welded'), `notes: ${model.notes}`);
      // A routine note: in the status bar (its whole text on hover and, pressed, in the banner), not over the model.
      assert.equal(model.bannerShown, false, 'no banner over the model');
      assert.match(model.note.text, /^note: .*vertices at the same point as another .* welded/);
      assert.match(model.note.title, /^checker\.glb:\n\u2022 .*welded/);
      assert.ok(model.note.box.height > 0 && model.note.box.top >= model.note.status.top && model.note.box.bottom <= model.note.status.bottom,
        `the note lies in the status bar: ${JSON.stringify(model.note)}`);
      await page.locator('.sd-model-note').click();
      assert.match(await page.locator('.sd-banner').innerText(), /vertices at the same point as another .* welded/);
      await page.locator('.sd-banner .sd-close').click();
      assert.equal(model.look, 1, 'its primitive is drawn with the file\'s material');
      await appShown(page);
      await t.screenshot(page, 'gltf-textured');
      const before = await checkerShare(page);
      assert.ok(before.red > 0.01 && before.blue > 0.01, `the checker texture is drawn: ${JSON.stringify(before)}`);

      // Top and bottom caps as handles; pull the top.
      const stats = await page.evaluate(async () => {
        const app = globalThis.subspaceDeformer;
        const p = app.restPositions();
        const bottom = [], top = [];
        for (let i = 0; i < p.length / 3; ++i) {
          if (p[3 * i + 1] < -0.8) bottom.push(i);
          if (p[3 * i + 1] > 0.8) top.push(i);
        }
        app.setHandles([bottom, top], { moving: [1] });
        return app.drag(1, [0.2, 0.3, 0]);
      });
      assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
      assert.ok(Math.abs(stats.volumeRelError) < 1e-6, `volume kept: ${stats.volumeRelError}`);
      await appShown(page);
      await t.screenshot(page, 'gltf-textured-deformed');
      const after = await checkerShare(page);
      assert.ok(after.red > 0.01 && after.blue > 0.01, `still textured after the drag: ${JSON.stringify(after)}`);

      // The export, from the panel's button as a user downloads it: the same primitive layout, the texture, the
      // UVs, the deformed positions.
      await page.locator('.lil-gui .lil-title', { hasText: 'Export' }).click(); // the folder starts closed
      const [download] = await Promise.all([page.waitForEvent('download'),
        page.locator('.lil-gui button', { hasText: 'deformed mesh (glTF .glb)' }).click()]);
      assert.match(download.suggestedFilename(), /^checker-subspace-deformed\.glb$/);
      const downloaded = [...readFileSync(await download.path())];
      const exported = await page.evaluate(async (bytes) => {
        const app = globalThis.subspaceDeformer;
        const glb = new Uint8Array(bytes);
        const view = new DataView(glb.buffer, glb.byteOffset, glb.byteLength);
        const jsonLength = view.getUint32(12, true);
        const json = JSON.parse(new TextDecoder().decode(glb.subarray(20, 20 + jsonLength)));
        const binStart = 20 + jsonLength + 8;
        const position = json.accessors[json.meshes[0].primitives[0].attributes.POSITION];
        const bufferView = json.bufferViews[position.bufferView];
        const start = binStart + (bufferView.byteOffset ?? 0) + (position.byteOffset ?? 0);
        const stride = bufferView.byteStride ?? 12;  // the writer may interleave the attributes
        const solved = app.positions();
        let gap = 0;
        for (let v = 0; v < position.count; ++v) {
          for (let a = 0; a < 3; ++a) gap = Math.max(gap, Math.abs(view.getFloat32(start + v * stride + 4 * a, true) - solved[3 * v + a]));
        }
        return { magic: view.getUint32(0, true), count: position.count, attributes: Object.keys(json.meshes[0].primitives[0].attributes).sort(),
          images: json.images?.length ?? 0, textures: json.textures?.length ?? 0, gap };
      }, downloaded);
      assert.equal(exported.magic, 0x46546c67, 'binary glTF');
      assert.equal(exported.count, vertices, 'its own vertex layout');
      assert.deepEqual(exported.attributes, ['NORMAL', 'POSITION', 'TEXCOORD_0']);
      assert.equal(exported.images, 1);
      assert.equal(exported.textures, 1);
      assert.ok(exported.gap < 1e-6, `the deformed positions: ${exported.gap}`);
      assert.deepEqual(page.errors, []);
    },
  },
  {
    name: 'an open mesh loads with a note, keeps its capped volume, and a bad glTF is refused by name',
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      const input = page.locator('.sd-app input[type=file]');
      // The bar example without two of its triangles: a hole.
      const obj = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        const p = app.restPositions(), f = app.indices().slice(6);
        let text = '';
        for (let i = 0; i < p.length; i += 3) text += `v ${p[i]} ${p[i + 1]} ${p[i + 2]}\n`;
        for (let i = 0; i < f.length; i += 3) text += `f ${f[i] + 1} ${f[i + 1] + 1} ${f[i + 2] + 1}\n`;
        return text;
      });
      const cage = await page.evaluate(() => {
        const m = globalThis.subspaceDeformer.model.cage;
        let text = '';
        for (let i = 0; i < m.positions.length; i += 3) text += `v ${m.positions[i]} ${m.positions[i + 1]} ${m.positions[i + 2]}\n`;
        for (let i = 0; i < m.indices.length; i += 3) text += `f ${m.indices[i] + 1} ${m.indices[i + 1] + 1} ${m.indices[i + 2] + 1}\n`;
        return text;
      });
      await input.setInputFiles([{ name: 'holed.obj', mimeType: 'text/plain', buffer: Buffer.from(obj) },
        { name: 'bar_cage.obj', mimeType: 'text/plain', buffer: Buffer.from(cage) }]);
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.name === 'holed.obj');
      assert.match(await page.locator('.sd-model-note').getAttribute('title'), /the mesh is open: .* around 1 hole/);
      const stats = await page.evaluate(() => globalThis.subspaceDeformer.drag(1, [0, 0.4, 0]));
      assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
      assert.equal(stats.partVolumeChange.length, 1, 'one capped volume');
      assert.ok(Math.abs(stats.partVolumeChange[0]) < 1e-6, `capped volume kept: ${stats.partVolumeChange}`);
      // A .glb that requires Draco: named, and the open mesh stays.
      const json = JSON.stringify({ asset: { version: '2.0' }, extensionsRequired: ['KHR_draco_mesh_compression'] });
      await input.setInputFiles([{ name: 'draco.gltf', mimeType: 'model/gltf+json', buffer: Buffer.from(json) }]);
      await page.waitForFunction(() => /draco\.gltf: its geometry is compressed/.test(document.querySelector('.sd-banner').textContent));
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.model.name), 'holed.obj');
      assert.deepEqual(page.errors.filter((e) => !/draco\.gltf/.test(e)), []);
    },
  },
  {
    name: 'a .gltf with separate .bin and texture loads from a URL and from a served scene, its files fetched beside it',
    async run(t) {
      const { json, resources } = await separateSphere();
      assert.deepEqual(Object.keys(resources).sort(), ['sphere.bin', 'textures/checker skin.png']);
      const page = await t.page(null);
      const served = [];
      const serve = (path, body, contentType) => page.route(`**/models/${path}`, (route) => {
        served.push(path);
        return route.fulfill({ contentType, body });
      });
      await serve('sphere.gltf', JSON.stringify(json), 'model/gltf+json');
      await serve('sphere.bin', Buffer.from(resources['sphere.bin']), 'application/octet-stream');
      await serve('textures/checker%20skin.png', Buffer.from(resources['textures/checker skin.png']), 'image/png');
      await serve('cage.obj', CAGE, 'text/plain');
      const scene = { mesh: 'sphere.gltf', cage: 'cage.obj', handles: [{ vertices: [0, 1, 2] }, { vertices: [400, 401], translate: [0, 0.2, 0] }] };
      await serve('scene.json', JSON.stringify(scene), 'application/json');
      const loaded = async () => {
        await appReady(page);
        return page.evaluate(() => {
          const m = globalThis.subspaceDeformer.model;
          return { name: m.name, vertices: m.mesh.positions.length / 3, notes: m.notes.map((n) => n.code), look: m.look?.parts.length ?? 0 };
        });
      };
      await page.goto(`${t.url}index.html?mesh=models/sphere.gltf&cage=models/cage.obj`);
      assert.deepEqual(await loaded(), { name: 'sphere.gltf', vertices: 25 * 17, notes: ['welded'], look: 1 });
      assert.deepEqual(served.sort(), ['cage.obj', 'sphere.bin', 'sphere.gltf', 'textures/checker%20skin.png']);
      await appShown(page);
      const share = await checkerShare(page);
      assert.ok(share.red > 0.01 && share.blue > 0.01, `the separate texture is drawn: ${JSON.stringify(share)}`);
      await page.goto(`${t.url}index.html?scene=models/scene.json`);
      assert.equal((await loaded()).name, 'sphere.gltf');
      const stats = await page.evaluate(() => globalThis.subspaceDeformer.solve());
      assert.equal(stats.state, 'converged', `${stats.state}: ${stats.stopReason}`);
      assert.ok(Math.abs(stats.volumeRelError) < 1e-6, `volume kept: ${stats.volumeRelError}`);
      // Dropped (picked) together: a scene, the .gltf, its .bin and texture and the cage; the scene's mesh brings
      // the files picked with it.
      await page.evaluate(() => {
        globalThis.pickedLoad = new Promise((resolve) => globalThis.subspaceDeformer.addEventListener('load', resolve));
      });
      const [chooser] = await Promise.all([page.waitForEvent('filechooser'), page.evaluate(() => globalThis.subspaceDeformer.openFilePicker())]);
      await chooser.setFiles([
        { name: 'picked.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(scene)) },
        { name: 'sphere.gltf', mimeType: 'model/gltf+json', buffer: Buffer.from(JSON.stringify(json)) },
        { name: 'sphere.bin', mimeType: 'application/octet-stream', buffer: Buffer.from(resources['sphere.bin']) },
        { name: 'checker skin.png', mimeType: 'image/png', buffer: Buffer.from(resources['textures/checker skin.png']) },
        { name: 'cage.obj', mimeType: 'text/plain', buffer: Buffer.from(CAGE) },
      ]);
      await page.evaluate(() => globalThis.pickedLoad);
      assert.equal((await loaded()).look, 1, 'the picked scene\'s glTF with its texture');
      // Its .bin gone from the server: named in the banner, no crash.
      await page.unroute('**/models/sphere.bin');
      await page.route('**/models/sphere.bin', (route) => route.fulfill({ status: 404, body: 'not found' }));
      await page.goto(`${t.url}index.html?mesh=models/sphere.gltf&cage=models/cage.obj`);
      await page.waitForFunction(() => /sphere\.gltf refers to sphere\.bin, which could not be loaded \(404/.test(document.querySelector('.sd-banner')?.textContent));
      assert.deepEqual(page.errors.filter((e) => !/sphere\.(gltf|bin)|404/.test(e)), []);
    },
  },
  {
    name: 'an open mesh alone is offered a generated cage and the spectral basis, as a closed one is',
    timeout: 120000,
    async run(t) {
      const page = await t.page('index.html');
      await appReady(page);
      // The bar example without two of its triangles (a hole), alone: no cage.
      const obj = await page.evaluate(() => {
        const app = globalThis.subspaceDeformer;
        const p = app.restPositions(), f = app.indices().slice(6);
        let text = '';
        for (let i = 0; i < p.length; i += 3) text += `v ${p[i]} ${p[i + 1]} ${p[i + 2]}\n`;
        for (let i = 0; i < f.length; i += 3) text += `f ${f[i] + 1} ${f[i + 1] + 1} ${f[i + 2] + 1}\n`;
        return text;
      });
      const pick = async () => {
        const [chooser] = await Promise.all([page.waitForEvent('filechooser'), page.evaluate(() => globalThis.subspaceDeformer.openFilePicker())]);
        await chooser.setFiles([{ name: 'holed.obj', mimeType: 'text/plain', buffer: Buffer.from(obj) }]);
        await page.waitForFunction(() => /holed\.obj has no cage/.test(document.querySelector('.sd-banner').textContent));
      };
      const banner = page.locator('.sd-banner');
      const dragKeepsTheCappedVolume = async (what) => {
        const stats = await page.evaluate(() => globalThis.subspaceDeformer.drag(1, [0, 0.4, 0]));
        assert.equal(stats.state, 'converged', `${what}: ${stats.state}: ${stats.stopReason}`);
        assert.equal(stats.partVolumeChange.length, 1, `${what}: one capped volume`);
        assert.ok(Math.abs(stats.partVolumeChange[0]) < 1e-6, `${what}: capped volume kept: ${stats.partVolumeChange}`);
      };
      await pick();
      await banner.locator('label', { hasText: 'cage vertices' }).locator('input').fill('60');
      await banner.getByRole('button', { name: 'Generate cage' }).click();
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.name === 'holed.obj', null, { timeout: 60000 });
      const generated = await page.evaluate(() => {
        const m = globalThis.subspaceDeformer.model;
        return { basis: m.basis, cage: m.cage.positions.length / 3, notes: m.notes.map((n) => n.code) };
      });
      assert.equal(generated.basis, 'cage');
      assert.ok(generated.cage > 8 && generated.cage <= 60, `a generated cage: ${generated.cage} vertices`);
      assert.ok(generated.notes.includes('open'), `notes: ${generated.notes}`);
      await dragKeepsTheCappedVolume('generated cage');
      await appShown(page);
      await t.screenshot(page, 'open-mesh-generated-cage');

      await pick();
      await banner.locator('label', { hasText: 'modes' }).locator('input').fill('20');
      await banner.getByRole('button', { name: 'Deform without a cage (spectral basis)' }).click();
      await page.waitForFunction(() => globalThis.subspaceDeformer.model?.basis === 'spectral', null, { timeout: 60000 });
      assert.equal(await page.evaluate(() => globalThis.subspaceDeformer.model.name), 'holed.obj');
      await dragKeepsTheCappedVolume('spectral basis');
      assert.deepEqual(page.errors, []);
    },
  },
];
