// Headless pictures of the experiment results: a tiny z-buffered flat-shaded rasterizer and a PNG writer
// (node:zlib only), so the README shows the shapes without a browser. One PNG per scene: the rest pose
// with the handles (blue fixed, orange moved) and the final shape of each series side by side, all in
// one orthographic view and scale.
import { writeFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { deflateSync } from 'node:zlib';

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});

function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

function chunk(type, data) {
  const out = Buffer.alloc(12 + data.length);
  out.writeUInt32BE(data.length, 0);
  out.write(type, 4, 'ascii');
  data.copy(out, 8);
  out.writeUInt32BE(crc32(out.subarray(4, 8 + data.length)), 8 + data.length);
  return out;
}

/** PNG bytes of an RGB image (Uint8Array of width * height * 3). */
export function encodePng(width, height, rgb) {
  const raw = Buffer.alloc((3 * width + 1) * height);
  for (let y = 0; y < height; ++y) {
    raw[y * (3 * width + 1)] = 0;
    Buffer.from(rgb.buffer, rgb.byteOffset + 3 * width * y, 3 * width).copy(raw, y * (3 * width + 1) + 1);
  }
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header[8] = 8; header[9] = 2; header[10] = 0; header[11] = 0; header[12] = 0;
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', header),
    chunk('IDAT', deflateSync(raw, { level: 9 })), chunk('IEND', Buffer.alloc(0))]);
}

// View: rotate by yaw about y, then pitch about x (radians); returns camera-space [x, y, depth].
function viewTransform(yaw, pitch) {
  const cy = Math.cos(yaw), sy = Math.sin(yaw), cp = Math.cos(pitch), sp = Math.sin(pitch);
  return (x, y, z) => {
    const x1 = cy * x + sy * z, z1 = -sy * x + cy * z;
    return [x1, cp * y - sp * z1, sp * y + cp * z1];
  };
}

function rasterize(img, W, H, ox, size, pts, indices, colors) {
  const depth = new Float64Array(size * size).fill(-Infinity);
  for (let f = 0; f < indices.length / 3; ++f) {
    // Screen y points down, so outward (counter-clockwise) faces appear clockwise: take them as a, c, b.
    const a = indices[3 * f], b = indices[3 * f + 2], c = indices[3 * f + 1];
    const [ax, ay, az] = pts[a], [bx, by, bz] = pts[b], [cx, cy, cz] = pts[c];
    const area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    if (area <= 0) continue;  // back face
    // Flat shading by the camera-space normal (light from the viewer, a bit from above).
    const ux = bx - ax, uy = by - ay, uz = bz - az, vx = cx - ax, vy = cy - ay, vz = cz - az;
    let nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const len = Math.hypot(nx, ny, nz) || 1;
    nx /= len; ny /= len; nz /= len;
    // Light from the viewer, up and to the left (screen y points down); |.| makes the face order irrelevant.
    const shade = 0.3 + 0.7 * Math.abs(0.35 * nx - 0.45 * ny + 0.82 * nz);
    const color = colors[f];
    const x0 = Math.max(0, Math.floor(Math.min(ax, bx, cx))), x1 = Math.min(size - 1, Math.ceil(Math.max(ax, bx, cx)));
    const y0 = Math.max(0, Math.floor(Math.min(ay, by, cy))), y1 = Math.min(size - 1, Math.ceil(Math.max(ay, by, cy)));
    for (let y = y0; y <= y1; ++y) {
      for (let x = x0; x <= x1; ++x) {
        const px = x + 0.5, py = y + 0.5;
        const w0 = (bx - px) * (cy - py) - (by - py) * (cx - px);
        const w1 = (cx - px) * (ay - py) - (cy - py) * (ax - px);
        const w2 = (ax - px) * (by - py) - (ay - py) * (bx - px);
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const z = (w0 * az + w1 * bz + w2 * cz) / area;
        if (z <= depth[y * size + x]) continue;
        depth[y * size + x] = z;
        const o = 3 * (y * W + ox + x);
        img[o] = color[0] * shade; img[o + 1] = color[1] * shade; img[o + 2] = color[2] * shade;
      }
    }
  }
}

/**
 * Writes <id>_shapes.png (or `file`): rest pose, then the final shape of each series; returns its file name
 * and the panel order. Faces are coloured by handle (blue fixed, orange moved, grey otherwise) or, with
 * faceColors, by those ([r, g, b] per triangle: e.g. volume parts); panelColors[k], when given, colours panel k
 * (0: the rest pose) instead (e.g. one basis column per panel).
 */
export function renderViews(out, id, mesh, series, ctx,
  { size = 300, yaw = 0, pitch = 0.25, faceColors = null, file = `${id}_shapes.png`, restLabel, panelColors = null } = {}) {
  const view = viewTransform(yaw, pitch);
  const shapes = [{ label: restLabel ?? 'rest pose (blue fixed, orange moved; target of the moved handle in red)', positions: mesh.positions },
    ...series.map((s) => ({ label: s.label, positions: s.positions }))];
  const fixed = new Set(ctx.groups[0]);
  const moved = new Set(ctx.groups.slice(1).flat());
  const colors = faceColors ? faceColors.slice() : [];
  for (let f = colors.length; f < mesh.indices.length / 3; ++f) {
    const v = [mesh.indices[3 * f], mesh.indices[3 * f + 1], mesh.indices[3 * f + 2]];
    colors.push(v.some((x) => moved.has(x)) ? [255, 150, 40] : v.some((x) => fixed.has(x)) ? [60, 110, 230] : [215, 215, 205]);
  }
  // One scale for every panel: the union of all shapes' and the targets' projected extents.
  let lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  const grow = (p) => { for (let a = 0; a < 2; ++a) { lo[a] = Math.min(lo[a], p[a]); hi[a] = Math.max(hi[a], p[a]); } };
  const projected = shapes.map((s) => {
    const pts = [];
    for (let i = 0; i < s.positions.length / 3; ++i) {
      const p = view(s.positions[3 * i], s.positions[3 * i + 1], s.positions[3 * i + 2]);
      pts.push(p);
      grow(p);
    }
    return pts;
  });
  const targetPts = [];
  for (let k = 0; k < ctx.targets.length / 3; ++k) {
    const p = view(ctx.targets[3 * k], ctx.targets[3 * k + 1], ctx.targets[3 * k + 2]);
    targetPts.push(p);
    grow(p);
  }
  const scale = (0.92 * size) / Math.max(hi[0] - lo[0], hi[1] - lo[1]);
  const toScreen = (p) => [size / 2 + (p[0] - (lo[0] + hi[0]) / 2) * scale, size / 2 - (p[1] - (lo[1] + hi[1]) / 2) * scale, p[2] * scale];
  const W = size * shapes.length, H = size;
  const img = new Uint8Array(W * H * 3).fill(255);
  projected.forEach((pts, k) => rasterize(img, W, H, k * size, size, pts.map(toScreen), mesh.indices, panelColors?.[k] ?? colors));
  // Targets of the moved handle as red dots on every panel; panel separators.
  const firstMoved = ctx.groups[0].length;
  for (let k = 0; k < shapes.length; ++k) {
    targetPts.slice(firstMoved).forEach((p) => {
      const [x, y] = toScreen(p);
      for (let dy = -1; dy <= 1; ++dy) for (let dx = -1; dx <= 1; ++dx) {
        const px = Math.round(x) + dx, py = Math.round(y) + dy;
        if (px >= 0 && px < size && py >= 0 && py < size) img.set([220, 20, 20], 3 * (py * W + k * size + px));
      }
    });
    for (let y = 0; y < H; ++y) img.set([160, 160, 160], 3 * (y * W + k * size));
  }
  writeFileSync(resolve(out, file), encodePng(W, H, img));
  return { file, panels: shapes.map((s) => s.label) };
}
