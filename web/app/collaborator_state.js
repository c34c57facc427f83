// What the app's collaborators hold that the tool strip shows (the model, the views, the handle groups and the
// selection, the skeleton's undo, the step-through), summarised as the app's state parts (app_state.js). The app
// copies it in after each of their changes; they still own it.

/**
 * @param {{ model: object|null, views: import('./view/solver_views.js').SolverViews,
 *           editor: import('./interaction/handle_editor.js').HandleEditor, skeleton: { canUndo: boolean, canRedo: boolean },
 *           stepping: import('./step_through.js').StepThrough }} collaborators
 * @returns {{ model: object|null, views: object, handles: object, stepping: object }} parts for AppState.update
 */
export function collaboratorState({ model, views, editor, skeleton, stepping }) {
  const { undoStack, redoStack } = editor.handles;
  return {
    model,
    views: { compare: views.compare, keys: views.list.map((v) => v.key) },
    handles: { ...editor.summary(), canUndo: undoStack.length > 0 || skeleton.canUndo, canRedo: redoStack.length > 0 || skeleton.canRedo },
    stepping: { paused: stepping.paused, hasArap: stepping.hasArap, nextPhase: stepping.nextPhase },
  };
}
