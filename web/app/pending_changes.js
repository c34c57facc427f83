// What changed on the page and is still to be told to a session's worker (session.js): the solver options, the
// handle groups and the targets. Edits between two requests overwrite each other; send() tells the worker the
// latest of each once, options first, before the session's next step request.

export class PendingChanges {
  /** @param {object|null} options the worker's options to send first (a fresh worker needs them) */
  constructor(options = null) {
    this.options = options;
    this.handles = null; // vertex groups
    this.targets = null; // { targets, lines }
  }

  /**
   * Sends what is pending to `client`. Without handles the rest pose is the minimizer: the worker is reset
   * instead (its frame goes to `onRest`) and targets wait for handles.
   * @param {{ hasHandles: boolean, onRest: (frame: object) => void, fail: (error: Error) => void }} context
   */
  send(client, { hasHandles, onRest, fail }) {
    if (this.options) {
      client.request('setOptions', { options: this.options }).catch(fail);
      this.options = null;
    }
    if (this.handles) {
      if (hasHandles) client.request('setHandles', { groups: this.handles }).catch(fail);
      else client.request('reset').then(onRest).catch(fail);
      this.handles = null;
    }
    if (this.targets && hasHandles) {
      client.request('setTargets', this.targets).catch(fail);
      this.targets = null;
    }
  }
}
