// Loading a lesson (catalogue.js) into the app through the parts and the public API the app hands it, never the
// app itself: the views it compares, its scene (model, handles already moved, solver options on top of the app's
// first ones, so that no earlier choice makes its caption false; the basis and volume parts), whether the solver
// starts paused, and its camera direction. The lesson stays current (its caption shown) until a different model is
// loaded (the app calls onLoad); a new cage or basis for the same model keeps it. A lesson is one of the user's load
// requests (ModelLoader's tickets): a load asked for while the lesson waits (for its scene, the views) wins, and the
// lesson then stops where it is, rejecting with a CancelledError, and changes nothing: what it changed before its
// model was bound (the views it compares, paused) goes back at once, before that load picks its views.
//
// Events: 'change' { lesson } with lesson = { id, title, caption, view } or null.
import { EventDispatcher } from 'three';
import { parseScene } from '../../lib/scene.js';
import { lessonScene } from './catalogue.js';

export class Lessons extends EventDispatcher {
  /**
   * @param {{ loader: import('../loading/model_loader.js').ModelLoader, banner: { show: Function },
   *           stepping: import('../step_through.js').StepThrough, setCompare: (compare: unknown) => Promise<unknown>,
   *           fitView: (direction?: number[]) => void }} parts loader: the app's (the lesson's scene loads there, its
   *   model is the bound one); setCompare, fitView: the app's public API
   */
  constructor({ loader, banner, stepping, setCompare, fitView }) {
    super();
    Object.assign(this, { loader, banner, stepping, setCompare, fitView });
    /** @type {{ id: string, title: string, caption: string, view: object|null, model: string }|null} */
    this.current = null;
    // A later request replaces the lesson loading: its views go back before that request binds in them.
    loader.addEventListener('request', (e) => this.#before?.ticket !== e.ticket && this.#undo(this.#before));
  }

  /** A model was bound: another model ends the lesson, unless it is the one of a lesson still loading as the user's last request. */
  onLoad(model) {
    const loading = this.#ticket !== null && this.loader.isNewest(this.#ticket);
    if (loading) this.#before = null; // the lesson's model is on screen: nothing to take back any more
    if (!loading && this.current && model.name !== this.current.model) this.#set(null);
  }

  #ticket = null; // the request of the lesson loading, or null
  #before = null; // { ticket, keys, paused }: the views and step-through before the lesson loading changed them

  // The views and step-through as they were before the lesson of `before` (if it still has them to take back).
  #undo(before) {
    if (!before || this.#before !== before) return;
    this.#before = null;
    const { keys } = before;
    if (this.loader.views.list.map((v) => v.key).join() !== keys.join()) this.setCompare(keys.length > 1 ? keys : false).catch(() => {});
    if (this.stepping.paused !== before.paused) this.stepping.setPaused(before.paused).catch(() => {}); // rejects once the app is disposed
  }

  /**
   * Loads lesson `id` (an InputError naming the lessons for an unknown one, shown in the banner too). Resolves
   * with the lesson once its model is bound in every view it compares.
   */
  async load(id) {
    const ticket = this.loader.request(); // now: a load the user asks for while this one waits wins
    const raw = await lessonScene(id).catch((error) => {
      if (this.loader.isNewest(ticket)) this.banner.show(error.message);
      throw error;
    });
    const scene = parseScene(raw);
    const view = scene.view ?? { compare: null, direction: null, paused: false };
    const stillNewest = () => this.loader.checkNewest(ticket, `Lesson ${id}`);
    this.#ticket = ticket;
    const before = { ticket, keys: this.loader.views.list.map((v) => v.key), paused: this.stepping.paused };
    try {
      stillNewest();
      this.#before = before;
      await this.stepping.setPaused(view.paused);
      stillNewest();
      await this.setCompare(view.compare ?? false);
      await this.loader.loadScene(raw, { ticket, fresh: true }); // cancelled there if no longer the newest; settings: the lesson's alone
    } catch (error) {
      this.#undo(before); // failed or cancelled (the progress bar's Cancel): as before it
      throw error;
    } finally {
      if (this.#ticket === ticket) this.#ticket = null;
      if (this.#before === before) this.#before = null;
    }
    // Framed again with the moved handles' targets (the load framed the rest pose), from the lesson's side.
    const model = this.loader.model;
    this.fitView(view.direction ?? model.defaultView?.direction ?? undefined);
    this.#set({ id, title: raw.name ?? id, caption: raw.description ?? '', view, model: model.name });
    return this.current;
  }

  #set(lesson) {
    this.current = lesson;
    this.dispatchEvent({ type: 'change', lesson });
  }
}
