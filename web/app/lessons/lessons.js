// Loading a lesson (catalogue.js) into the app through its public API: the views it compares, its scene
// (model, handles already moved, solver options, the basis and volume parts), whether the solver starts
// paused, and its camera direction. The lesson stays current (its caption shown) until a different model is
// loaded; a new cage or basis for the same model keeps it.
//
// Events: 'change' { lesson } with lesson = { id, title, caption, view } or null.
import { EventDispatcher } from 'three';
import { parseScene } from '../../lib/scene.js';
import { lessonScene } from './catalogue.js';

export class Lessons extends EventDispatcher {
  /** @param {import('../deformer_app.js').DeformerApp} app */
  constructor(app) {
    super();
    this.app = app;
    /** @type {{ id: string, title: string, caption: string, view: object|null, model: string }|null} */
    this.current = null;
    this.loading = false;
    app.addEventListener('load', (e) => {
      if (!this.loading && this.current && e.model.name !== this.current.model) this.#set(null);
    });
  }

  /**
   * Loads lesson `id` (an InputError naming the lessons for an unknown one). Resolves with the lesson once its
   * model is bound in every view it compares.
   */
  async load(id) {
    const raw = await lessonScene(id);
    const scene = parseScene(raw);
    const view = scene.view ?? { compare: null, direction: null, paused: false };
    const app = this.app;
    this.loading = true;
    try {
      await app.stepping.setPaused(view.paused);
      await app.setCompare(view.compare ?? false);
      await app.loadScene(raw);
    } finally {
      this.loading = false;
    }
    // Framed again with the moved handles' targets (the load framed the rest pose), from the lesson's side.
    app.fitView(view.direction ?? app.model.defaultView?.direction ?? undefined);
    this.#set({ id, title: raw.name ?? id, caption: raw.description ?? '', view, model: app.model.name });
    return this.current;
  }

  #set(lesson) {
    this.current = lesson;
    this.dispatchEvent({ type: 'change', lesson });
  }
}
