// The element's entry imported where there is no DOM (a server rendering a page that uses it, or a Node script
// that bundles it): the import must not throw, and defining the element does nothing there. It threw
// "HTMLElement is not defined" (an attack on the packed package).
import { describe, expect, it } from 'vitest';

describe('the embed element outside a browser', () => {
  it('imports without a DOM and defines nothing', async () => {
    expect(globalThis.HTMLElement).toBeUndefined(); // vitest's node environment
    const entry = await import('../../web/app/embed/index.js');
    expect(typeof entry.mount).toBe('function');
    expect(typeof entry.SubspaceDeformerElement).toBe('function');
    expect(() => entry.defineElement('sd-test-element')).not.toThrow();
  });
});
