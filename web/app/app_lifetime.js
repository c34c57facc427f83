// The app's life as its scripting API's promises see it. dispose() (an embed removed from the page disposes its
// app) stops the workers those promises wait on, and some waits never end then: a step-through step waiting for a
// request the terminated worker will never answer, a `ready` waiting for the banner's no-cage choice. Every such
// promise is raced against this one end, so it rejects with a CancelledError (code cancelled) instead of pending
// for ever.
import { CancelledError } from '../lib/errors.js';

export class AppLifetime {
  #leave;
  #gone = new Promise((_, reject) => (this.#leave = reject));

  constructor() {
    this.#gone.catch(() => {}); // nobody may be racing against it when it ends
  }

  /** Whether end() was called. */
  ended = false;

  /**
   * The outcome of `start()` (a function returning a promise or a value), or a CancelledError once the app is
   * disposed, whichever comes first. After end() it rejects at once without calling `start`: a disposed app's call
   * does nothing (no edit, no event, no wait on a promise nobody would handle). A synchronous throw rejects.
   */
  guard(start) {
    if (this.ended) return Promise.reject(AppLifetime.cancelled());
    return Promise.race([new Promise((resolve) => resolve(start())), this.#gone]);
  }

  /** The app is disposed: every guarded promise still pending rejects. */
  end() {
    this.ended = true;
    this.#leave(AppLifetime.cancelled());
  }

  /** The error a guarded promise rejects with. */
  static cancelled() {
    return new CancelledError('cancelled: the app was disposed');
  }
}
