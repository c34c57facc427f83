// The full-window app (index.html). URL parameters choose what loads:
//   ?example=sphere   ?scene=path/to/scene.json   ?mesh=a.obj&cage=b.obj   ?compare=1 (or arap,subspace, or
//   coordinates)   ?method=arap   ?coordinates=harmonic
import { mount } from './embed/subspace_deformer_element.js';

const params = new URLSearchParams(location.search);
const compare = params.get('compare');
const app = mount(document.getElementById('app'), {
  example: params.get('example') ?? undefined,
  scene: params.get('scene') ?? undefined,
  mesh: params.get('mesh') ?? undefined,
  cage: params.get('cage') ?? undefined,
  compare: compare === null || compare === '0' || compare === 'false' ? false : compare === '1' ? true : compare,
  settings: Object.fromEntries(['method', 'coordinates'].filter((key) => params.has(key)).map((key) => [key, params.get(key)])),
});
// For tests and the browser console.
globalThis.subspaceDeformer = app;
