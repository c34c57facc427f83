// The intents the tool strip, the keys, the lesson bar and the control panel send: the app's actions as plain
// functions, so that none of them holds the app (what they show comes from the app's state: app_state.js). Built
// once by the app; each calls the public API a script would (docs/embed.md), so a button, a key and a script do
// the same. Promises that fail are shown in the page, so the ones here are settled quietly. Beside them, the few
// read-only queries the panel makes of what the state does not hold (appQueries).
import { downloadGlb, downloadObj, downloadScene, downloadScreenshot } from './ui/download.js';
import { copyPoseLink } from './ui/share_link.js';

const quietly = (promise) => promise?.catch?.(() => {});

/** @param {import('./deformer_app.js').DeformerApp} app */
export function appIntents(app) {
  return Object.freeze({
    setOptions: (partial) => app.setOptions(partial),
    addGroupFromSelection: (moving) => app.addGroupFromSelection(moving),
    removeActiveGroup: () => app.removeActiveGroup(),
    clearGroups: () => app.clearGroups(),
    clearSelection: () => app.clearSelection(),
    undo: () => app.undo(),
    redo: () => app.redo(),
    resetHandles: () => quietly(app.resetHandles()),
    fitView: () => app.fitView(),
    loadLesson: (id) => quietly(app.loadLesson(id)),
    loadExample: (name) => quietly(app.loadExample(name)),
    openFilePicker: () => app.openFilePicker(),
    generateCage: (vertices) => quietly(app.generateCage(vertices)),
    setBasis: (basis, modes) => quietly(app.setBasis(basis, modes)),
    setCoordinates: (coordinates, resolution) => quietly(app.setCoordinates(coordinates, resolution)),
    setCompare: (compare) => quietly(app.setCompare(compare)),
    resolveFromRest: () => quietly(app.resolveFromRest()),
    setPanelOpen: (open) => app.setPanelOpen(open),
    toggleStepping: () => quietly(app.stepping.toggle()),
    nextStep: () => quietly(app.stepping.next()),
    nextHalfStep: () => quietly(app.stepping.nextHalf()),
    setPainting: (on) => app.parts.setPainting(on),
    togglePainting: () => app.parts.setPainting(!app.parts.painting),
    setPaintedPart: (part) => app.parts.setCurrent(part),
    keepPaintedParts: () => quietly(app.parts.apply()),
    autoParts: (count) => quietly(app.parts.auto(count)),
    defaultParts: () => quietly(app.parts.clear()),
    useParts: (description) => quietly(app.parts.use(description)),
    setPicking: (on) => app.influence.setPicking(on),
    togglePicking: () => app.influence.setPicking(!app.influence.picking),
    showInfluence: (column) => quietly(app.influence.show(column)),
    hideInfluence: () => app.influence.hide(),
    setBonesEnabled: (on) => quietly(app.skeleton.setEnabled(on)),
    deleteSelectedBone: () => quietly(app.skeleton.deleteSelected()),
    newBoneChain: () => app.skeleton.newChain(),
    clearSkeleton: () => quietly(app.skeleton.clear()),
    downloadObj: (what) => downloadObj(app, what),
    downloadGlb: () => downloadGlb(app),
    downloadScene: () => downloadScene(app),
    downloadScreenshot: () => downloadScreenshot(app),
    copyPoseLink: () => copyPoseLink(app),
  });
}

/**
 * What the panel reads that the state does not hold: the example names the bound model brought, the skeleton's
 * last report, and the stats as they are drawn (every tick, too often for the state's change event).
 * @param {import('./deformer_app.js').DeformerApp} app
 */
export function appQueries(app) {
  return Object.freeze({
    exampleNames: () => app.exampleNames,
    skeletonReport: () => app.skeleton.report,
    /** Calls `listener(stats)` each time the stats are drawn; returns the function that stops it. */
    followStats: (listener) => {
      const heard = (e) => listener(e.stats);
      app.addEventListener('stats', heard);
      return () => app.removeEventListener('stats', heard);
    },
  });
}
