// The full-window app (index.html). URL parameters choose what loads:
//   ?example=sphere   ?scene=path/to/scene.json   ?mesh=a.obj&cage=b.obj   ?compare=1 (or arap,subspace)
//   ?method=arap   ?paused=1 (step-through from the first iteration)   ?lesson=arap-vs-subspace (lessons/catalogue.js)
import { mount } from './embed/subspace_deformer_element.js';

const params = new URLSearchParams(location.search);
const compare = params.get('compare');
const app = mount(document.getElementById('app'), {
  example: params.get('example') ?? undefined,
  lesson: params.get('lesson') ?? undefined,
  scene: params.get('scene') ?? undefined,
  mesh: params.get('mesh') ?? undefined,
  cage: params.get('cage') ?? undefined,
  compare: compare === null || compare === '0' || compare === 'false' ? false : compare === '1' ? true : compare,
  paused: params.get('paused') === '1',
  settings: params.get('method') ? { method: params.get('method') } : {},
});
// For tests and the browser console.
globalThis.subspaceDeformer = app;
