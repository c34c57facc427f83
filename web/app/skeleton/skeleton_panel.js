// The control panel's Skeleton folder: the bone tool on/off (B), whether the solvers keep the bones, a new
// chain, deleting the selected bone or joint, clearing the skeleton, and a row with the bones' largest errors.
// Like the panel, it never holds the app: it sends intents, shows what the panel hands it of the app's state
// (follow: the settings' tool and the skeleton part) and reads the bones' report when the stats are drawn.
import { skeletonPanelText } from './skeleton_text.js';

/**
 * Adds the folder to the panel's lil-gui.
 * @param {import('lil-gui').default} gui
 * @param {{ settings: { tool: string }, intents: ReturnType<typeof import('../app_intents.js').appIntents>,
 *           report: () => object|null }} parts settings: the current ones; report: the first view's bones report
 * @returns {{ folder: object, follow: (change: object) => void, showStats: () => void }} follow: a change of the app's
 *   state; showStats: the errors row again (each time the stats are drawn)
 */
export function skeletonFolder(gui, { settings, intents, report }) {
  const folder = gui.addFolder('Skeleton');
  const skeleton = { bones: 0, enabled: true }; // the state's skeleton part, as last heard
  const state = { tool: settings.tool === 'bone', enabled: true, bones: skeletonPanelText(null, skeleton) };
  const button = (name, title, run) => {
    const c = folder.add({ [name]: run }, name);
    c.domElement.title = title;
  };
  const tool = folder.add(state, 'tool').name('bone tool (B)').onChange((on) => intents.setOptions({ tool: on ? 'bone' : 'pick' }));
  tool.domElement.title = 'taps place joints inside the mesh, midway through it; consecutive joints make bones';
  const enabled = folder.add(state, 'enabled').name('use bones').onChange((on) => intents.setBonesEnabled(on));
  enabled.domElement.title = 'the solvers keep every bone\'s length and keep it straight; off: the bones are only drawn';
  button('new chain (Esc)', 'the next joint starts a new chain (tap a joint to continue from it)', () => intents.newBoneChain());
  button('delete bone / joint (Del)', 'deletes the selected bone, or the chain\'s tip joint with its bones', () => intents.deleteSelectedBone());
  button('clear skeleton', 'no joints, no bones (undo brings them back)', () => intents.clearSkeleton());
  const bones = folder.add(state, 'bones').name('bones').disable();
  bones.domElement.title = 'the largest relative length and straightness errors over the bones (first view)';
  folder.close();

  let last = '';
  return {
    folder,
    follow(change) {
      if (change.settings?.tool !== undefined) {
        state.tool = change.settings.tool === 'bone';
        tool.updateDisplay();
      }
      if (!change.skeleton) return;
      if (change.skeleton.bones && !skeleton.bones) folder.open(); // the first bone made
      Object.assign(skeleton, { bones: change.skeleton.bones, enabled: change.skeleton.enabled });
      state.enabled = skeleton.enabled;
      enabled.updateDisplay();
    },
    showStats() {
      const text = skeletonPanelText(report(), skeleton);
      if (text === last) return;
      last = state.bones = text;
      bones.updateDisplay();
    },
  };
}
