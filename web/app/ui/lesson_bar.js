// The current lesson's title and caption, in a bar between the views and the status bar (in the layout's
// flow: it covers no view, label or stats). The title toggles the caption; "restart" loads the lesson again.
// It never holds the app: it shows the app's state's current lesson (app_state.js) and sends one intent, loadLesson;
// the app calls only dispose().
export class LessonBar {
  /**
   * @param {HTMLElement} element the bar (AppLayout.lessonBar), hidden while no lesson is current
   * @param {{ state: import('../app_state.js').AppState, intents: { loadLesson: (id: string) => void } }} app
   */
  constructor(element, { state, intents }) {
    this.element = element;
    this.title = Object.assign(document.createElement('button'), { type: 'button', className: 'sd-lesson-title' });
    this.title.setAttribute('aria-expanded', 'true');
    this.title.onclick = () => this.#toggle();
    this.restart = Object.assign(document.createElement('button'), { type: 'button', className: 'sd-lesson-restart', textContent: 'restart' });
    this.restart.title = 'Load the lesson again: its model, handles and views as at the start';
    this.restart.onclick = () => intents.loadLesson(this.lesson.id);
    this.caption = Object.assign(document.createElement('p'), { className: 'sd-lesson-caption' });
    const head = Object.assign(document.createElement('div'), { className: 'sd-lesson-head' });
    head.append(this.title, this.restart);
    element.append(head, this.caption);
    element.hidden = true;
    this.lesson = null;
    this.unsubscribe = state.subscribe((change) => 'lesson' in change && this.#show(change.lesson));
  }

  #show(lesson) {
    this.lesson = lesson;
    this.element.hidden = !lesson;
    if (!lesson) return;
    this.title.textContent = `\u25be Lesson: ${lesson.title}`;
    this.caption.textContent = lesson.caption;
    this.caption.hidden = false;
  }

  /** Stops following the state and empties the bar (the app's dispose). */
  dispose() {
    this.unsubscribe();
    this.title.onclick = null;
    this.restart.onclick = null;
    this.element.replaceChildren();
    this.element.hidden = true;
  }

  #toggle() {
    this.caption.hidden = !this.caption.hidden;
    this.title.setAttribute('aria-expanded', String(!this.caption.hidden));
    this.title.textContent = `${this.caption.hidden ? '\u25b8' : '\u25be'} Lesson: ${this.lesson.title}`;
  }
}
