// The app's parts that need no page: its settings (the solver options per method and a scene's "solver"
// both ways, checked and defaulted by the library's options schema), the compare-mode option, the sorting of dropped files and the stats text.
import { describe, expect, it } from 'vitest';
import { AppSettings, DEFAULT_SETTINGS, checkCageSize, touchesSolver } from '../../web/app/settings.js';
import { COMPARE_METHODS, METHODS, compareMethods, parseViewKey, readCompare, viewKeys, viewLabel } from '../../web/app/methods.js';
import { asModelFile, readFile, sortFiles, withDroppedFiles, withGltfFiles } from '../../web/app/loading/files.js';
import { modelFormatOf } from '../../web/lib/formats.js';
import { duration, meritText, modelLine, panelStats, progressLine, solverLine, statsLine, volumeChangeText } from '../../web/app/stats_format.js';
import { SolveRecord } from '../../web/app/solve_record.js';
import { savedScene, sceneText } from '../../web/app/loading/saved_scene.js';
import { parseScene } from '../../web/lib/scene.js';
import { DEFAULT_OPTIONS, OPTION_NAMES } from '../../web/lib/options.js';
import { InputError } from '../../web/lib/errors.js';
import { thrown } from './support/thrown.js';

describe('AppSettings', () => {
  it('gives each method its own iteration cap and sends scene-only options only once set', () => {
    const settings = new AppSettings({ maxIterations: 40 });
    expect(settings.solverOptions('subspace').maxIterations).toBe(40);
    expect(settings.solverOptions('arap').maxIterations).toBe(DEFAULT_SETTINGS.arapMaxIterations);
    expect(settings.solverOptions('full')).not.toHaveProperty('cgMemory');
    settings.update({ cgMemory: 8 });
    expect(settings.solverOptions('full').cgMemory).toBe(8);
    // Display settings are no solver options.
    expect(settings.solverOptions('subspace')).not.toHaveProperty('showCage');
  });

  it("maps a scene's maxIterations to the cap of the scene's method, and back", () => {
    for (const method of ['subspace', 'arap']) {
      const solver = { method, maxIterations: 77, c1: 1e-3, arapEnergyTolerance: 1e-6 };
      const settings = new AppSettings(AppSettings.fromScene(solver, 'full'));
      expect(settings.values[method === 'arap' ? 'arapMaxIterations' : 'maxIterations']).toBe(77);
      expect(settings.values[method === 'arap' ? 'maxIterations' : 'arapMaxIterations']).toBe(DEFAULT_SETTINGS[method === 'arap' ? 'maxIterations' : 'arapMaxIterations']);
      expect(settings.toScene(method)).toMatchObject(solver);
    }
    // Without a method, the cap is the current view's.
    expect(AppSettings.fromScene({ maxIterations: 9 }, 'arap')).toEqual({ arapMaxIterations: 9 });
  });

  it('dispatches what changed; only solver settings concern the solvers', () => {
    const settings = new AppSettings();
    const seen = [];
    settings.addEventListener('change', (e) => seen.push(e.changed));
    settings.update({ wireframe: true });
    expect(seen).toEqual([{ wireframe: true }]);
    expect(settings.snapshot().wireframe).toBe(true);
    expect(touchesSolver({ wireframe: true, brushRadius: 0.1, cageVertices: 50 })).toBe(false);
    expect(touchesSolver({ showCage: false, jacobian: 'exact' })).toBe(true);
    expect(touchesSolver({ iterationsPerFrame: 3 })).toBe(true);
  });

  it('takes the page\'s thread count as a setting of its own, never a solver option or part of a scene', () => {
    const settings = new AppSettings();
    expect(settings.values.threads).toBe('auto');
    settings.update({ threads: 2 });
    expect(touchesSolver({ threads: 2 })).toBe(false); // no re-solve: only the speed changes
    expect(settings.solverOptions('subspace')).not.toHaveProperty('threads');
    expect(settings.toScene('subspace')).not.toHaveProperty('threads');
    for (const bad of [0, -1, 1.5, 'many', 2000]) expect(() => settings.update({ threads: bad })).toThrow(/threads must be 'auto' or an integer/);
    expect(settings.values.threads).toBe(2);
  });

  it('accepts cage sizes from 20 to 1000 only', () => {
    expect(() => checkCageSize(20)).not.toThrow();
    expect(() => checkCageSize(1000)).not.toThrow();
    for (const bad of [19, 1001, 50.5, '50', NaN]) expect(() => checkCageSize(bad)).toThrow(/from 20 to 1000/);
  });
});

describe('cage coordinates in the app', () => {
  it('names the views of "compare coordinates" by key and labels them by their coordinates', () => {
    const settings = { method: 'subspace', coordinates: 'mvc', compareCoordinates: 'harmonic' };
    // readCompare gives 'coordinates' as a list of one; viewKeys makes it the two views.
    expect(readCompare('coordinates').methods).toEqual(['coordinates']);
    expect(viewKeys(['coordinates'], settings)).toEqual(['subspace:mvc', 'subspace:harmonic']);
    // The same type twice would compare nothing: the second view takes another one.
    expect(viewKeys(['coordinates'], { ...settings, compareCoordinates: 'mvc' })).toEqual(['subspace:mvc', 'subspace:pmvc']);
    expect(viewKeys(null, settings)).toEqual(['subspace']);
    expect(compareMethods('subspace:pmvc, subspace:harmonic, full:mvc')).toEqual(['subspace:pmvc', 'subspace:harmonic']);
    expect(parseViewKey('subspace:harmonic')).toEqual({ method: 'subspace', coordinates: 'harmonic' });
    expect(parseViewKey('arap')).toEqual({ method: 'arap', coordinates: null });
    expect(viewLabel('subspace:pmvc')).toBe('Subspace (positive mean value coordinates)');
  });

  it('checks the coordinates settings and saves non-default coordinates in scenes', () => {
    const settings = new AppSettings();
    expect(settings.values).toMatchObject({ coordinates: 'mvc', pmvcResolution: 32, harmonicResolution: 0 });
    settings.update({ coordinates: 'harmonic', harmonicResolution: 40 });
    expect(touchesSolver({ coordinates: 'pmvc' })).toBe(false); // the next binding, not the solver
    expect(() => settings.update({ coordinates: 'green' })).toThrow(/coordinates must be one of 'mvc', 'pmvc', 'harmonic'/);
    expect(() => settings.update({ harmonicResolution: 2000 })).toThrow(/harmonicResolution must be an integer from 0 to 1024/);
    expect(() => settings.update({ pmvcResolution: 0 })).toThrow(/pmvcResolution must be an integer from 2 to 1024/);
    const model = { name: 'c-bar', basis: 'cage', source: { example: 'c-bar' }, subspace: { basis: 'cage', coordinates: 'harmonic', harmonicResolution: 40 } };
    const scene = savedScene(model, [], {});
    expect(scene.subspace).toEqual({ basis: 'cage', coordinates: 'harmonic', harmonicResolution: 40 });
    expect(parseScene(scene).subspace).toEqual(scene.subspace);
    expect(savedScene({ ...model, subspace: { basis: 'cage', coordinates: 'mvc' } }, [], {})).not.toHaveProperty('subspace');
  });
});

describe('compareMethods', () => {
  it('reads lists, strings and booleans', () => {
    expect(compareMethods(false)).toBeNull();
    expect(compareMethods(undefined)).toBeNull();
    expect(compareMethods(true)).toEqual(COMPARE_METHODS);
    expect(compareMethods('true')).toEqual(COMPARE_METHODS);
    expect(compareMethods('arap, full')).toEqual(['arap', 'full']);
    expect(compareMethods('subspace|magic')).toEqual(['subspace']);
    expect(compareMethods('magic')).toEqual(COMPARE_METHODS);
    expect(compareMethods(['full', 'nope', 'arap'])).toEqual(['full', 'arap']);
    for (const m of COMPARE_METHODS) expect(METHODS).toContain(m);
  });
});

describe('sortFiles', () => {
  const file = (name) => ({ name });
  it('sorts meshes and scenes by extension, any case', () => {
    const { scenes, meshes } = sortFiles([file('a.OBJ'), file('s.json'), file('c.off'), file('d.ply'), file('e.stl')]);
    expect(scenes.map((f) => f.name)).toEqual(['s.json']);
    expect(meshes.map((f) => f.name)).toEqual(['a.OBJ', 'c.off', 'd.ply', 'e.stl']);
  });

  it('refuses other files, naming them', () => {
    expect(() => sortFiles([file('a.obj'), file('notes.txt'), file('b.fbx')])).toThrow(/notes\.txt, b\.fbx: unsupported file type/);
    // A .bin or texture is a .gltf's own file: accepted beside a .gltf only.
    expect(() => sortFiles([file('a.glb'), file('a.bin')])).toThrow(/a\.bin: unsupported file type/);
    expect(sortFiles([file('a.gltf'), file('a.bin'), file('t.png')])).toMatchObject({ meshes: [{ name: 'a.gltf' }], resources: [{ name: 'a.bin' }, { name: 't.png' }] });
  });
});

describe('withGltfFiles', () => {
  const gltf = (json, url) => ({ name: 'm.gltf', bytes: new TextEncoder().encode(typeof json === 'string' ? json : JSON.stringify(json)), url });
  const bin = { name: 'm.bin', bytes: new Uint8Array([1]) }, png = { name: 'skin 1.png', bytes: new Uint8Array([2]) };
  const doc = { buffers: [{ uri: 'm.bin' }, { uri: 'data:application/octet-stream;base64,AAAA' }], images: [{ uri: 'tex/skin%201.png' }, { bufferView: 0 }] };

  it('adds the separate files a .gltf names from those dropped with it (by unescaped name), named by their uri, nothing for other models', async () => {
    expect((await withGltfFiles(gltf(doc), [png, bin, { name: 'other.png', bytes: new Uint8Array() }])).map((f) => f.name)).toEqual(['m.gltf', 'm.bin', 'tex/skin%201.png']);
    expect(await withGltfFiles({ name: 'a.glb', bytes: new Uint8Array(4) }, [bin])).toHaveLength(1);
    // Not given and nowhere to fetch from, or not JSON: the file alone (the reader names what is missing or wrong).
    expect(await withGltfFiles(gltf(doc), [])).toHaveLength(1);
    expect(await withGltfFiles(gltf('{"buffers": ['), [bin])).toHaveLength(1);
  });

  it('fetches the rest relative to the .gltf\'s URL, naming a file that cannot be loaded', async () => {
    const fetched = [];
    const realFetch = globalThis.fetch;
    globalThis.fetch = async (url) => {
      fetched.push(String(url));
      return String(url).endsWith('m.bin') ? new Response(new Uint8Array([7])) : new Response('gone', { status: 404, statusText: 'Not Found' });
    };
    try {
      const files = await withGltfFiles(gltf({ buffers: [{ uri: 'm.bin' }] }, 'https://example.test/models/m.gltf'));
      expect(files.map((f) => f.name)).toEqual(['m.gltf', 'm.bin']);
      expect(Array.from(files[1].bytes)).toEqual([7]);
      expect(fetched).toEqual(['https://example.test/models/m.bin']);
      const error = await withGltfFiles(gltf(doc, 'https://example.test/models/m.gltf'), [bin]).then(() => null, (e) => e);
      expect(error).toBeInstanceOf(InputError);
      expect(error.code).toBe('unreadable_file');
      expect(error.message).toMatch(/^m\.gltf refers to tex\/skin%201\.png, which could not be loaded \(404 Not Found\)/);
    } finally {
      globalThis.fetch = realFetch;
    }
  });

  // Issue 32, item 7: buffers a/data.bin and b/data.bin used to be looked up by base name, so mesh 0 silently
  // read mesh 1's buffer.
  it('keys files by their path: a/data.bin and b/data.bin stay apart, and base names alone are refused, not guessed', async () => {
    const two = { buffers: [{ uri: 'a/data.bin' }, { uri: './b/data.bin' }] };
    const a = { name: 'data.bin', path: 'model/a/data.bin', bytes: new Uint8Array([1]) };
    const b = { name: 'data.bin', path: 'model/b/data.bin', bytes: new Uint8Array([2]) };
    const inFolder = { ...gltf(two), path: 'model/m.gltf' };
    const files = await withGltfFiles(inFolder, [b, a]);
    expect(files.map((f) => [f.name, f.bytes[0]])).toEqual([['m.gltf', 123], ['a/data.bin', 1], ['./b/data.bin', 2]]);
    // Dropped without their folders: two files of one name, or one file for two uris of that name.
    for (const dropped of [[{ ...a, path: undefined }, { ...b, path: undefined }], [{ ...a, path: undefined }]]) {
      const error = await withGltfFiles(gltf(two), dropped).then(() => null, (e) => e);
      expect(error).toBeInstanceOf(InputError);
      expect(error.code).toBe('unreadable_file');
      expect(error.message).toMatch(/^m\.gltf refers to a\/data\.bin, \.\/b\/data\.bin, and \d dropped files are named data\.bin: which is which cannot be told/);
    }
    // One uri of a name, one file of it: still found by its name.
    expect((await withGltfFiles(gltf({ buffers: [{ uri: 'a/data.bin' }] }), [{ ...a, path: undefined }])).map((f) => f.name)).toEqual(['m.gltf', 'a/data.bin']);
  });

  it('withDroppedFiles gives each dropped model its own files, and readFile keeps a picked folder\'s paths', async () => {
    const two = { buffers: [{ uri: 'a/data.bin' }, { uri: 'b/data.bin' }] };
    const a = { name: 'data.bin', path: 'm/a/data.bin', bytes: new Uint8Array([1]) };
    const b = { name: 'data.bin', path: 'm/b/data.bin', bytes: new Uint8Array([2]) };
    const cage = { name: 'cage.obj', bytes: new Uint8Array([3]) };
    const files = await withDroppedFiles([a, { ...gltf(two), path: 'm/m.gltf' }, b, cage]);
    expect(files.map((f) => [f.name, f.bytes[0]])).toEqual([['m.gltf', 123], ['a/data.bin', 1], ['b/data.bin', 2], ['cage.obj', 3]]);
    const picked = { name: 'data.bin', webkitRelativePath: 'm/a/data.bin', size: 1, arrayBuffer: async () => new Uint8Array([1]).buffer };
    expect(await readFile(picked)).toMatchObject({ name: 'data.bin', path: 'm/a/data.bin' });
  });

  it('refuses a .gltf that names more than 64 separate files before fetching any', async () => {
    const many = { buffers: Array.from({ length: 65 }, (_, i) => ({ uri: `b${i}.bin` })) };
    await expect(withGltfFiles(gltf(many, 'https://example.test/m.gltf'))).rejects.toThrow(/m\.gltf refers to 65 separate files, more than 64/);
  });
});

// Issue 32, item 7: a mesh URL without an extension (an API endpoint) was taken for the cage, or for no model.
describe('a model by its content', () => {
  const text = (t) => new TextEncoder().encode(t);

  it('modelFormatOf reads the format from the content as the C++ readers do', () => {
    expect(modelFormatOf(text('# made by hand\nv 0 0 0\n'))).toBe('obj');
    expect(modelFormatOf(text('  OFF\n4 4 0\n'))).toBe('off');
    expect(modelFormatOf(text('ply\nformat ascii 1.0\n'))).toBe('ply');
    expect(modelFormatOf(text('solid x\nendsolid x\n'))).toBe('stl');
    const binaryStl = new Uint8Array(84 + 50);
    binaryStl[80] = 1;
    expect(modelFormatOf(binaryStl)).toBe('stl');
    expect(modelFormatOf(text('\n{"asset": {"version": "2.0"}}'))).toBe('gltf');
    expect(modelFormatOf(new Uint8Array([0x67, 0x6c, 0x54, 0x46, 2, 0, 0, 0, 12, 0, 0, 0]))).toBe('glb');
    expect(modelFormatOf(text('<!doctype html><p>not found</p>'))).toBeNull();
    expect(modelFormatOf(new Uint8Array())).toBeNull();
  });

  it('asModelFile names a URL without an extension by its content, and refuses one that is no model', () => {
    const url = 'https://example.test/api/model/17';
    expect(asModelFile({ name: '17', url, bytes: text('v 0 0 0\n') }).name).toBe('17.obj');
    expect(asModelFile({ name: '17', url, bytes: text('{"asset": {}}') }).name).toBe('17.gltf');
    expect(asModelFile({ name: 'cage.obj', url, bytes: text('nonsense') }).name).toBe('cage.obj');
    const error = thrown(() => asModelFile({ name: '17', url, bytes: text('<html></html>') }));
    expect(error).toBeInstanceOf(InputError);
    expect(error.code).toBe('parse_error');
    expect(error.message).toMatch(/^https:\/\/example\.test\/api\/model\/17 is no model the app reads/);
  });
});

describe('stats text', () => {
  const stats = { state: 'stopped', stopReason: 'not converged after 100 iterations', merit: 0.00123, volumeRelError: 2e-9,
    iterations: 100, msPerIteration: 3.24, fps: 59.6, vertexCount: 5042, bindMs: 7.4 };

  it('shows the numbers, the state and why a solve stopped', () => {
    const line = statsLine(stats, { loaded: true, requestSize: 4 });
    expect(line.numbers).toBe('merit 1.230e-3   volume change 0.000000%\niterations 100   3.2 ms/iteration   k=4/request');
    expect(line).toMatchObject({ state: 'stopped', label: 'stopped', reason: ': not converged after 100 iterations' });
    expect(panelStats(stats)).toEqual({ status: 'stopped: not converged after 100 iterations', merit: '1.230e-3',
      volume: '0.000000 %', parts: 'global volume', iterations: '100', msPerIteration: '3.24', fps: '60' });
  });

  // Issue 31, item 4: round-off is shown as 0, and never with a minus sign ("-0.000000%", a merit of -1.239e-17).
  it('shows round-off as 0, never as a negative number or "-0"', () => {
    const rest = { ...stats, state: 'converged', merit: -1.239e-17, energy: 0, lambda: 0.8, restVolume: 0.06, volumeRelError: -3e-16 };
    expect(meritText(rest)).toBe('0');
    expect(volumeChangeText(rest)).toBe('0.000000');
    expect(statsLine(rest, { loaded: true, requestSize: 1 }).numbers).toMatch(/^merit 0 {3}volume change 0\.000000%\n/);
    expect(panelStats(rest)).toMatchObject({ merit: '0', volume: '0.000000 %' });
    // Rounded to 6 decimals but above round-off: still no "-0".
    expect(volumeChangeText({ volumeRelError: -2e-9 })).toBe('0.000000');
    expect(volumeChangeText({ volumeRelError: -2e-8 })).toBe('-0.000002');
    // A real negative merit (lambda g below -E, far above round-off) and a real small one are shown.
    expect(meritText({ ...rest, merit: -0.0031, energy: 0.002 })).toBe('-3.100e-3');
    expect(meritText({ ...rest, merit: 4.2e-9, energy: 4.2e-9, lambda: 0 })).toBe('4.200e-9');
    expect(meritText({ merit: 0 })).toBe('0');
    // With volume parts the multipliers are per part.
    expect(meritText({ ...rest, lambda: 0, partLambda: [0.5, -0.3] })).toBe('0');
  });

  it('before the first iteration: the model size and bind time, or loading', () => {
    const idle = { ...stats, state: 'idle', iterations: 0 };
    expect(statsLine(idle, { loaded: true, requestSize: 1 })).toMatchObject({ numbers: '5042 vertices, bind 7 ms', label: 'no handles', reason: '' });
    expect(statsLine(idle, { loaded: false, requestSize: 1 }).numbers).toBe('loading\u2026');
    expect(panelStats({ ...stats, state: 'converged' }).status).toBe('converged');
  });
});

describe('AppSettings and the library options schema', () => {
  it("takes the solver defaults from the library's table", () => {
    for (const key of ['method', 'jacobian', 'volume', 'maxIterations', 'positionWeight', 'c1', 'c2']) {
      expect(DEFAULT_SETTINGS[key]).toBe(DEFAULT_OPTIONS[key]);
    }
  });

  it('passes every other option of the table on once set (an option added to the table needs no app edit)', () => {
    const others = OPTION_NAMES.filter((name) => !(name in DEFAULT_SETTINGS));
    expect(others.length).toBeGreaterThan(3);
    const settings = new AppSettings();
    for (const name of others) expect(settings.solverOptions('subspace')).not.toHaveProperty(name);
    settings.update(Object.fromEntries(others.map((name) => [name, DEFAULT_OPTIONS[name]])));
    for (const name of others) expect(settings.solverOptions('subspace')[name]).toBe(DEFAULT_OPTIONS[name]);
  });

  it("refuses a bad solver option with the library's message, changing nothing", () => {
    const settings = new AppSettings();
    expect(() => settings.update({ wireframe: true, c1: 2 })).toThrow(InputError);
    expect(() => settings.update({ c1: 2 })).toThrow(/setOptions: c1 must be a number in \(0, 1\) \(got 2\)/);
    expect(() => settings.update({ method: 'magic' })).toThrow(/setOptions: method must be one of/);
    expect(() => settings.update({ arapMaxIterations: 0 })).toThrow(/arapMaxIterations must be an integer from 1/);
    expect(() => new AppSettings({ jacobian: 'approximate' })).toThrow(/settings: jacobian must be one of/);
    expect(settings.values.wireframe).toBe(false);
    expect(settings.values.c1).toBe(DEFAULT_OPTIONS.c1);
  });
});

describe('progress of long solves and the solver build in the stats', () => {
  const base = { state: 'solving', stopReason: '', merit: 1, volumeRelError: 0, iterations: 3, msPerIteration: 1900,
    firstIterationMs: 2300, fps: 60, vertexCount: 23110, bindMs: 900 };

  it('says how far a long solve is, the most time left, and how it ended', () => {
    const progress = { iteration: 12, maxIterations: 100, elapsedMs: 24000, msLeftAtMost: 88 * 1900, runningMs: 1200 };
    expect(progressLine({ ...base, progress })).toBe(
      'iteration 12 of at most 100 \u00b7 24.0 s so far \u00b7 at most 2 min 47 s left (iteration 13 running 1.2 s)');
    expect(progressLine({ ...base, state: 'converged', progress })).toBe('12 iterations in 24.0 s');
    expect(progressLine({ ...base, progress: { ...progress, elapsedMs: 300 } })).toBe(''); // quick solves: nothing
    // The first iteration of a long solve still running: no time per iteration yet, so nothing about the time left
    // (a tester saw "at most 0.0 ms left").
    const record = new SolveRecord('subspace');
    const first = record.progress(100, true);
    expect(first.msLeftAtMost).toBe(null);
    expect(progressLine({ ...base, progress: { ...first, elapsedMs: 2400, runningMs: 2400 } })).toBe(
      'iteration 0 of at most 100 \u00b7 2.4 s so far (iteration 1 running 2.4 s)');
    const line = statsLine({ ...base, progress }, { loaded: true, requestSize: 1 });
    expect(line.numbers.split('\n')).toHaveLength(3);
    expect(line.numbers).toContain('1.9 s/iteration');
  });

  it('shows the first iteration as such until a warm one is measured', () => {
    const line = statsLine({ ...base, msPerIteration: 0 }, { loaded: true, requestSize: 1 });
    expect(line.numbers).toContain('first iteration 2.3 s');
    expect(duration(3.24)).toBe('3.2 ms');
    expect(duration(125000)).toBe('2 min 05 s');
  });

  it('names the wasm build and its threads, and why a page runs single-threaded', () => {
    expect(solverLine({ build: 'threads', threads: 2 })).toBe('wasm: threaded build, 2 threads');
    expect(solverLine({ build: 'single', threads: 1, buildNote: 'the page is not cross-origin isolated, so it runs single-threaded' }))
      .toBe('wasm: single-threaded build (page not cross-origin isolated)');
    expect(solverLine({ build: 'single', threads: 1, buildNote: 'the threaded build did not load (x); running single-threaded' }))
      .toBe('wasm: single-threaded build (the threaded build did not load)');
    expect(statsLine({ ...base, solver: { build: 'threads', threads: 1 } }, { loaded: true, requestSize: 1 }).numbers)
      .toMatch(/\nwasm: threaded build, 1 thread$/);
  });

  it('names the model and its size, and says why nothing is loaded', () => {
    const model = { name: 'cow.obj', mesh: { positions: new Float64Array(3 * 23110), indices: new Uint32Array(3 * 46216) },
      cage: { positions: new Float64Array(3 * 82) } };
    expect(modelLine(model)).toBe('cow.obj: 23,110 vertices, 46,216 triangles, cage 82 vertices');
    // With the spectral basis the status bar names its modes, not a cage (a lone mesh has none).
    const lone = { ...model, name: 'bunny.obj', cage: { positions: new Float64Array(0) }, basis: 'spectral', basisSize: 44 };
    expect(modelLine(lone)).toBe('bunny.obj: 23,110 vertices, 46,216 triangles, spectral basis, 40 modes');
    expect(modelLine({ ...lone, basisSize: 5 })).toMatch(/spectral basis, 1 mode$/); // not "1 modes"
    expect(statsLine({ ...base, iterations: 0 }, { loaded: 'no model loaded', requestSize: 1 }).numbers).toBe('no model loaded');
  });
});

describe('SolveRecord', () => {
  const its = (...ms) => ms.map((m) => ({ merit: 1 / m, ms: m }));

  it('starts a fresh series per method and per model', () => {
    const record = new SolveRecord('subspace');
    record.add(its(90, 30, 28));
    record.setMethod('arap');
    record.add(its(5));
    expect(record.series.map((s) => [s.method, s.points.length])).toEqual([['subspace', 3], ['arap', 1]]);
    expect(record.points.map((p) => p.iteration)).toEqual([1]);
    record.setMethod('full'); // nothing iterated yet with full: the empty series is relabelled, not kept
    record.setMethod('subspace');
    expect(record.series.map((s) => s.method)).toEqual(['subspace', 'arap', 'subspace']);
    record.newModel();
    expect(record.series.map((s) => s.points.length)).toEqual([0]);
    expect(record.iterations).toBe(0);
  });

  it('leaves the first iteration after a set-up out of the time per iteration', () => {
    const record = new SolveRecord('subspace');
    record.add(its(88));
    expect(record.msPerIteration).toBe(0);
    expect(record.firstMs).toBe(88);
    record.add(its(27, 26, 29));
    expect(record.msPerIteration).toBe(27);
    record.expectSetUp(); // new handle groups
    record.add(its(70, 25));
    expect(record.msPerIteration).toBe(26.5); // median of 27, 26, 29, 25
    expect(record.sinceChange).toBe(6);
    record.changed();
    expect(record.progress(100, false)).toMatchObject({ iteration: 0, maxIterations: 100, msLeftAtMost: 100 * 26.5, runningMs: 0 });
  });
});

describe('saved scene text', () => {
  it('writes each vertex list and vector on one line and reads back as the same scene', () => {
    const scene = { example: 'bar', handles: [{ vertices: Array.from({ length: 300 }, (_, i) => i) },
      { vertices: [307, 308], translate: [0.1, -2.5e-7, 3], rotate: { axis: [0, 0, 1], angle: 0.5, center: [1, 0, 0] } }],
      solver: { method: 'subspace', maxIterations: 100 } };
    const text = sceneText(scene);
    expect(JSON.parse(text)).toEqual(scene);
    expect(text.split('\n').length).toBeLessThan(30); // JSON.stringify(scene, null, 2): 340 lines
    expect(text).toContain(`"vertices": [${scene.handles[0].vertices.join(', ')}]`);
    expect(text).toContain('"translate": [0.1, -2.5e-7, 3]');
    expect(parseScene(text, { modelOptional: true }).handles).toHaveLength(2);
  });

  // The numbers' regex used to reach into strings: "pull [1,2,3]" was saved as "pull [1, 2, 3]".
  it('leaves strings as they are, brackets, escaped quotes and all', () => {
    const scene = { example: 'bar', description: 'pull [1,2,3] then "[4,5]" \\ [6 ,7]', handles: [{ vertices: [1, 2] }] };
    const text = sceneText(scene);
    expect(JSON.parse(text)).toEqual(scene);
    expect(text).toContain('"vertices": [1, 2]');
  });
});
