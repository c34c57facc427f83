// The app's CSS, injected once per document so the one-tag embed needs no stylesheet. Classes are
// prefixed sd- because the embed lives in the host page's DOM (lil-gui styles need the light DOM too).
const CSS = `
.sd-app { position: relative; display: flex; flex-direction: column; width: 100%; height: 100%; min-height: 320px; box-sizing: border-box;
  aspect-ratio: 16 / 10; /* applies only where the host gave no height (mount() into an unsized div) */
  overflow: hidden; font: 12px/1.35 system-ui, -apple-system, 'Segoe UI', sans-serif; color: #1d2430; background: #eef1f5;
  outline: none; }
.sd-main { position: relative; flex: 1; display: flex; min-height: 0; }
.sd-views { position: relative; flex: 1; display: flex; min-height: 0; min-width: 0; }
.sd-view { position: relative; flex: 1; min-width: 0; border-left: 1px solid #cfd6e0; touch-action: none; }
.sd-view:first-child { border-left: none; }
.sd-canvas { display: block; width: 100%; height: 100%; }
.sd-label { position: absolute; top: 6px; left: 8px; font-weight: 600; font-size: 13px; pointer-events: none;
  text-transform: none; color: #1d2430; }
.sd-cage-note { position: absolute; top: 24px; left: 8px; font-size: 11px; color: #5a6472; pointer-events: none; }
.sd-cage-note:empty { display: none; }
.sd-stats { position: absolute; left: 8px; bottom: 100px; pointer-events: none; white-space: pre-wrap; overflow-wrap: anywhere;
  max-width: calc(100% - 32px); box-sizing: border-box; font-variant-numeric: tabular-nums;
  background: rgba(255,255,255,0.8); padding: 3px 6px; border-radius: 4px; }
.sd-stats .sd-converged { color: #137a3a; font-weight: 600; }
.sd-stats .sd-solving { color: #b05a00; font-weight: 600; }
.sd-stats .sd-stopped { color: #a01c1c; font-weight: 600; }
.sd-stats .sd-paused { color: #2a5ea8; font-weight: 600; }
.sd-view.sd-compact .sd-plot { display: none; }
.sd-view.sd-compact .sd-stats { bottom: 6px; font-size: 11px; }
.sd-trace { position: absolute; top: 42px; right: 8px; max-width: min(520px, calc(100% - 16px)); z-index: 1; pointer-events: none;
  white-space: pre-wrap; font: 11px/1.35 ui-monospace, 'DejaVu Sans Mono', monospace; background: rgba(255,255,255,0.88);
  border: 1px solid #cfd6e0; border-radius: 4px; padding: 4px 6px; }
.sd-plot { position: absolute; left: 8px; bottom: 6px; border-radius: 4px; pointer-events: none; }
.sd-influence { position: absolute; top: 26px; right: 8px; width: 210px; z-index: 1; pointer-events: none;
  background: rgba(255,255,255,0.88); padding: 4px 6px; border-radius: 4px; font-size: 11px; }
.sd-influence-title { font-weight: 600; margin-bottom: 3px; }
.sd-influence-bar { display: flex; height: 10px; border-radius: 2px; overflow: hidden; border: 1px solid #b8c0cc; }
.sd-influence-negative { flex: 3; }
.sd-influence-positive { flex: 7; }
.sd-influence-ticks { display: flex; font-variant-numeric: tabular-nums; }
.sd-influence-ticks > span { display: flex; justify-content: space-between; }
.sd-influence-note { color: #4a5466; }
.sd-influence-note.sd-negative { color: #1a2f9c; font-weight: 600; }
.sd-lasso { position: absolute; inset: 0; width: 100%; height: 100%; pointer-events: none; }
.sd-lasso polyline { fill: rgba(255, 210, 31, 0.12); stroke: #d9a400; stroke-width: 1.5; stroke-dasharray: 4 3; }
.sd-lasso .sd-brush-cursor { fill: rgba(255, 210, 31, 0.15); stroke: #d9a400; stroke-width: 1.5; }
.sd-banner { position: absolute; top: 8px; left: 50%; transform: translateX(-50%); max-width: min(720px, 90%); z-index: 5;
  background: #fff1f0; border: 1px solid #e0a3a0; color: #7a1212; border-radius: 6px; padding: 8px 30px 8px 10px;
  white-space: pre-wrap; box-shadow: 0 2px 8px rgba(0,0,0,0.12); max-height: 45%; overflow: auto; }
.sd-banner.sd-info { background: #eef6ff; border-color: #9cc0e6; color: #123a66; }
.sd-banner.sd-warning { background: #fff8e6; border-color: #e2c275; color: #5c4200; }
.sd-banner button { margin: 6px 6px 0 0; }
.sd-banner .sd-banner-input { margin: 6px 8px 0 0; display: inline-block; }
.sd-banner .sd-banner-input input { width: 5em; }
.sd-banner .sd-close { position: absolute; top: 4px; right: 6px; border: none; background: none; font-size: 16px; cursor: pointer; color: inherit; margin: 0; }
.sd-progress { position: absolute; left: 50%; bottom: 50%; transform: translate(-50%, 50%); z-index: 6; width: min(360px, 80%);
  background: rgba(255,255,255,0.95); border: 1px solid #cfd6e0; border-radius: 6px; padding: 10px; box-shadow: 0 2px 10px rgba(0,0,0,0.15); }
.sd-progress-bar { height: 8px; background: #dde3ea; border-radius: 4px; overflow: hidden; margin: 6px 0; }
.sd-progress-bar > div { height: 100%; width: 0%; background: #f08a24; transition: width 0.1s; }
.sd-help { position: absolute; right: 8px; bottom: 6px; z-index: 2; font-size: 11px; color: #4a5466; pointer-events: none; text-align: right;
  background: rgba(255,255,255,0.75); padding: 3px 6px; border-radius: 4px; }
.sd-status { display: flex; justify-content: space-between; gap: 12px; padding: 2px 8px; font-size: 11px; line-height: 16px;
  color: #4a5466; background: #e3e8ee; border-top: 1px solid #cfd6e0; white-space: nowrap; overflow: hidden; }
.sd-model { overflow: hidden; text-overflow: ellipsis; min-width: 0; }
.sd-model-note { flex: 1 1 0; min-width: 0; overflow: hidden; text-overflow: ellipsis; border: none; background: none; padding: 0;
  margin: 0; font: inherit; color: #2b5d8a; cursor: pointer; text-align: left; }
.sd-model-note[hidden] { display: none; }
.sd-build-note { flex: none; color: #8a4a00; }
.sd-build-note:empty { display: none; }
.sd-fps { flex: none; font-variant-numeric: tabular-nums; }
/* The open panel sits beside the views, the lesson bar (its restart button, its caption) and the status bar. */
.sd-app.sd-panel-open:not(.sd-narrow):not(.sd-panel-float) .sd-main,
.sd-app.sd-panel-open:not(.sd-narrow):not(.sd-panel-float) .sd-lesson,
.sd-app.sd-panel-open:not(.sd-narrow):not(.sd-panel-float) .sd-status { margin-right: var(--sd-panel-width, 250px); }
.sd-drop { position: absolute; inset: 0; z-index: 7; display: none; align-items: center; justify-content: center;
  background: rgba(240, 138, 36, 0.12); border: 3px dashed #f08a24; font-size: 18px; color: #8a4a00; pointer-events: none; }
.sd-app.sd-dragover .sd-drop { display: flex; }
.sd-app .lil-gui.lil-root { position: absolute; top: 0; right: 0; z-index: 4; max-height: 100%; overflow-y: auto; touch-action: pan-y; }
/* With the tool strip its panel button opens the panel: a closed panel leaves no header over the views' labels. */
.sd-app.sd-has-tools .lil-gui.lil-root.lil-closed { display: none; }
/* Without it the closed header stays: the labels move under it. */
.sd-app.sd-has-panel:not(.sd-has-tools):not(.sd-panel-open) .sd-label { top: 30px; }
.sd-app.sd-has-panel:not(.sd-has-tools):not(.sd-panel-open) .sd-cage-note { top: 48px; }
/* Phones: a bottom sheet under the views, which move up (and are framed again) so the model stays in sight. */
.sd-app.sd-narrow .lil-gui.lil-root { top: auto; bottom: 0; left: 0; right: 0; width: auto !important; height: var(--sd-sheet, 50%);
  max-height: none; box-shadow: 0 -2px 12px rgba(0,0,0,0.2); border-radius: 10px 10px 0 0; }
.sd-app.sd-narrow.sd-panel-open:not(.sd-panel-float) { padding-bottom: var(--sd-sheet, 50%); } /* all of the rest above it */
/* lil-gui's touch styles give a slider's number 50 px at a 16 px font: Armijo c1's "0.0001" read "0.000", like zero. */
@media (pointer: coarse) {
  .sd-app .lil-gui.lil-allow-touch-styles, .sd-app .lil-gui.lil-allow-touch-styles .lil-gui { --slider-input-min-width: 64px; }
}
.sd-app.sd-narrow .sd-help { display: none; }
.sd-tools { flex: none; display: flex; flex-flow: column wrap; align-content: flex-start; gap: 2px; padding: 4px;
  background: #e3e8ee; border-right: 1px solid #cfd6e0; overflow: hidden; touch-action: manipulation; user-select: none; }
.sd-tool { width: var(--sd-tool, 40px); height: var(--sd-tool, 40px); padding: 2px 0 0; margin: 0; display: flex; flex-direction: column;
  align-items: center; justify-content: center; gap: 1px; border: 1px solid transparent; border-radius: 6px; background: none;
  color: #1d2430; font: 9px/1 system-ui, -apple-system, 'Segoe UI', sans-serif; cursor: pointer; touch-action: manipulation;
  -webkit-tap-highlight-color: transparent; }
@media (hover: hover) { .sd-tool:hover:not(:disabled) { background: #d3dae3; } }
.sd-tool.sd-on, .sd-tool.sd-on:hover { background: #f08a24; border-color: #c96a0e; color: #fff; }
.sd-tool:disabled { opacity: 0.35; cursor: default; }
.sd-tool[hidden] { display: none; }
.sd-icon { width: 20px; height: 20px; fill: none; stroke: currentColor; stroke-width: 1.8; stroke-linecap: round; stroke-linejoin: round; }
.sd-tool-gap { flex: none; height: 6px; width: var(--sd-tool, 40px); }
@media (pointer: coarse) { .sd-app { --sd-tool: 48px; } .sd-tool { font-size: 10px; } .sd-icon { width: 24px; height: 24px; } }
/* Phones and small embeds (sd-narrow): the strip is one row of icons over the views (it scrolls sideways when
   they do not all fit; the panel and help buttons come first, so opening the bottom sheet moves none of them),
   the views stack, and a banner sits in the flow under the views instead of over the model. */
.sd-app.sd-narrow .sd-main { flex-direction: column; }
.sd-app.sd-narrow .sd-tools { flex-flow: row nowrap; align-items: center; overflow-x: auto; overflow-y: hidden; padding: 2px 4px;
  border-right: none; border-bottom: 1px solid #cfd6e0; touch-action: pan-x; scrollbar-width: none; }
.sd-app.sd-narrow .sd-tools::-webkit-scrollbar { display: none; }
/* A shadow at an edge while more buttons lie beyond it: covers that scroll with the buttons hide it at the ends. */
.sd-app.sd-narrow .sd-tools { background: linear-gradient(to right, #e3e8ee 40%, rgba(227, 232, 238, 0)) left / 28px 100% no-repeat local,
  linear-gradient(to left, #e3e8ee 40%, rgba(227, 232, 238, 0)) right / 28px 100% no-repeat local,
  linear-gradient(to right, rgba(29, 36, 48, 0.28), rgba(29, 36, 48, 0)) left / 14px 100% no-repeat scroll,
  linear-gradient(to left, rgba(29, 36, 48, 0.28), rgba(29, 36, 48, 0)) right / 14px 100% no-repeat scroll, #e3e8ee; }
.sd-app.sd-narrow .sd-tool { flex: none; width: 44px; height: 44px; padding: 0; }
.sd-app.sd-narrow .sd-tool-label { display: none; }
.sd-app.sd-narrow .sd-tool-gap { width: 2px; height: 28px; border-left: 1px solid #c4ccd6; }
.sd-app.sd-narrow .sd-tool[data-action="panel"], .sd-app.sd-narrow .sd-tool[data-action="help"] { order: -1; }
/* Phones in landscape (sd-short, touch, too wide for sd-narrow): the strip is one column of the same 44 px icons
   down the side, scrolling when they do not all fit, the panel and help buttons first; its labelled buttons
   wrapped into three columns, 157 px of an 844 px screen. The views stay side by side: the screen is wide. */
@media (pointer: coarse) {
  .sd-app.sd-short:not(.sd-narrow) .sd-tools { flex-flow: column nowrap; align-items: center; overflow-y: auto; overflow-x: hidden;
    padding: 4px 2px; touch-action: pan-y; scrollbar-width: none; }
  .sd-app.sd-short:not(.sd-narrow) .sd-tools::-webkit-scrollbar { display: none; }
  .sd-app.sd-short:not(.sd-narrow) .sd-tool { flex: none; width: 44px; height: 44px; padding: 0; }
  .sd-app.sd-short:not(.sd-narrow) .sd-tool-label { display: none; }
  .sd-app.sd-short:not(.sd-narrow) .sd-tool-gap { width: 28px; height: 2px; border-top: 1px solid #c4ccd6; }
  .sd-app.sd-short:not(.sd-narrow) .sd-tool[data-action="panel"], .sd-app.sd-short:not(.sd-narrow) .sd-tool[data-action="help"] { order: -1; }
}
.sd-app.sd-narrow .sd-views { flex-direction: column; }
.sd-app.sd-narrow .sd-view { min-height: 0; border-left: none; border-top: 1px solid #cfd6e0; }
.sd-app.sd-narrow .sd-view:first-child { border-top: none; }
.sd-view.sd-tiny .sd-cage-note { display: none; }
.sd-view.sd-tiny .sd-stats { top: 4px; bottom: auto; left: auto; right: 6px; max-width: 60%; } /* the label's line: the model keeps the rest */
.sd-app.sd-narrow .sd-banner { position: relative; order: 1; flex: none; top: auto; left: auto; transform: none; max-width: none;
  max-height: 30%; border-radius: 0; border-width: 1px 0 0; box-shadow: none; }
.sd-app.sd-narrow .sd-lesson, .sd-app.sd-narrow .sd-status { order: 2; }
/* The status bar's texts shrink with an ellipsis (the build note's reason stays in its tooltip); no fps. */
.sd-app.sd-narrow .sd-status { gap: 8px; }
.sd-app.sd-narrow .sd-build-note { flex: 0 3 auto; min-width: 0; overflow: hidden; text-overflow: ellipsis; }
.sd-app.sd-narrow .sd-fps { display: none; }
.sd-lesson { flex: none; padding: 4px 10px 6px; background: #fff8ec; border-top: 1px solid #e8cf9f; color: #3d3322;
  max-height: 40%; overflow-y: auto; touch-action: pan-y; }
.sd-lesson[hidden] { display: none; }
.sd-lesson-head { display: flex; align-items: center; gap: 10px; }
.sd-lesson-title { flex: 1; text-align: left; border: none; background: none; padding: 2px 0; font: 600 13px system-ui, sans-serif;
  color: inherit; cursor: pointer; }
.sd-lesson-restart { flex: none; font-size: 11px; }
.sd-lesson-caption { margin: 2px 0 0; max-width: 80em; }
.sd-help-backdrop { position: absolute; inset: 0; z-index: 7; background: rgba(0, 0, 0, 0.2); }
.sd-help-card { position: absolute; z-index: 8; left: 50%; top: 50%; transform: translate(-50%, -50%); width: min(560px, 92%);
  box-sizing: border-box; /* the width with its padding: a phone's 390 px got a card of 409 px */
  max-height: 86%; overflow-y: auto; background: #fff; border: 1px solid #cfd6e0; border-radius: 8px; padding: 10px 34px 10px 14px;
  box-shadow: 0 4px 18px rgba(0,0,0,0.2); touch-action: pan-y; }
.sd-help-card h3 { margin: 6px 0 4px; font-size: 13px; }
.sd-help-card dl { display: grid; grid-template-columns: max-content 1fr; gap: 3px 10px; margin: 0 0 6px; }
.sd-help-card dt { font-weight: 600; }
.sd-help-card dd { margin: 0; }
.sd-help-card .sd-close { position: absolute; top: 4px; right: 6px; border: none; background: none; font-size: 20px; cursor: pointer; }
`;

export function injectStyles(doc = document) {
  if (doc.getElementById('sd-styles')) return;
  const style = doc.createElement('style');
  style.id = 'sd-styles';
  style.textContent = CSS;
  doc.head.appendChild(style);
}
