// The glTF reader's newer paths against hostile files (issue 32), one property each:
//   resources  a .gltf whose buffer uri is made of path pieces (sub/, .., ., %2E%2E, %2F, a malformed %, /abs,
//              C:, file:, backslashes) with files given inside and outside its folder: read from inside, or
//              refused by name -- never the outside file's bytes
//   data       data: URIs of random sizes, with or without ;base64, their payload cut, padded or spoiled by
//              stray characters, the buffer's byteLength off by a little
//   nodes      node forests of random shape (shared meshes, cycles, two parents, missing meshes, deep chains)
//              and transforms (zero and flat scales, mirrors, huge and tiny scales, unnormalised rotations),
//              each read, written back with every instance moved differently, and read again
// Every input: a mesh, or an InputError (parse_error, unreadable_file) naming the file, within a few
// seconds; nothing written holds NaN or infinity, and each instance comes back as it was written (or, where
// its node cannot take it, as the file had it).
// Used by tests/js/gltf_fuzz.test.js (fixed seeds) and scripts/fuzz_properties.mjs (targets gltf-resources,
// gltf-data, gltf-nodes).
import fc from 'fast-check';
import { InputError } from '../../web/lib/errors.js';
import { readGltf, writeGltf } from '../../web/lib/gltf.js';
import { inverseAffine, transformPoint } from '../../web/lib/gltf_space.js';

const TRIANGLE = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]);
const OUTSIDE = new Float32Array([7, 7, 7, 9, 7, 7, 7, 9, 7]); // a file outside the folder: never read
const bytesOf = (array) => new Uint8Array(array.buffer.slice(0));
const MAX_SECONDS = 5;

function triangle(uri, byteLength = 36) {
  return { asset: { version: '2.0' }, buffers: [{ byteLength, uri }], bufferViews: [{ buffer: 0, byteLength: 36 }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3' }], meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
    nodes: [{ mesh: 0 }], scenes: [{ nodes: [0] }] };
}

// Reads `json` as name; an error must be a named InputError with a file code; a read takes under MAX_SECONDS.
async function readNamed(json, name, options) {
  const started = performance.now();
  let result = null;
  try {
    result = await readGltf(new TextEncoder().encode(JSON.stringify(json)), name, options);
  } catch (error) {
    if (!(error instanceof InputError) || !['parse_error', 'unreadable_file', 'file_too_large'].includes(error.code) || !error.message.startsWith(`${name}: `)) {
      throw new Error(`not a named InputError: ${error?.name} ${error?.code}: ${error?.message}`);
    }
  }
  const seconds = (performance.now() - started) / 1000;
  if (seconds > MAX_SECONDS) throw new Error(`reading took ${seconds.toFixed(1)} s`);
  return result;
}

const PIECES = ['sub', '..', '.', 'tri.bin', 'secret.bin', '%2E%2E', '%2F', '%5C', '%', '%E0%A4%A', '%20', '', '/', '\\', 'C:', 'file:', 'x'];

/** A buffer uri of path pieces. */
export const resourceInput = fc.array(fc.constantFrom(...PIECES), { minLength: 1, maxLength: 6 }).map((parts) => parts.join('/'));

/** The property: the triangle inside the folder, or a named refusal; never the outside file. */
export async function checkResource(uri) {
  const given = { 'tri.bin': bytesOf(TRIANGLE), 'sub/tri.bin': bytesOf(TRIANGLE), '../secret.bin': bytesOf(OUTSIDE), '/secret.bin': bytesOf(OUTSIDE) };
  const result = await readNamed(triangle(uri), 'res.gltf', { resources: given });
  if (result && result.mesh.positions.some((x) => x === 7 || x === 9)) throw new Error(`read the outside file through "${uri}"`);
  return true;
}

/** A data: URI: the triangle's bytes (or random ones) as base64 or percent-encoded text, spoiled at random. */
export const dataUriInput = fc.record({
  bytes: fc.oneof(fc.constant(bytesOf(TRIANGLE)), fc.uint8Array({ maxLength: 300 })),
  base64: fc.boolean(),
  mime: fc.constantFrom('application/octet-stream', 'application/gltf-buffer', '', 'text/plain;charset=utf-8'),
  cut: fc.option(fc.nat({ max: 500 }), { nil: undefined }),
  insert: fc.array(fc.record({ at: fc.nat(), text: fc.constantFrom('=', '==', '!', ' ', '\n', '%', '%zz', 'é', '-', '_', ',', '\0') }), { maxLength: 3 }),
  lengthDelta: fc.integer({ min: -4, max: 4 }),
});

/** The property: a mesh or a named refusal, whatever the URI. */
export async function checkDataUri({ bytes, base64, mime, cut, insert, lengthDelta }) {
  let payload = base64 ? Buffer.from(bytes).toString('base64') : Array.from(bytes, (b) => `%${b.toString(16).padStart(2, '0')}`).join('');
  if (cut !== undefined) payload = payload.slice(0, cut);
  for (const { at, text } of insert) payload = payload.slice(0, at % (payload.length + 1)) + text + payload.slice(at % (payload.length + 1));
  const uri = `data:${mime}${base64 ? ';base64' : ''},${payload}`;
  const result = await readNamed(triangle(uri, Math.max(0, 36 + lengthDelta)), 'data.gltf');
  if (result && !result.mesh.positions.every(Number.isFinite)) throw new Error('a data: URI read into positions that are not finite');
  return true;
}

const TRANSFORMS = [
  {}, { scale: [0, 0, 0] }, { scale: [1, 1, 0] }, { scale: [-1, 1, 1] }, { scale: [1e30, 1e30, 1e30] }, { scale: [1e-30, 1e-30, 1e-30] },
  { translation: [1, 2, 3] }, { rotation: [0, 0, 0.7071, 0.7071] }, { rotation: [0, 0, 0, 0] }, { rotation: [1, 2, 3, 4] },
  { matrix: [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 5, 0, 0, 1] }, { matrix: [1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] },
];

/**
 * A node forest: node i's parent is an earlier node or none (a root), its mesh 0, 1 or none, its transform
 * one of TRANSFORMS; sometimes one corruption (a cycle, a second parent, a missing mesh, a child listed as
 * a root); sometimes a deep chain.
 */
export const nodeTreeInput = fc.record({
  nodes: fc.array(fc.record({
    parent: fc.nat({ max: 40 }),
    mesh: fc.constantFrom(0, 0, 1, undefined),
    transform: fc.nat({ max: TRANSFORMS.length - 1 }),
  }), { minLength: 1, maxLength: 40 }),
  corrupt: fc.constantFrom(undefined, undefined, undefined, 'cycle', 'two parents', 'missing mesh', 'child as root'),
  chain: fc.constantFrom(0, 0, 0, 50, 3000),
});

export function nodeDocument({ nodes, corrupt, chain }) {
  const json = triangle(`data:application/octet-stream;base64,${Buffer.from(TRIANGLE.buffer).toString('base64')}`);
  json.meshes.push({ primitives: [{ attributes: { POSITION: 0 } }] });
  const parents = nodes.map((n, i) => (n.parent % (i + 1)) - 1); // -1: a root
  json.nodes = nodes.map((n) => ({ ...(n.mesh === undefined ? {} : { mesh: n.mesh }), children: [], ...TRANSFORMS[n.transform] }));
  parents.forEach((p, i) => p >= 0 && json.nodes[p].children.push(i));
  json.scenes = [{ nodes: parents.flatMap((p, i) => (p < 0 ? [i] : [])) }];
  // A deep chain hung under the last node: translations down to a mesh.
  for (let k = 0; k < chain; ++k) {
    json.nodes[json.nodes.length - 1].children.push(json.nodes.length);
    json.nodes.push({ children: [], translation: [0.001, 0, 0], ...(k + 1 === chain ? { mesh: 0 } : {}) });
  }
  const last = json.nodes.length - 1;
  if (corrupt === 'cycle') json.nodes[last].children.push(0);
  if (corrupt === 'two parents' && last > 1) json.nodes[0].children.push(last);
  if (corrupt === 'missing mesh') json.nodes[last].mesh = 5;
  if (corrupt === 'child as root' && last > 0) json.scenes[0].nodes.push(json.nodes[0].children[0] ?? last);
  return json;
}

/**
 * The property: read (or refused by name), written back with instance k moved by (0, k + 1, 0) (or refused by
 * name where that passes float32's range in a node's space), read again.
 */
export async function checkNodeTree(input) {
  const read = await readNamed(nodeDocument(input), 'nodes.gltf');
  if (!read) return true;
  const { mesh, gltf } = read;
  const written = Float64Array.from(mesh.positions);
  gltf.instances.forEach((instance, k) => {
    for (let v = instance.start; v < instance.start + instance.count; ++v) written[3 * v + 1] += k + 1;
  });
  const started = performance.now();
  let bytes;
  try {
    bytes = await writeGltf(gltf, written, mesh.indices);
  } catch (error) {
    // A move that a huge scale's inverse takes past float32 in the node's space is refused by name, never written.
    if (error instanceof InputError && /beyond float32's range/.test(error.message)) return true;
    throw error;
  }
  const back = await readGltf(bytes, 'nodes.glb');
  if ((performance.now() - started) / 1000 > MAX_SECONDS) throw new Error('writing took too long');
  if (!back.mesh.positions.every(Number.isFinite)) throw new Error('wrote positions that are not finite');
  if (back.gltf.instances.length !== gltf.instances.length) throw new Error('the instances changed on the way back');
  gltf.instances.forEach((instance, k) => {
    const range = [3 * instance.start, 3 * (instance.start + instance.count)];
    const got = back.mesh.positions.subarray(...range);
    if (!near(got, written.subarray(...range), instance.matrix) && !near(got, mesh.positions.subarray(...range), instance.matrix)) {
      throw new Error(`instance ${k} (node ${instance.node}) came back neither as written nor as the file had it`);
    }
  });
  return true;
}

// Equal to float32's precision in the node's space: a coordinate there rounded by its relative 6e-8 moves the
// scene position by up to that times |m| (the 3x3 part's largest row sum) times the largest local coordinate.
function near(got, want, m) {
  const inverse = inverseAffine(m);
  const local = new Float64Array(3);
  let localMax = 0, wantMax = 0;
  for (let v = 0; v < want.length; v += 3) {
    if (inverse) transformPoint(inverse, want[v], want[v + 1], want[v + 2], local, 0);
    localMax = Math.max(localMax, ...local.map(Math.abs));
    wantMax = Math.max(wantMax, Math.abs(want[v]), Math.abs(want[v + 1]), Math.abs(want[v + 2]));
  }
  const rows = [0, 1, 2].map((r) => Math.abs(m[r]) + Math.abs(m[4 + r]) + Math.abs(m[8 + r]));
  const tolerance = 1e-6 * (Math.max(...rows) * localMax + wantMax + 1);
  return got.every((x, i) => Math.abs(x - want[i]) <= tolerance);
}

export { fc };
