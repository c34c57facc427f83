// Whether a scene fits a model, asked before the model replaces anything (model_loader.js): a scene with its own
// model is checked on it in the worker that bound it, one without on the model on screen.
import { handleTargets } from '../../lib/scene.js';

/**
 * Whether a parsed scene fits a model: its handles name vertices the mesh has and move them to finite targets within
 * the coordinates a mesh may have (handleTargets), and its volume parts and skeleton can be made on it (by `client`'s
 * worker, which holds that model). Throws the error naming what does not fit.
 * @returns {Promise<Int32Array|null>} the partition the worker made (one part per triangle), or null
 */
export async function sceneFits(scene, model, client) {
  handleTargets(model.mesh.positions, scene.handles);
  if (scene.skeleton && client) await client.request('setSkeleton', { skeleton: scene.skeleton }); // joints inside the mesh
  if (!scene.volumeParts || !client) return null;
  const { parts } = await client.request('setVolumeParts', { parts: scene.volumeParts });
  return parts;
}
