// The glTF reader against hostile files: a small valid document (a tetrahedron under a transformed node, as
// .gltf with a data: URI buffer or as .glb) with random edits -- any field replaced by a random value (huge,
// negative, fractional, wrong type), deleted, or the binary cut short or padded -- must be read into a valid
// mesh or refused with an InputError (parse_error or unreadable_file) naming the file, never another error.
// Used by tests/js/gltf_fuzz.test.js (fixed seed) and scripts/fuzz_properties.mjs (long runs, fresh seeds: target gltf).
import fc from 'fast-check';
import { InputError } from '../../web/lib/errors.js';
import { readGltf } from '../../web/lib/gltf.js';

const POSITIONS = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]);
const INDICES = new Uint16Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]);

function baseDocument() {
  const bin = new Uint8Array(POSITIONS.byteLength + INDICES.byteLength);
  bin.set(new Uint8Array(POSITIONS.buffer), 0);
  bin.set(new Uint8Array(INDICES.buffer), POSITIONS.byteLength);
  const json = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ children: [1], translation: [1, 2, 3] }, { mesh: 0, scale: [2, 2, 2], rotation: [0, 0, 0.7071, 0.7071] }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1, mode: 4 }] }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: 4, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 1] },
      { bufferView: 1, componentType: 5123, count: 12, type: 'SCALAR' },
    ],
    bufferViews: [{ buffer: 0, byteLength: POSITIONS.byteLength }, { buffer: 0, byteOffset: POSITIONS.byteLength, byteLength: INDICES.byteLength }],
    buffers: [{ byteLength: bin.byteLength }],
  };
  return { json, bin };
}

// Every path to a value in the JSON (arrays by index), for the edits to pick from.
function paths(value, prefix = []) {
  if (!value || typeof value !== 'object') return [prefix];
  return [prefix, ...Object.keys(value).flatMap((k) => paths(value[k], [...prefix, k]))];
}

const strangeValue = fc.oneof(
  fc.integer({ min: -5, max: 20 }), fc.constantFrom(2 ** 31, 2 ** 40, 2 ** 53, -(2 ** 31), 1e308, 0.5, -0.0, NaN),
  fc.constantFrom('', 'VEC3', 'SCALAR', 'data:application/octet-stream;base64,AAAA', 'missing.bin', '__proto__'),
  fc.constant(null), fc.constant([]), fc.constant({}), fc.array(fc.integer({ min: -1, max: 5 }), { maxLength: 4 }),
  fc.constantFrom(['KHR_draco_mesh_compression'], ['EXT_meshopt_compression'], ['KHR_mesh_quantization'], ['EXT_unknown']),
);

const edit = fc.record({ at: fc.nat(), kind: fc.constantFrom('set', 'delete'), value: strangeValue });

/** A document (as .gltf text or .glb bytes) with 0 to 4 random edits, and whether to cut or pad the .glb. */
export const gltfInput = fc.record({
  edits: fc.array(edit, { maxLength: 4 }),
  binary: fc.boolean(),
  cut: fc.option(fc.nat({ max: 400 }), { nil: undefined }),
  pad: fc.option(fc.uint8Array({ maxLength: 16 }), { nil: undefined }),
});

function applyEdits(json, edits) {
  const all = paths(json).filter((p) => p.length > 0);
  for (const { at, kind, value } of edits) {
    const path = all[at % all.length];
    let parent = json;
    for (const key of path.slice(0, -1)) parent = parent?.[key];
    if (!parent || typeof parent !== 'object') continue;
    const key = path.at(-1);
    if (kind === 'delete') delete parent[key];
    else parent[key] = structuredClone(value);  // a copy: one shared value set twice could become its own child
  }
}

function glb(json, bin) {
  const text = new TextEncoder().encode(JSON.stringify(json));
  const jsonLength = (text.length + 3) & ~3, binLength = (bin.length + 3) & ~3;
  const out = new Uint8Array(12 + 8 + jsonLength + 8 + binLength).fill(0x20, 20, 20 + jsonLength);
  const view = new DataView(out.buffer);
  view.setUint32(0, 0x46546c67, true);
  view.setUint32(4, 2, true);
  view.setUint32(8, out.length, true);
  view.setUint32(12, jsonLength, true);
  view.setUint32(16, 0x4e4f534a, true);
  out.set(text, 20);
  view.setUint32(20 + jsonLength, binLength, true);
  view.setUint32(24 + jsonLength, 0x004e4942, true);
  out.fill(0, 28 + jsonLength);
  out.set(bin, 28 + jsonLength);
  return out;
}

/** The bytes and name of one input. */
export function gltfBytes({ edits, binary, cut, pad }) {
  const { json, bin } = baseDocument();
  if (!binary) json.buffers[0].uri = `data:application/octet-stream;base64,${Buffer.from(bin).toString('base64')}`;
  applyEdits(json, edits);
  let bytes = binary ? glb(json, bin) : new TextEncoder().encode(JSON.stringify(json));
  if (cut !== undefined) bytes = bytes.subarray(0, Math.min(bytes.length, cut));
  if (pad) bytes = Uint8Array.from([...bytes, ...pad]);
  return { bytes, name: binary ? 'fuzz.glb' : 'fuzz.gltf' };
}

/** The property: a valid mesh, or an InputError with a file code naming the file. */
export async function checkGltf(input) {
  const { bytes, name } = gltfBytes(input);
  let result;
  try {
    result = await readGltf(bytes, name);
  } catch (error) {
    if (!(error instanceof InputError) || !['parse_error', 'unreadable_file'].includes(error.code) || !error.message.startsWith(`${name}: `)) {
      throw new Error(`not a named InputError: ${error?.name} ${error?.code}: ${error?.message}`);
    }
    return true;
  }
  const { positions, indices } = result.mesh;
  const n = positions.length / 3;
  if (indices.length % 3 !== 0 || indices.some((i) => i >= n)) throw new Error('a mesh with an index out of range');
  return true;
}

export { fc };
