// The deformed mesh: shaded (MeshStandardMaterial, smooth or flat) with an optional wireframe overlay.
// Each solver result arrives from the worker as Float32 positions and vertex normals already computed there
// (Deformer.renderBuffers): update() swaps them in as the attribute arrays (no copy, no normals on the
// main thread), and three.js uploads them with the next render.
// On software renderers a large mesh also gets a motion proxy (motion_proxy.js): a coarse mesh over the same
// vertex buffers, drawn instead of the full one while the view is in motion (setMotion).
// A glTF model is drawn with its own look (setLook, gltf_look.js): each primitive instance with its material,
// textures and UVs over its range of the same buffers; the plain mesh then stays for picking only, and comes
// back while volume parts are coloured.
import { BufferAttribute, BufferGeometry, DynamicDrawUsage, Group, Mesh, MeshBasicMaterial, MeshStandardMaterial } from 'three';
import { proxyIndices } from './motion_proxy.js';

export class MeshView {
  /** @param {{ motionProxy?: boolean }} [options] motionProxy: build a coarse stand-in for large meshes */
  constructor({ motionProxy = false } = {}) {
    this.motionProxyEnabled = motionProxy;
    this.inMotion = false;
    this.object = new Group();
    this.material = new MeshStandardMaterial({
      color: 0xb9c6d8,
      roughness: 0.55,
      metalness: 0.05,
      // Pushes the surface back a little so handle points drawn on it pass the depth test.
      polygonOffset: true,
      polygonOffsetFactor: 1,
      polygonOffsetUnits: 1,
    });
    this.wireMaterial = new MeshBasicMaterial({ color: 0x253041, wireframe: true, transparent: true, opacity: 0.18 });
    this.wireVisible = false;
    this.geometry = null;
    this.mesh = null;
    this.wire = null;
    this.proxy = null; // { geometry, mesh, wire } or null
    this.look = null; // { group, parts: [{ mesh, start, count }] } or null
    this.colored = false;
  }

  /**
   * Draws the model with a glTF look (gltf_look.js) instead of the plain material: each part gets its own
   * geometry (the file's UVs, colours and index, this view's positions and normals) and the file's material.
   * @param {import('./gltf_look.js').GltfLook|null} look
   */
  setLook(look) {
    this.#removeLook();
    if (!look || !this.geometry) return;
    const group = new Group();
    const parts = look.parts.map(({ instance, geometry, material }) => {
      const g = geometry.clone();
      g.morphAttributes = {};
      const { start, count } = instance;
      const position = new BufferAttribute(this.geometry.attributes.position.array.slice(3 * start, 3 * (start + count)), 3);
      const normal = new BufferAttribute(this.geometry.attributes.normal.array.slice(3 * start, 3 * (start + count)), 3);
      position.setUsage(DynamicDrawUsage);
      normal.setUsage(DynamicDrawUsage);
      g.setAttribute('position', position);
      g.setAttribute('normal', normal);
      const mesh = new Mesh(g, material);
      mesh.frustumCulled = false;
      mesh.raycast = () => {}; // picking uses the plain mesh
      group.add(mesh);
      return { mesh, start, count };
    });
    this.look = { group, parts };
    this.object.add(group);
    this.#showLook();
  }

  // The look while there is one and no part colours are shown; the plain material otherwise.
  #showLook() {
    const look = this.look !== null && !this.colored;
    if (this.look) this.look.group.visible = look;
    this.material.visible = !look;
  }

  #removeLook() {
    if (!this.look) return;
    this.object.remove(this.look.group);
    for (const part of this.look.parts) part.mesh.geometry.dispose();
    this.look = null;
    this.material.visible = true;
  }

  /** @param {{ positions: Float64Array, indices: Uint32Array }} data */
  setMesh(data) {
    this.dispose();
    const geometry = new BufferGeometry();
    const position = new BufferAttribute(new Float32Array(data.positions), 3);
    position.setUsage(DynamicDrawUsage);
    geometry.setAttribute('position', position);
    geometry.setIndex(new BufferAttribute(new Uint32Array(data.indices), 1));
    geometry.computeVertexNormals();
    geometry.attributes.normal.setUsage(DynamicDrawUsage);
    geometry.computeBoundingSphere();
    geometry.computeBoundingBox();
    this.geometry = geometry;
    ({ mesh: this.mesh, wire: this.wire } = this.#drawables(geometry));
    if (this.motionProxyEnabled) this.#buildProxy(data);
    this.setMotion(this.inMotion);
  }

  #buildProxy(data) {
    const indices = proxyIndices(data.positions, this.geometry.index.array);
    if (!indices) return;
    // The same attribute objects: every solver result swapped into them (update) moves the proxy too.
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', this.geometry.attributes.position);
    geometry.setAttribute('normal', this.geometry.attributes.normal);
    geometry.setIndex(new BufferAttribute(indices, 1));
    const { mesh, wire } = this.#drawables(geometry);
    mesh.raycast = () => {}; // picking always uses the full mesh
    this.proxy = { geometry, mesh, wire };
  }

  // The shaded mesh and its wireframe overlay for a geometry, added to this view's group.
  #drawables(geometry) {
    const mesh = new Mesh(geometry, this.material);
    const wire = new Mesh(geometry, this.wireMaterial);
    wire.raycast = () => {};
    // Bounds lag behind the solver (see update), so never cull on them.
    mesh.frustumCulled = false;
    wire.frustumCulled = false;
    this.object.add(mesh, wire);
    return { mesh, wire };
  }

  /** Draw the motion proxy (if this mesh has one) instead of the full mesh while `moving`. */
  setMotion(moving) {
    this.inMotion = moving;
    if (!this.mesh) return;
    const proxy = this.drawingProxy;
    this.mesh.visible = !proxy;
    this.wire.visible = !proxy && this.wireVisible;
    if (this.proxy) {
      this.proxy.mesh.visible = proxy;
      this.proxy.wire.visible = proxy && this.wireVisible;
    }
  }

  /** True while the coarse proxy is drawn instead of the mesh. */
  get drawingProxy() {
    return this.inMotion && this.proxy !== null;
  }

  /**
   * Takes a solver result's render buffers as the geometry's arrays (same vertex count; a stale result of
   * another model is ignored). Bounds (picking, culling) are refreshed lazily by updateBounds.
   * @param {{ positions: Float32Array, normals: Float32Array }} buffers from the worker (now owned here)
   */
  update({ positions, normals }) {
    if (!this.geometry) return;
    const position = this.geometry.attributes.position;
    const normal = this.geometry.attributes.normal;
    if (positions.length !== position.array.length || normals.length !== normal.array.length) return;
    position.array = positions;
    position.needsUpdate = true;
    normal.array = normals;
    normal.needsUpdate = true;
    this.boundsDirty = true;
    for (const part of this.look?.parts ?? []) {
      const { attributes } = part.mesh.geometry;
      attributes.position.array = positions.subarray(3 * part.start, 3 * (part.start + part.count));
      attributes.position.needsUpdate = true;
      attributes.normal.array = normals.subarray(3 * part.start, 3 * (part.start + part.count));
      attributes.normal.needsUpdate = true;
    }
  }

  updateBounds() {
    if (!this.geometry || !this.boundsDirty) return;
    this.geometry.computeBoundingSphere();
    this.geometry.computeBoundingBox();
    this.boundsDirty = false;
  }

  get positions() {
    return this.geometry?.attributes.position.array ?? null;
  }

  setFlat(flat) {
    this.material.flatShading = flat;
    this.material.needsUpdate = true;
    if (!flat && this.geometry) this.geometry.computeVertexNormals();
  }

  /** Vertex colours (RGB per vertex, e.g. volume parts), or null for the plain colour. */
  setColors(colors) {
    if (!this.geometry) return;
    if (colors) this.geometry.setAttribute('color', new BufferAttribute(colors, 3));
    else this.geometry.deleteAttribute('color');
    this.material.vertexColors = !!colors;
    this.material.color.set(colors ? 0xffffff : 0xb9c6d8);
    this.material.needsUpdate = true;
    this.colored = !!colors;
    this.#showLook();
  }

  setWireframe(visible) {
    this.wireVisible = visible;
    this.setMotion(this.inMotion);
  }

  dispose() {
    this.#removeLook();
    if (this.proxy) {
      this.object.remove(this.proxy.mesh, this.proxy.wire);
      this.proxy.geometry.dispose();
      this.proxy = null;
    }
    if (this.mesh) this.object.remove(this.mesh, this.wire);
    this.geometry?.dispose();
    this.geometry = null;
    this.mesh = null;
    this.wire = null;
  }
}
