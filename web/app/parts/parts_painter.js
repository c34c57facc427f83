// The painted volume parts (docs/method.md section 16) as data: one part per vertex (-1: not painted, i.e.
// the rest part), the part the brush paints, and the colours that show them. Painting uses the picker's
// brush and lasso (op 'add' paints the current part, 'remove' unpaints); a partition the worker made (auto
// parts) comes back per triangle and is shown and edited per vertex, vertex lists (a saved scene's painted
// parts) as they are, list k as part k.

/** One colour per part index (repeating), as 0..1 RGB; unpainted vertices keep the mesh's own colour. */
export const PART_COLORS = [[0.9, 0.31, 0.31], [0.31, 0.63, 0.9], [0.35, 0.78, 0.43], [0.94, 0.78, 0.24], [0.71, 0.39, 0.86],
  [0.98, 0.55, 0.24], [0.39, 0.86, 0.86], [0.78, 0.78, 0.78], [0.59, 0.35, 0.24], [0.94, 0.47, 0.75]];
const UNPAINTED = [0.73, 0.78, 0.85];

/** The most parts the painter offers (the brush's part index is 0 .. MAX_PARTS - 1). */
export const MAX_PARTS = 16;

export class PartsPainter {
  constructor() {
    /** @type {Int32Array|null} part per vertex, -1 = not painted */
    this.vertexPart = null;
    this.current = 0;
  }

  /** A new mesh: nothing painted. */
  reset(vertexCount) {
    this.vertexPart = new Int32Array(vertexCount).fill(-1);
  }

  get painted() {
    return !!this.vertexPart && this.vertexPart.some((p) => p >= 0);
  }

  /** Paints `vertices` with the current part ('add') or unpaints them ('remove'). */
  paint(vertices, op = 'add', part = op === 'remove' ? -1 : this.current) {
    if (!this.vertexPart) return;
    for (const v of vertices) if (v >= 0 && v < this.vertexPart.length) this.vertexPart[v] = part;
  }

  /** Whether paint(vertices, op) would change any vertex (a stroke over paint already there is no undo step). */
  changes(vertices, op = 'add') {
    const part = op === 'remove' ? -1 : this.current;
    return !!this.vertexPart && vertices.some((v) => v >= 0 && v < this.vertexPart.length && this.vertexPart[v] !== part);
  }

  /** Takes vertex lists (a saved scene's parts): list k becomes part k; unlisted vertices are not painted. */
  fromVertexLists(lists) {
    if (!this.vertexPart) return;
    this.vertexPart.fill(-1);
    lists.forEach((list, k) => this.paint(list, 'add', k));
  }

  /** The paint as a compact copy (one byte per vertex: parts are at most 64), for undo; null without a mesh. */
  snapshot() {
    return this.vertexPart ? Int8Array.from(this.vertexPart) : null;
  }

  restore(snapshot) {
    if (snapshot && snapshot.length === this.vertexPart?.length) this.vertexPart.set(snapshot);
  }

  /** Whether the paint is the same as a snapshot's. */
  same(snapshot) {
    return !!snapshot && snapshot.length === this.vertexPart?.length && snapshot.every((p, v) => p === this.vertexPart[v]);
  }

  /** Takes a partition per triangle (the worker's answer): each vertex gets the part of its last triangle. */
  fromTriangles(triangleParts, indices) {
    if (!this.vertexPart) return;
    this.vertexPart.fill(-1);
    for (let f = 0; f < triangleParts.length; ++f) {
      for (let k = 0; k < 3; ++k) this.vertexPart[indices[3 * f + k]] = triangleParts[f];
    }
  }

  /**
   * The painted parts as a parts description (web/lib/parts.js): vertex lists of the painted part indices in
   * order (empty indices skipped); unpainted vertices form the rest part. null when nothing is painted.
   */
  description() {
    if (!this.painted) return null;
    const lists = new Map();
    this.vertexPart.forEach((p, v) => {
      if (p >= 0) (lists.get(p) ?? lists.set(p, []).get(p)).push(v);
    });
    return { vertices: [...lists.keys()].sort((a, b) => a - b).map((p) => lists.get(p)) };
  }

  /** Vertex colours (Float32Array, RGB per vertex) for the painted parts, or null when nothing is painted. */
  colors() {
    if (!this.painted) return null;
    const out = new Float32Array(3 * this.vertexPart.length);
    this.vertexPart.forEach((p, v) => out.set(p >= 0 ? PART_COLORS[p % PART_COLORS.length] : UNPAINTED, 3 * v));
    return out;
  }
}
