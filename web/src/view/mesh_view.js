// The deformed mesh: shaded (MeshStandardMaterial, flat or smooth normals recomputed when positions change)
// with an optional wireframe overlay. Positions arrive as Float64Array from the worker and are copied into a
// DynamicDrawUsage Float32 attribute.
import { BufferAttribute, BufferGeometry, DynamicDrawUsage, Group, Mesh, MeshBasicMaterial, MeshStandardMaterial } from 'three';

export class MeshView {
  constructor() {
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
    this.geometry = null;
    this.mesh = null;
    this.wire = null;
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
    this.mesh = new Mesh(geometry, this.material);
    this.wire = new Mesh(geometry, this.wireMaterial);
    this.wire.visible = this.wireVisible ?? false;
    this.wire.raycast = () => {};
    // Bounds lag behind the solver (see update), so never cull on them.
    this.mesh.frustumCulled = false;
    this.wire.frustumCulled = false;
    this.object.add(this.mesh, this.wire);
  }

  /** Copies new positions in (same vertex count) and refreshes normals and bounds (for picking). */
  update(positions) {
    if (!this.geometry) return;
    const attribute = this.geometry.attributes.position;
    attribute.array.set(positions);
    attribute.needsUpdate = true;
    if (!this.material.flatShading) this.geometry.computeVertexNormals();
    // Bounds are for picking and culling; refreshed lazily (updateBounds) instead of every solver update.
    this.boundsDirty = true;
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

  setWireframe(visible) {
    this.wireVisible = visible;
    if (this.wire) this.wire.visible = visible;
  }

  dispose() {
    if (this.mesh) this.object.remove(this.mesh, this.wire);
    this.geometry?.dispose();
    this.geometry = null;
    this.mesh = null;
    this.wire = null;
  }
}
