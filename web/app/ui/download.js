// Saving what the app shows as files, through a temporary <a download> link: the panel's Export folder.
// Each takes the app (its public API) and names the file after the model.
import { sceneText } from '../loading/saved_scene.js';

/** A file-name stem from a model name: no extension, only letters, digits, '_' and '-'. */
function baseName(name = 'model') {
  return String(name).replace(/\.[a-z0-9]+$/i, '').replace(/[^\w-]+/g, '_');
}

/** The deformed mesh ('mesh') or cage ('cage') of the first view, or the cage at rest ('restCage'), as OBJ. */
export async function downloadObj(app, what) {
  try {
    const text = await app.exportObj(what);
    const name = baseName(app.model?.name);
    downloadText(text, what === 'restCage' ? `${name}-cage.obj` : `${name}-${app.views[0].method}-deformed${what === 'cage' ? '-cage' : ''}.obj`);
  } catch (error) {
    app.banner.show(`export failed: ${error.message}`);
  }
}

/**
 * The deformed mesh of the first view as binary glTF in the model's own vertex layout (a glTF model keeps its
 * materials, textures, UVs and nodes).
 */
export async function downloadGlb(app) {
  try {
    const bytes = await app.exportGlb();
    const url = URL.createObjectURL(new Blob([bytes], { type: 'model/gltf-binary' }));
    clickLink(url, `${baseName(app.model?.name)}-${app.views[0].method}-deformed.glb`);
    setTimeout(() => URL.revokeObjectURL(url), 10000);
  } catch (error) {
    app.banner.show(`export failed: ${error.message}`);
  }
}

/** The current scene (JSON). It holds the parts the solvers keep: paint not kept is said to be left out. */
export function downloadScene(app) {
  downloadText(sceneText(app.sceneJson()), `${baseName(app.model?.name)}-scene.json`, 'application/json');
  if (app.parts.unkeptPaint) {
    app.banner.show('Scene saved with the volume parts the solvers keep: the paint not kept yet is not in it ("keep painted parts" first to save it).', { kind: 'info' });
  }
}

/** A PNG of all views side by side. */
export function downloadScreenshot(app) {
  clickLink(app.screenshot(), `${baseName(app.model?.name)}-${app.compare ? 'compare' : app.views[0].method}.png`);
}

function downloadText(text, filename, type = 'text/plain') {
  const url = URL.createObjectURL(new Blob([text], { type }));
  clickLink(url, filename);
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

function clickLink(href, filename) {
  const a = document.createElement('a');
  a.href = href;
  a.download = filename;
  a.style.display = 'none';
  document.body.appendChild(a);
  a.click();
  a.remove();
}
