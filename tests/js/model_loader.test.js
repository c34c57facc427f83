// What the app's ModelLoader lets go of when the app is disposed (an embed removed from the page). It had no
// dispose(): the model's look (a glTF's geometries and the object URLs of its separate files) stayed, a fetch under
// way ran on and its load then started workers for views that were gone, and `ready` waiting for a lone mesh's
// no-cage choice never settled. Stand-in views, banner and progress bar (Node has no DOM).
import { afterEach, describe, expect, it, vi } from 'vitest';
import { ModelLoader } from '../../web/app/loading/model_loader.js';
import { deformable } from '../../web/app/loading/no_cage.js';
import { AppSettings } from '../../web/app/settings.js';
import { CancelledError } from '../../web/lib/errors.js';

function standIn() {
  const session = { client: null, model: null, loading: null, cancelLoad() {} };
  const view = { session, coordinates: null };
  const banner = { show: vi.fn(), hide() {} };
  const progress = { start: vi.fn(), set() {}, done() {} };
  const loader = new ModelLoader({ views: { list: [view], first: view }, banner, progress, settings: new AppSettings(), editor: {}, parts: {}, skeleton: {} });
  return { loader, banner, progress };
}

const tick = () => new Promise((resolve) => setTimeout(resolve, 0));
const lone = [{ name: 'lone.obj', bytes: new Uint8Array(8) }];

afterEach(() => vi.unstubAllGlobals());

describe('ModelLoader.dispose', () => {
  it('lets go of the model\'s look and a waiting mesh, and later loads reject as cancelled before they bind', async () => {
    const { loader, progress } = standIn();
    const look = { dispose: vi.fn() }; // gltf_look.js: revokes its object URLs, disposes its geometries
    loader.model = { name: 'model.gltf', look };
    loader.noCage.waiting = lone;
    loader.dispose();
    expect(look.dispose).toHaveBeenCalledTimes(1);
    expect(loader.model).toBe(null);
    expect(loader.noCage.waiting).toBe(null);
    expect(loader.disposed).toBe(true);
    const refused = await loader.example('bar').catch((error) => error);
    expect(refused).toBeInstanceOf(CancelledError);
    expect(refused.message).toBe('Loading bar cancelled: the app was disposed');
    expect(progress.start).not.toHaveBeenCalled(); // nothing was started
  });

  it('stops a fetch under way; its load rejects as cancelled, not as a failed fetch in the banner', async () => {
    vi.stubGlobal('document', { baseURI: 'http://localhost/course/' });
    const signals = [];
    vi.stubGlobal('fetch', (url, options) => new Promise((_, reject) => {
      signals.push(options?.signal);
      options?.signal?.addEventListener('abort', () => reject(new DOMException('The user aborted a request.', 'AbortError')));
    }));
    const { loader, banner, progress } = standIn();
    const loading = loader.urls('mesh.obj').catch((error) => error);
    await tick();
    loader.dispose();
    const outcome = await Promise.race([loading, new Promise((resolve) => setTimeout(() => resolve('still pending'), 1000))]);
    expect(outcome).toBeInstanceOf(CancelledError);
    expect(signals.map((s) => s?.aborted)).toEqual([true]);
    expect(banner.show).not.toHaveBeenCalled();
    expect(progress.start).not.toHaveBeenCalled();
  });

  it('rejects the app\'s `ready` that waits for a lone mesh\'s choice', async () => {
    const { loader } = standIn();
    loader.noCage.waiting = lone; // the first load stopped at a mesh without a cage; the banner asks
    const ready = deformable(Promise.reject(new Error('no cage')), loader).catch((error) => error);
    await tick();
    loader.dispose();
    const outcome = await Promise.race([ready, new Promise((resolve) => setTimeout(() => resolve('still pending'), 1000))]);
    expect(outcome).toBeInstanceOf(CancelledError);
  });

  // A reviewer's find: a .gltf's own files (its .bin, its textures) were fetched without the loader's abort signal,
  // so they ran on after dispose() although the .gltf's own fetch was aborted.
  it('stops the fetch of a .gltf\'s own files (its .bin) under way too', async () => {
    vi.stubGlobal('document', { baseURI: 'http://localhost/course/' });
    const gltf = new TextEncoder().encode(JSON.stringify({ asset: { version: '2.0' }, buffers: [{ uri: 'model.bin', byteLength: 12 }] }));
    const fetched = [];
    vi.stubGlobal('fetch', (url, options) => new Promise((resolve, reject) => {
      fetched.push({ url: String(url), signal: options?.signal });
      if (String(url).endsWith('.gltf')) resolve({ ok: true, headers: null, arrayBuffer: async () => gltf.buffer });
      options?.signal?.addEventListener('abort', () => reject(new DOMException('The user aborted a request.', 'AbortError')));
    }));
    const { loader, banner } = standIn();
    const loading = loader.urls('model.gltf').catch((error) => error);
    while (fetched.length < 2) await tick();
    loader.dispose();
    const outcome = await Promise.race([loading, new Promise((resolve) => setTimeout(() => resolve('still pending'), 1000))]);
    expect(fetched.map((f) => [f.url, f.signal?.aborted])).toEqual([['http://localhost/course/model.gltf', true], ['http://localhost/course/model.bin', true]]);
    expect(outcome).toBeInstanceOf(CancelledError);
    expect(banner.show).not.toHaveBeenCalled();
  });

  // A reviewer's find: generateCage() (a promise for its callers, who only .catch it: load_offers.js) threw at the
  // call once the loader was disposed, so the banner action's .catch never saw the refusal.
  it('generateCage() after dispose rejects, never throws at the call', async () => {
    const { loader } = standIn();
    loader.dispose();
    let result;
    expect(() => { result = loader.generateCage(60); }).not.toThrow();
    await expect(result).rejects.toBeInstanceOf(CancelledError);
  });
});
