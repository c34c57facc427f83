// What the app's collaborators hold that the tool strip and the panel show (the model, the views, the handle groups
// and the selection, the step-through, the volume parts, the influence view, the skeleton, and the one undo timeline), summarised
// as the app's state parts (app_state.js). The app copies it in after each of their changes; they still own it.

/**
 * @param {{ model: object|null, views: import('./view/solver_views.js').SolverViews,
 *           editor: import('./interaction/handle_editor.js').HandleEditor,
 *           skeleton: { joints: number, bones: number, enabled: boolean },
 *           stepping: import('./step_through.js').StepThrough, parts: { painting: boolean, current: number, count: number },
 *           influence: { picking: boolean, column: number|null }, timeline: { canUndo: boolean, canRedo: boolean } }} collaborators
 * @returns {{ model: object|null, views: object, handles: object, stepping: object, parts: object, influence: object,
 *             skeleton: object }} parts for AppState.update
 */
export function collaboratorState({ model, views, editor, skeleton, stepping, parts, influence, timeline }) {
  return {
    model,
    views: { compare: views.compare, keys: views.list.map((v) => v.key) },
    handles: { ...editor.summary(), canUndo: timeline.canUndo, canRedo: timeline.canRedo },
    stepping: { paused: stepping.paused, hasArap: stepping.hasArap, nextPhase: stepping.nextPhase },
    parts: { painting: parts.painting, current: parts.current, count: parts.count },
    influence: { picking: influence.picking, column: influence.column },
    skeleton: { joints: skeleton.joints, bones: skeleton.bones, enabled: skeleton.enabled },
  };
}
