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

  /** `promise`'s outcome, or a CancelledError once the app is disposed, whichever comes first. */
  guard(promise) {
    return this.ended ? Promise.reject(AppLifetime.cancelled()) : Promise.race([promise, this.#gone]);
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
