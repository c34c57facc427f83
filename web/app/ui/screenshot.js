// One PNG of several views side by side (compare mode), each drawn at full quality first.

/**
 * @param {import('../view/viewport.js').Viewport[]} viewports
 * @returns {string} a PNG data URL
 */
export function screenshotOf(viewports) {
  const canvases = viewports.map((viewport) => {
    viewport.renderFull();
    return viewport.canvas;
  });
  const out = document.createElement('canvas');
  out.width = canvases.reduce((w, c) => w + c.width, 0);
  out.height = Math.max(...canvases.map((c) => c.height));
  const ctx = out.getContext('2d');
  let x = 0;
  for (const c of canvases) {
    ctx.drawImage(c, x, 0);
    x += c.width;
  }
  return out.toDataURL('image/png');
}
