// The full-window app (index.html). URL parameters choose what loads and any setting:
//   ?example=sphere   ?scene=path/to/scene.json   ?mesh=a.obj&cage=b.obj   ?compare=1 (or arap,subspace, or
//   coordinates)   ?method=arap   ?jacobian=exact   ?coordinates=harmonic   ?wireframe=true ...   ?paused=1
//   (step-through from the first iteration)   ?lesson=arap-vs-subspace (a built-in lesson: lessons/catalogue.js)
//   ?noCage=generate|spectral (a mesh without a cage gets a generated one, or the spectral basis; default ask)
//   ?pose=1.... (a shared pose: the panel's "copy link to this pose"; loading/pose_link.js): its scene, the
//   methods it compares, paused or not and its camera direction; other parameters still set what it does not
// They are read and checked by the same tables as the embed's attributes and mount()'s options
// (page_options.js): a bad value is named in the banner and its default used, so the page never stays empty.
import { mount } from './embed/subspace_deformer_element.js';
import { kebabName, pageOptionsFromText } from './page_options.js';
import { POSE_PARAM, decodePose } from './loading/pose_link.js';

const params = new URLSearchParams(location.search);
const options = pageOptionsFromText((name) => params.get(name) ?? params.get(kebabName(name)));
// A shared pose: its scene replaces example/mesh/scene; a link that cannot be read is said in the banner.
const pose = params.has(POSE_PARAM) ? await decodePose(params.get(POSE_PARAM)).catch((error) => error) : null;
const view = pose instanceof Error ? null : pose?.view;
if (pose && !(pose instanceof Error)) {
  for (const name of ['example', 'mesh', 'cage', 'lesson']) delete options[name];
  Object.assign(options, { scene: pose }, view?.compare ? { compare: view.compare } : {}, view?.paused ? { paused: true } : {});
}
const app = mount(document.getElementById('app'), { ...options, shareLink: options.shareLink ?? true });
if (pose instanceof Error) app.ready.finally(() => app.banner.show(pose.message)).catch(() => {});
else if (view?.direction) app.ready.then(() => app.fitView(view.direction), () => {});
// For tests and the browser console.
globalThis.subspaceDeformer = app;
