// The embed element's life in the document, with a stand-in app (Node has no DOM, so the element class is a plain
// one here and its callbacks are called as the browser would). A move within the document (wrap.append(el):
// disconnect, then connect in the same task) disposed the app and mounted a fresh one from the attributes, losing
// the pose, handles and parts; two methods threw a TypeError instead of the documented InputError before the
// element was in the document; and attributes changed after the start were ignored without a word.
import { describe, expect, it, vi } from 'vitest';
import { SubspaceDeformerElement } from '../../web/app/embed/subspace_deformer_element.js';
import { InputError } from '../../web/lib/errors.js';

/** An element with a stand-in app, as connectedCallback leaves it; `isConnected` set by hand (no DOM). */
function connected() {
  const el = new SubspaceDeformerElement();
  const app = { disposed: 0, dispose() { this.disposed++; } };
  Object.assign(el, { app, isConnected: true });
  return { el, app };
}
const microtasks = () => new Promise((resolve) => setTimeout(resolve, 0));

describe('<subspace-deformer> in and out of the document', () => {
  it('keeps its app when moved (disconnected and connected again in one task)', async () => {
    const { el, app } = connected();
    el.isConnected = false;
    el.disconnectedCallback();
    el.isConnected = true;
    el.connectedCallback(); // the app is there: nothing is mounted again
    await microtasks();
    expect(app.disposed).toBe(0);
    expect(el.app).toBe(app);
  });

  it('disposes its app once removed for good, after the current script', async () => {
    const { el, app } = connected();
    el.isConnected = false;
    el.disconnectedCallback();
    await microtasks();
    expect(app.disposed).toBe(1);
    expect(el.app).toBe(null);
  });

  it('has no app before it connects, and every method then throws an InputError', () => {
    const el = new SubspaceDeformerElement();
    expect(el.app).toBe(null);
    for (const call of [() => el.exportGlb(), () => el.setCoordinates('pmvc'), () => el.drag(0, [0, 0, 0]), () => el.exportObj()]) {
      expect(call).toThrow(InputError);
    }
  });
});

describe('<subspace-deformer> attributes changed after it started', () => {
  it('observes every attribute it reads, as HTML spells them', () => {
    const names = SubspaceDeformerElement.observedAttributes;
    for (const name of ['example', 'method', 'no-cage', 'compare', 'maxiterations', 'max-iterations']) expect(names).toContain(name);
  });

  it('warns once in the console, naming the API to use; nothing before the app starts', () => {
    const warn = vi.spyOn(console, 'warn').mockImplementation(() => {});
    try {
      const idle = new SubspaceDeformerElement();
      idle.attributeChangedCallback('example', null, 'bar'); // the parser's first values: read at connect
      expect(warn).not.toHaveBeenCalled();
      const { el } = connected();
      el.attributeChangedCallback('method', null, 'arap');
      el.attributeChangedCallback('example', 'bar', 'sphere');
      expect(warn).toHaveBeenCalledTimes(1);
      expect(warn.mock.calls[0][0]).toMatch(/"method".*read once.*setOptions.*loadExample/);
    } finally {
      warn.mockRestore();
    }
  });
});
