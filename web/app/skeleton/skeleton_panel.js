// The control panel's Skeleton folder: the bone tool on/off (B), whether the solvers keep the bones, a new
// chain, deleting the selected bone or joint, clearing the skeleton, and a row with the bones' largest errors.
// Like the panel, it calls only the app's public API and follows its events ('skeleton', 'options', 'stats').
import { skeletonPanelText } from './skeleton_text.js';

/**
 * Adds the folder to the panel's lil-gui.
 * @param {import('lil-gui').default} gui
 * @param {import('../deformer_app.js').DeformerApp} app
 */
export function skeletonFolder(gui, app) {
  const folder = gui.addFolder('Skeleton');
  const state = { tool: app.settings.tool === 'bone', enabled: true, bones: skeletonPanelText(null, { bones: 0, enabled: true }) };
  const quietly = (promise) => promise?.catch?.(() => {}); // failures are shown in the page
  const button = (name, title, run) => {
    const c = folder.add({ [name]: run }, name);
    c.domElement.title = title;
  };
  const tool = folder.add(state, 'tool').name('bone tool (B)').onChange((on) => app.setOptions({ tool: on ? 'bone' : 'pick' }));
  tool.domElement.title = 'taps place joints inside the mesh, midway through it; consecutive joints make bones';
  const enabled = folder.add(state, 'enabled').name('use bones').onChange((on) => quietly(app.skeleton.setEnabled(on)));
  enabled.domElement.title = 'the solvers keep every bone\'s length and keep it straight; off: the bones are only drawn';
  button('new chain (Esc)', 'the next joint starts a new chain (tap a joint to continue from it)', () => app.skeleton.newChain());
  button('delete bone / joint (Del)', 'deletes the selected bone, or the chain\'s tip joint with its bones', () => quietly(app.skeleton.deleteSelected()));
  button('clear skeleton', 'no joints, no bones (undo brings them back)', () => quietly(app.skeleton.clear()));
  const bones = folder.add(state, 'bones').name('bones').disable();
  bones.domElement.title = 'the largest relative length and straightness errors over the bones (first view)';
  folder.close();

  let last = '';
  let had = false; // bones before the last event: the folder opens when the first bone is made
  const listeners = {
    options: (e) => {
      state.tool = e.settings.tool === 'bone';
      tool.updateDisplay();
    },
    skeleton: (e) => {
      state.enabled = e.enabled;
      enabled.updateDisplay();
      if (e.bones && !had) folder.open();
      had = e.bones > 0;
    },
    stats: () => {
      const text = skeletonPanelText(app.skeleton.report, { bones: app.skeleton.bones, enabled: app.skeleton.enabled });
      if (text === last) return;
      last = state.bones = text;
      bones.updateDisplay();
    },
    dispose: () => {
      for (const [type, listener] of Object.entries(listeners)) app.removeEventListener(type, listener);
    },
  };
  for (const [type, listener] of Object.entries(listeners)) app.addEventListener(type, listener);
  return folder;
}
