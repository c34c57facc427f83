// Touch screens in the browser tests: a phone or tablet context of Debian's Chromium (playwright-core's
// hasTouch and isMobile: touch events, a coarse pointer, the page's meta viewport) and fingers driven through
// the DevTools protocol (Input.dispatchTouchEvent), which Chromium turns into pointer events as a real touch
// screen does: taps, one-finger drags, holds, and two-finger pinches.
import { chromium } from 'playwright-core';
import { CHROMIUM_ARGS } from './browser.mjs';

export const PHONE = { width: 390, height: 844 }; // a 6.1" phone in portrait, CSS px
export const TABLET = { width: 820, height: 1180 }; // a 10.9" tablet in portrait
const GESTURE_GAP_MS = 400;
const REST_BEFORE_LIFT_MS = 300;

/**
 * A browser with one touch context (closed by the returned close()).
 * @param {{ width: number, height: number }} viewport
 */
export async function launchTouch(viewport) {
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium', headless: true, args: CHROMIUM_ARGS });
  const context = await browser.newContext({ viewport, hasTouch: true, isMobile: true, deviceScaleFactor: 2 });
  return { context, close: () => browser.close().catch(() => {}) };
}

const fingersOf = new WeakMap();

/**
 * Fingers on a page: every position in CSS px of the page's viewport. One per page (Fingers.on), so that its touch
 * events carry one clock of their own (DevTools' timestamp, never behind real time), by which Chromium's gesture
 * detection times them: a gesture starts a hand's pause (GESTURE_GAP_MS) after the last one, moves come a frame
 * (16 ms) apart, and fingers rest (REST_BEFORE_LIFT_MS) before they lift. Lifted at speed they would start a
 * fling, and Chromium does not turn the touch that stops a fling into a click (the next tap would be lost). So
 * the gestures are a hand's without the test waiting for the time they take.
 */
export class Fingers {
  static async on(page) {
    if (!fingersOf.has(page)) {
      const fingers = new Fingers();
      fingers.cdp = await page.context().newCDPSession(page);
      fingers.page = page;
      fingersOf.set(page, fingers);
    }
    return fingersOf.get(page);
  }

  #stamp = 0; // seconds since the epoch, as the protocol takes them

  #send(type, points, { afterMs = 0 } = {}) {
    this.#stamp = Math.max(this.#stamp + afterMs / 1000, Date.now() / 1000);
    return this.cdp.send('Input.dispatchTouchEvent',
      { type, touchPoints: points.map((p, i) => ({ x: p.x, y: p.y, id: p.id ?? i })), timestamp: this.#stamp });
  }

  /** A finger lands: a new gesture, a hand's pause after the last one by the touch clock. */
  #land(points) {
    return this.#send('touchStart', points, { afterMs: GESTURE_GAP_MS });
  }

  /** A move: the next animation frame (a touch screen reports a move per frame), then the move. */
  async #move(points) {
    await this.#frame();
    await this.#send('touchMove', points, { afterMs: 16 });
  }

  /** The fingers lift after resting where they are (by the touch clock): no fling follows. */
  async #lift() {
    await this.#send('touchEnd', [], { afterMs: REST_BEFORE_LIFT_MS });
    await this.#frame();
  }

  /** The page's next animation frame (what a lifted finger changed is then drawn). */
  #frame() {
    return this.page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
  }

  async tap(at) {
    await this.#land([at]);
    await this.#send('touchEnd', []);
    await this.#frame();
  }

  /**
   * One finger from `path[0]` through each point of `path`; holdUntil: a page expression the finger waits for,
   * still, before moving (a long press: e.g. the app has started its stroke).
   */
  async drag(path, { holdUntil = null } = {}) {
    await this.#land([path[0]]);
    if (holdUntil) await this.page.waitForFunction(holdUntil, null, { polling: 'raf' });
    for (const p of path.slice(1)) await this.#move([p]);
    await this.#lift();
  }

  /**
   * Two fingers: the first lands at a[0] (and may move along a first, a stroke that the second cancels), then
   * the second at b[0]; both move to their last points together.
   */
  async twoFinger(a, b, { firstAlone = 1, steps = 8 } = {}) {
    await this.#land([{ ...a[0], id: 0 }]);
    for (let i = 1; i <= firstAlone && i < a.length; ++i) await this.#send('touchMove', [{ ...a[i], id: 0 }]);
    const start = a[Math.min(firstAlone, a.length - 1)];
    await this.#send('touchStart', [{ ...start, id: 0 }, { ...b[0], id: 1 }]);
    const end = [a.at(-1), b.at(-1)];
    for (let i = 1; i <= steps; ++i) {
      const t = i / steps;
      const lerp = (p, q) => ({ x: p.x + t * (q.x - p.x), y: p.y + t * (q.y - p.y) });
      await this.#move([{ ...lerp(start, end[0]), id: 0 }, { ...lerp(b[0], end[1]), id: 1 }]);
    }
    await this.#lift();
  }
}

/** Taps a button (a locator) with a finger, as the next gesture. */
export async function tapButton(locator) {
  const page = locator.page();
  const fingers = await Fingers.on(page);
  await fingers.tap(await centre(locator));
  // What the button changed (a panel opening resizes the views, which are framed again a frame later).
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => r()))));
}

/** The centre of an element (a locator), for a tap. */
export async function centre(locator) {
  await locator.scrollIntoViewIfNeeded();
  const box = await locator.boundingBox();
  if (!box) throw new Error('the element is not visible');
  return { x: box.x + box.width / 2, y: box.y + box.height / 2 };
}
