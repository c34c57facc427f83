// One 3D view: a canvas with its renderer, camera, OrbitControls, lights, the mesh, cage and handle views,
// a label, a stats line and a convergence plot. Compare mode shows several, their cameras linked.
// Events: 'resize' (the canvas changed size), 'userCamera' (the user started moving the camera).
import { Box3, Color, DirectionalLight, EventDispatcher, HemisphereLight, PerspectiveCamera, Scene, Vector2, Vector3, WebGLRenderer } from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { MeshView } from './mesh_view.js';
import { CageView } from './cage_view.js';
import { HandleView } from './handle_view.js';
import { ConvergencePlot } from './convergence_plot.js';
import { DEFAULT_DIRECTION, frameBox } from './framing.js';
import { cameraAbove, coveredBelow, shiftProjection } from './overlay_room.js';

const MOTION_MS = 200; // changes closer than this are motion (software renderer: reduced resolution)
const SETTLE_MS = 250; // still this long: one full-resolution frame
const _size = new Vector2();

export class Viewport extends EventDispatcher {
  /**
   * @param {HTMLElement} parent
   * @param {{ label?: string, color?: string }} [options]
   */
  constructor(parent, { label = '', color = '#f08a24' } = {}) {
    super();
    this.element = document.createElement('div');
    this.element.className = 'sd-view';
    parent.appendChild(this.element);

    // Software WebGL (SwiftShader: headless Chromium, machines without a GPU) draws several times faster
    // without multisampling; a real GPU gets antialiasing.
    const software = isSoftwareRenderer();
    this.renderer = new WebGLRenderer({ antialias: !software });
    this.fullPixelRatio = software ? 1 : Math.min(globalThis.devicePixelRatio ?? 1, 2);
    // Software rendering is partly fill-bound (bar-fine: 17 -> 23 redraws/s at half resolution): while the
    // view keeps changing (a drag, an orbit, a solve in progress) it draws at this ratio, and once it has
    // been still for SETTLE_MS it draws one frame at full resolution. A real GPU always gets full quality.
    // It also pays per triangle (bar-fine's 86k: 22 redraws/s even at half resolution), so meshes above
    // PROXY_MIN_TRIANGLES draw a coarse proxy of ~12k triangles while in motion (motion_proxy.js).
    this.motionPixelRatio = software ? 0.5 : this.fullPixelRatio;
    this.software = software;
    this.lastChange = 0;
    this.inMotion = false;
    this.renderer.setPixelRatio(this.fullPixelRatio);
    this.canvas = this.renderer.domElement;
    this.canvas.className = 'sd-canvas';
    this.element.appendChild(this.canvas);

    this.label = document.createElement('div');
    this.label.className = 'sd-label';
    this.label.textContent = label;
    this.element.appendChild(this.label);

    this.statsLine = document.createElement('div');
    this.statsLine.className = 'sd-stats';
    this.element.appendChild(this.statsLine);

    this.plot = new ConvergencePlot({ color });
    this.element.appendChild(this.plot.canvas);

    this.scene = new Scene();
    this.scene.background = new Color(0xeef1f5);
    this.camera = new PerspectiveCamera(40, 1, 0.01, 100);
    this.camera.position.set(0, 0.6, 3);
    this.scene.add(this.camera);
    this.scene.add(new HemisphereLight(0xffffff, 0x8a8f99, 1.6));
    const head = new DirectionalLight(0xffffff, 1.8);
    head.position.set(0.4, 0.8, 1);
    this.camera.add(head); // a headlight: the side you look at is always lit

    this.meshView = new MeshView({ motionProxy: software });
    this.cageView = new CageView();
    this.handleView = new HandleView();
    this.scene.add(this.meshView.object, this.cageView.object, this.handleView.object);

    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.enableDamping = false;
    this.controls.addEventListener('change', () => this.invalidate());
    this.controls.addEventListener('start', () => this.dispatchEvent({ type: 'userCamera' }));
    // Render on demand: only after something changed (camera, positions, handles, display, size).
    this.needsRender = true;

    this.resizeObserver = new ResizeObserver(() => {
      if (this.resize()) this.dispatchEvent({ type: 'resize' });
    });
    this.resizeObserver.observe(this.element);
    this.resize();
  }

  /** Takes the element's size; returns whether it changed. */
  resize() {
    const width = Math.max(1, this.element.clientWidth);
    const height = Math.max(1, this.element.clientHeight);
    const size = this.renderer.getSize(_size);
    if (size.x === width && size.y === height) return false;
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / height;
    shiftProjection(this.camera, this.covered, width, height);
    this.camera.updateProjectionMatrix();
    this.invalidate();
    return true;
  }

  covered = 0; // the fraction of a portrait view's height under the stats and plot, framed above (overlay_room.js)

  invalidate() {
    this.needsRender = true;
  }

  /**
   * Renders if something changed since the last frame; returns whether it did. With a software renderer,
   * changes on consecutive frames draw at motionPixelRatio, and the view is redrawn at full resolution
   * once it has been still for SETTLE_MS.
   * @param {number} [now] the animation frame's timestamp
   */
  renderIfNeeded(now = performance.now()) {
    if (this.software) {
      if (this.needsRender) {
        // A second change within a few frames: motion, draw cheaply.
        if (now - this.lastChange < MOTION_MS) this.#setMotion(true);
        this.lastChange = now;
      } else if (this.inMotion && now - this.lastChange > SETTLE_MS) {
        this.#setMotion(false);
      }
    }
    if (!this.needsRender) return false;
    this.needsRender = false;
    this.render();
    return true;
  }

  // Motion (software renderer only): reduced resolution and the mesh's coarse proxy; still: full quality.
  #setMotion(moving) {
    if (this.inMotion === moving) return;
    this.inMotion = moving;
    this.renderer.setPixelRatio(moving ? this.motionPixelRatio : this.fullPixelRatio); // the CSS size stays
    this.meshView.setMotion(moving);
    this.invalidate();
  }

  /** Full quality now (screenshots). */
  renderFull() {
    this.#setMotion(false);
    this.lastChange = 0;
    this.render();
  }

  /** The direction the camera looks along now (unit). */
  viewDirection() {
    return this.camera.getWorldDirection(new Vector3());
  }

  /**
   * The camera distance that frames `box` in this view's aspect (framing.js), looking along `direction`;
   * keep(aspect): a point to keep in view with room around it, for the current aspect (frameBox's keep).
   * @returns {{ center: Vector3, distance: number, radius: number }}
   */
  frameFor(box, direction = DEFAULT_DIRECTION, keep = null) {
    this.resize();
    this.covered = coveredBelow(this.element, this.statsLine);
    return frameBox(box, cameraAbove(this.camera, this.covered), direction, undefined, keep?.(this.camera.aspect) ?? null);
  }

  /** Puts the camera `distance` from `center`, looking along `direction`, with clipping planes around a sphere of `radius`. */
  placeCamera({ center, distance, radius }, direction = DEFAULT_DIRECTION) {
    this.camera.position.copy(center).addScaledVector(direction, -distance);
    this.camera.lookAt(center);
    this.camera.near = Math.max(distance - 2 * radius, distance / 100) * 0.5;
    this.camera.far = distance + 4 * radius;
    const { x, y } = this.renderer.getSize(_size);
    shiftProjection(this.camera, this.covered, x, y);
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();
    this.handleView.arrowScale = radius;
    this.invalidate();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }

  dispose() {
    this.resizeObserver.disconnect();
    this.controls.dispose();
    this.meshView.dispose();
    this.cageView.dispose();
    this.handleView.dispose();
    this.renderer.dispose();
    this.element.remove();
  }
}

let software = null;
/** True when WebGL runs on a CPU rasterizer (probed once per page with a throwaway context). */
export function isSoftwareRenderer() {
  if (software !== null) return software;
  software = false;
  try {
    const gl = document.createElement('canvas').getContext('webgl2');
    const info = gl?.getExtension('WEBGL_debug_renderer_info');
    const name = info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl?.getParameter(gl.RENDERER);
    software = /swiftshader|llvmpipe|software/i.test(String(name ?? ''));
    gl?.getExtension('WEBGL_lose_context')?.loseContext();
  } catch {
    software = false;
  }
  return software;
}

export function boxOf(positions) {
  const box = new Box3();
  box.setFromArray(positions);
  return box;
}
