// The lesson bar (web/app/ui/lesson_bar.js) follows the app's state until disposed: it shows the current lesson,
// sends loadLesson on "restart", and after dispose() it is empty and no change of the state reaches it.
// Node has no DOM: the few element calls the bar makes are stood in for.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { AppState } from '../../web/app/app_state.js';
import { LessonBar } from '../../web/app/ui/lesson_bar.js';

class StandInElement {
  constructor(tag) {
    Object.assign(this, { tag, children: [], hidden: false, textContent: '', attributes: {} });
  }
  append(...children) { this.children.push(...children); }
  replaceChildren() { this.children = []; }
  setAttribute(name, value) { this.attributes[name] = value; }
}

const LESSON = { id: 'volume', title: 'Volume kept', caption: 'The bar keeps its volume.', view: null };

describe('LessonBar', () => {
  let saved;
  beforeAll(() => {
    saved = globalThis.document;
    globalThis.document = { createElement: (tag) => new StandInElement(tag) };
  });
  afterAll(() => { globalThis.document = saved; });

  const make = () => {
    const state = new AppState();
    const sent = [];
    const element = new StandInElement('div');
    const bar = new LessonBar(element, { state, intents: { loadLesson: (id) => sent.push(id) } });
    return { state, sent, element, bar };
  };

  it('shows the state\'s lesson and restarts it through the intent', () => {
    const { state, sent, element, bar } = make();
    expect(element.hidden).toBe(true);
    state.update({ lesson: LESSON });
    expect(element.hidden).toBe(false);
    expect(bar.title.textContent).toMatch(/Volume kept/);
    expect(bar.caption.textContent).toBe(LESSON.caption);
    bar.restart.onclick();
    expect(sent).toEqual(['volume']);
  });

  it('after dispose() is empty, hidden and deaf to the state', () => {
    const { state, element, bar } = make();
    state.update({ lesson: LESSON });
    bar.dispose();
    expect(element.children).toEqual([]);
    expect(element.hidden).toBe(true);
    expect(bar.restart.onclick).toBe(null);
    state.update({ lesson: { ...LESSON, id: 'spectral', title: 'Spectral' } });
    expect(bar.lesson.id).toBe('volume'); // the change never reached it
    expect(element.hidden).toBe(true);
  });
});
