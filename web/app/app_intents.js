// The intents the tool strip, the keys and the lesson bar send: the app's actions as plain functions, so that neither holds the
// app (what they show comes from the app's state: app_state.js). Built once by the app; each calls the public API
// a script would (docs/embed.md), so a button, a key and a script do the same. Promises that fail are shown in
// the page, so the ones here are settled quietly.

const quietly = (promise) => promise?.catch?.(() => {});

/** @param {import('./deformer_app.js').DeformerApp} app */
export function appIntents(app) {
  return Object.freeze({
    setOptions: (partial) => app.setOptions(partial),
    addGroupFromSelection: (moving) => app.addGroupFromSelection(moving),
    removeActiveGroup: () => app.removeActiveGroup(),
    clearSelection: () => app.clearSelection(),
    undo: () => app.undo(),
    redo: () => app.redo(),
    fitView: () => app.fitView(),
    loadLesson: (id) => quietly(app.loadLesson(id)),
    setPanelOpen: (open) => app.setPanelOpen(open),
    toggleStepping: () => quietly(app.stepping.toggle()),
    nextStep: () => quietly(app.stepping.next()),
    nextHalfStep: () => quietly(app.stepping.nextHalf()),
    togglePainting: () => app.parts.setPainting(!app.parts.painting),
    togglePicking: () => app.influence.setPicking(!app.influence.picking),
    deleteSelectedBone: () => app.skeleton.deleteSelected(),
    newBoneChain: () => app.skeleton.newChain(),
  });
}
