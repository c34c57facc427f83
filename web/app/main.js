// The full-window app (index.html). URL parameters choose what loads and any setting:
//   ?example=sphere   ?scene=path/to/scene.json   ?mesh=a.obj&cage=b.obj   ?compare=1 (or arap,subspace, or
//   coordinates)   ?method=arap   ?jacobian=exact   ?coordinates=harmonic   ?wireframe=true ...   ?paused=1
//   (step-through from the first iteration)   ?lesson=arap-vs-subspace (a built-in lesson: lessons/catalogue.js)
//   ?noCage=generate|spectral (a mesh without a cage gets a generated one, or the spectral basis; default ask)
// They are read and checked by the same tables as the embed's attributes and mount()'s options
// (page_options.js): a bad value is named in the banner and its default used, so the page never stays empty.
import { mount } from './embed/subspace_deformer_element.js';
import { kebabName, pageOptionsFromText } from './page_options.js';

const params = new URLSearchParams(location.search);
const app = mount(document.getElementById('app'), pageOptionsFromText((name) => params.get(name) ?? params.get(kebabName(name))));
// For tests and the browser console.
globalThis.subspaceDeformer = app;
