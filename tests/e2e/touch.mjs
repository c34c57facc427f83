// Touch screens in the browser tests: a phone or tablet context of Debian's Chromium (playwright-core's
// hasTouch and isMobile: touch events, a coarse pointer, the page's meta viewport) and fingers driven through
// the DevTools protocol (Input.dispatchTouchEvent), which Chromium turns into pointer events as a real touch
// screen does: taps, one-finger drags, holds, and two-finger pinches.
import { chromium } from 'playwright-core';
import { CHROMIUM_ARGS } from './browser.mjs';

export const PHONE = { width: 390, height: 844 }; // a 6.1" phone in portrait, CSS px
export const TABLET = { width: 820, height: 1180 }; // a 10.9" tablet in portrait
const GESTURE_GAP_MS = 400;

/**
 * A browser with one touch context (closed by the returned close()).
 * @param {{ width: number, height: number }} viewport
 */
export async function launchTouch(viewport) {
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium', headless: true, args: CHROMIUM_ARGS });
  const context = await browser.newContext({ viewport, hasTouch: true, isMobile: true, deviceScaleFactor: 2 });
  return { context, close: () => browser.close().catch(() => {}) };
}

/** Fingers on a page: every position in CSS px of the page's viewport. */
export class Fingers {
  static async on(page) {
    const fingers = new Fingers();
    fingers.cdp = await page.context().newCDPSession(page);
    fingers.page = page;
    return fingers;
  }

  #send(type, points) {
    return this.cdp.send('Input.dispatchTouchEvent', { type, touchPoints: points.map((p, i) => ({ x: p.x, y: p.y, id: p.id ?? i })) });
  }

  /**
   * After a finger lifts: the next frame, then the pause a hand takes before the next touch. Chromium's gesture
   * detector drops the click of a tap that follows a touch sequence within a few hundred ms (a double tap).
   */
  async #frame() {
    await this.page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
    await this.page.waitForTimeout(GESTURE_GAP_MS);
  }

  async tap(at) {
    await this.#send('touchStart', [at]);
    await this.#send('touchEnd', []);
    await this.#frame();
  }

  /** One finger from `path[0]` through each point of `path`; holdMs: wait before moving (a long press). */
  async drag(path, { holdMs = 0, stepMs = 16 } = {}) {
    await this.#send('touchStart', [path[0]]);
    if (holdMs) await this.page.waitForTimeout(holdMs);
    for (const p of path.slice(1)) {
      await this.#send('touchMove', [p]);
      await this.page.waitForTimeout(stepMs);
    }
    await this.#send('touchEnd', []);
    await this.#frame();
  }

  /**
   * Two fingers: the first lands at a[0] (and may move along a first, a stroke that the second cancels), then
   * the second at b[0]; both move to their last points together.
   */
  async twoFinger(a, b, { firstAlone = 1, steps = 8 } = {}) {
    await this.#send('touchStart', [{ ...a[0], id: 0 }]);
    for (let i = 1; i <= firstAlone && i < a.length; ++i) await this.#send('touchMove', [{ ...a[i], id: 0 }]);
    const start = a[Math.min(firstAlone, a.length - 1)];
    await this.#send('touchStart', [{ ...start, id: 0 }, { ...b[0], id: 1 }]);
    const end = [a.at(-1), b.at(-1)];
    for (let i = 1; i <= steps; ++i) {
      const t = i / steps;
      const lerp = (p, q) => ({ x: p.x + t * (q.x - p.x), y: p.y + t * (q.y - p.y) });
      await this.#send('touchMove', [{ ...lerp(start, end[0]), id: 0 }, { ...lerp(b[0], end[1]), id: 1 }]);
      await this.page.waitForTimeout(16);
    }
    await this.#send('touchEnd', []);
    await this.#frame();
  }
}

/** Taps a button (a locator) as a finger does, after the pause between two gestures. */
export async function tapButton(locator) {
  const page = locator.page();
  await page.waitForTimeout(GESTURE_GAP_MS);
  await locator.tap();
  // What the button changed (a panel opening resizes the views, which are framed again a frame later).
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => r()))));
}

/** The centre of an element (a locator), for a tap. */
export async function centre(locator) {
  const box = await locator.boundingBox();
  if (!box) throw new Error('the element is not visible');
  return { x: box.x + box.width / 2, y: box.y + box.height / 2 };
}
