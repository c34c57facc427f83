// A lone mesh without a cage is never a dead end, as the first model or a later one: the page chooses up front
// (mount()'s `noCage`, the element's `no-cage` attribute, the app's ?noCage=; page_options.js NO_CAGE_CHOICES)
// or the banner asks with two buttons (load_offers.js offerCage): 'generate' (a generated cage of
// settings.cageVertices) or 'spectral' (the mesh's own spectral basis of settings.spectralModes, no cage needed).
// The load that follows the choice binds the mesh's kept files again; once it is bound the loader dispatches
// 'nocage' { choice, model } after 'load'. While the first model waits for the user's choice, the app's `ready`
// waits too (deformable()).
import { CancelledError } from '../../lib/errors.js';
import { isCancelled } from '../errors.js';
import { offerCage } from './load_offers.js';

export class NoCage {
  /**
   * @param {{ loader: import('./model_loader.js').ModelLoader, choice?: 'ask'|'generate'|'spectral',
   *           load: (files: object[], generateCage: { vertices: number }|null, options: object) => Promise<object>,
   *           keptNote: () => string }} parts load: the loader's meshFiles; keptNote: whether a model stays
   */
  constructor({ loader, choice = 'ask', load, keptNote }) {
    this.loader = loader;
    this.choice = choice;
    this.load = load;
    this.keptNote = keptNote;
  }

  /** The files of the lone mesh refused last for having no cage, while no model was bound since; else null. */
  waiting = null;

  /**
   * A lone mesh's load failed for want of a cage (or its generation failed or was cancelled): with a choice made
   * up front and `missing` (the cage was missing, and the load was no choice's), the same request loads it that
   * way; else the banner asks. Rejects with `error` when asking.
   */
  async refused(files, error, ticket, missing) {
    this.waiting = files;
    if (this.choice !== 'ask' && missing) return this.choose(this.choice, {}, ticket);
    const message = isCancelled(error) ? `Cage generation for ${files[0].name} cancelled.` : error.message;
    offerCage(this.loader, message, this.keptNote(), (choice, sizes) => this.choose(choice, sizes, this.loader.request(), files));
    throw error;
  }

  /**
   * Loads the waiting mesh as `choice` says: 'generate' with about `vertices` cage vertices, or 'spectral' with
   * `modes` modes (the basis setting goes back if that fails; the modes stay, as a refusal over the memory budget
   * lowered them). The sizes default to the settings, and become them. `files`: the waiting mesh's by default.
   */
  choose(choice, { vertices, modes } = {}, ticket = this.loader.request(), files = this.waiting) {
    const { settings } = this.loader;
    if (choice === 'generate') {
      settings.update({ cageVertices: vertices ?? settings.values.cageVertices });
      return this.load(files, { vertices: settings.values.cageVertices }, { choice, ticket });
    }
    const before = settings.values.basis;
    settings.update({ basis: 'spectral', spectralModes: modes ?? settings.values.spectralModes });
    return this.load(files, null, { choice, ticket }).catch((failure) => {
      settings.update({ basis: before });
      throw failure;
    });
  }

  /** A model was bound: nothing waits any more. */
  bound() { this.waiting = null; }
}

/**
 * The app's `ready`: the first load, or where that stopped at a lone mesh that waits for the user's choice, the
 * model the next load binds (the choice's, or any other the user or a script loads). Disposed while it waits (the
 * loader's 'dispose'), it rejects with a CancelledError: no choice can come any more.
 * @param {Promise<object>} first
 * @param {import('./model_loader.js').ModelLoader} loader
 */
export function deformable(first, loader) {
  return first.catch((error) => {
    if (!loader.noCage.waiting || loader.model) throw error;
    return new Promise((resolve, reject) => {
      const settle = (e) => {
        loader.removeEventListener('load', settle);
        loader.removeEventListener('dispose', settle);
        if (e.type === 'load') resolve(e.model);
        else reject(new CancelledError('cancelled: the app was disposed'));
      };
      loader.addEventListener('load', settle);
      loader.addEventListener('dispose', settle);
    });
  });
}
