// The animation-frame loop: calls `frame(now)` every animation frame (it returns how many views it redrew),
// measures frames and redraws per second over one-second windows, and calls `tick(now)` at most every
// `tickMs` (the stats lines, which need not follow every frame).

export class FrameLoop {
  /**
   * @param {{ frame: (now: number) => number, tick: (now: number) => void, tickMs?: number }} callbacks
   *   frame returns the redraws of this frame, per view (a fraction in compare mode)
   */
  constructor({ frame, tick, tickMs = 200 }) {
    this.frame = frame;
    this.tick = tick;
    this.tickMs = tickMs;
    this.fps = 0;
    this.renderFps = 0;
    this.frames = 0;
    this.redraws = 0;
    this.windowStart = performance.now();
    this.lastTick = 0;
    this.running = false;
    this.raf = 0;
    this.run = this.run.bind(this);
  }

  start() {
    this.running = true;
    this.raf = requestAnimationFrame(this.run);
  }

  stop() {
    this.running = false;
    cancelAnimationFrame(this.raf);
  }

  run(now) {
    if (!this.running) return;
    this.raf = requestAnimationFrame(this.run);
    this.redraws += this.frame(now);
    this.frames++;
    if (now - this.windowStart >= 1000) {
      this.fps = (1000 * this.frames) / (now - this.windowStart);
      this.renderFps = (1000 * this.redraws) / (now - this.windowStart);
      this.frames = 0;
      this.redraws = 0;
      this.windowStart = now;
    }
    if (now - this.lastTick > this.tickMs) {
      this.lastTick = now;
      this.tick(now);
    }
  }
}
