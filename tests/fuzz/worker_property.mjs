// Fuzz property of the solver worker's messages (fast-check), shared by the Vitest run with a fixed seed
// (tests/js/worker_fuzz.test.js) and the long runs of `npm run fuzz` (scripts/fuzz_properties.mjs). The worker
// runs as the browser runs it, in a thread (tests/js/support/worker_host.mjs), and gets sequences of requests:
// well-formed ones with hostile fields, unknown types (also Object's property names), missing or extra fields,
// wrong types, sparse arrays, NaN. Property: every request gets exactly one reply, in time; a refusal carries a
// code of ERROR_CODES that is not 'internal' (an ordinary mistake is never reported as a bug); and after the
// sequence the worker still answers.
import fc from 'fast-check';
import { Worker } from 'node:worker_threads';
import { ERROR_CODES } from '../../build/wasm/solver_schema.js';
import { OPTIONS } from '../../web/lib/options.js';
import { REQUEST_TYPES, requestFields } from '../../web/lib/worker/protocol.js';

const REPLY_MS = 60000; // far above any request here (the slowest binds the sphere: about a second)

/** A solver worker in a Node thread, with one request at a time. */
export class WorkerUnderTest {
  async start() {
    this.worker = new Worker(new URL('../js/support/worker_host.mjs', import.meta.url));
    this.waiting = null;
    this.nextId = 1;
    await new Promise((resolve, reject) => {
      this.worker.on('error', reject);
      this.worker.on('message', (message) => {
        if (message.type === 'host-ready') resolve();
        else if (message.type !== 'progress') this.waiting?.(message);
      });
    });
    return this;
  }

  /** Posts { id, ...message } and resolves with the reply, or rejects after REPLY_MS. */
  request(message) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => reject(new Error(`no reply in ${REPLY_MS} ms to ${describe(message)}`)), REPLY_MS);
      this.waiting = (reply) => {
        clearTimeout(timer);
        this.waiting = null;
        if (reply.id !== id) reject(new Error(`reply ${reply.id} to request ${id} (${describe(message)})`));
        else resolve(reply);
      };
      this.worker.postMessage({ ...message, id });
    });
  }

  stop() {
    return this.worker?.terminate();
  }
}

function describe(message) {
  return JSON.stringify(message, (k, v) => (ArrayBuffer.isView(v) ? `${v.constructor.name}(${v.length})` : v))?.slice(0, 400);
}

const PROTOTYPE_KEYS = ['constructor', 'toString', '__proto__', 'hasOwnProperty', 'valueOf'];
const hostileNumber = fc.oneof(fc.constantFrom(0, -0, 1, -1, 0.5, 3, 2 ** 31 - 1, 2 ** 31, 1e300, NaN, Infinity, -Infinity),
  fc.integer({ min: -5, max: 40 }));
const hostileValue = fc.oneof(hostileNumber, fc.boolean(), fc.constantFrom(null, undefined, '', 'x', ...PROTOTYPE_KEYS),
  fc.string({ maxLength: 6 }), fc.array(hostileNumber, { maxLength: 4 }), fc.jsonValue({ maxDepth: 2 }));
const mostly = (plausible) => fc.oneof({ weight: 5, arbitrary: plausible }, { weight: 1, arbitrary: hostileValue });

const OBJ_TETRA = new TextEncoder().encode('v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n');
const bytes = fc.oneof(fc.constant(OBJ_TETRA), fc.uint8Array({ maxLength: 64 }), fc.string({ maxLength: 40 }).map((s) => new TextEncoder().encode(s)));
const meshData = fc.oneof(
  fc.constant({ positions: new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]), indices: new Uint32Array([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]) }),
  fc.record({ positions: fc.float64Array({ maxLength: 12 }), indices: fc.uint32Array({ maxLength: 12 }) }),
  hostileValue,
);
const vertexList = fc.array(mostly(fc.integer({ min: 0, max: 60 })), { maxLength: 4 });
// Sizes are kept small where a valid value means work: iterations, cage vertices and modes (a valid request
// for hours of work would only time out; the protocol has no limit to find there).
const FIELDS = {
  name: mostly(fc.constantFrom('bar', 'sphere', 'nope', ...PROTOTYPE_KEYS)),
  subspace: mostly(fc.oneof(fc.constant({ basis: 'cage' }), fc.record({ basis: fc.constantFrom('spectral', 'cage', 'x'), modes: fc.oneof(fc.integer({ min: -1, max: 12 }), hostileNumber) }))),
  files: mostly(fc.array(fc.record({ name: mostly(fc.constantFrom('a.obj', 'b.off', 'c.stl', 'x')), bytes: mostly(bytes) }), { maxLength: 3 })),
  generateCage: mostly(fc.record({ vertices: fc.oneof(fc.constantFrom(4, 12, 20, 0, -1, 1e9), hostileNumber.filter((v) => !(v > 40))) })),
  mesh: meshData,
  cage: meshData,
  description: mostly(fc.string({ maxLength: 8 })),
  parts: fc.oneof(fc.constant(null), fc.record({ auto: fc.oneof(fc.integer({ min: -1, max: 5 }), hostileNumber) }),
    fc.array(vertexList, { maxLength: 3 }), fc.record({ triangles: fc.array(vertexList, { maxLength: 3 }) }), hostileValue),
  // An option near its limits (its default, a choice, a limit, one past it), sometimes a hostile value or key.
  options: mostly(fc.array(fc.oneof({ weight: 4, arbitrary: fc.constantFrom(...OPTIONS).chain((o) => fc.constantFrom(o.default, ...o.choices,
    o.min ?? 0, Math.min(o.max ?? 50, 50), (o.min ?? 0) - 1).map((v) => [o.name, v])) },
  { weight: 1, arbitrary: fc.tuple(fc.constantFrom(...OPTIONS.map((o) => o.name), 'bogus', ...PROTOTYPE_KEYS), hostileValue) }), { maxLength: 3 })
    .map((pairs) => Object.fromEntries(pairs))),
  // Sometimes sparse: a hole where group 1 was.
  groups: mostly(fc.tuple(fc.array(mostly(vertexList), { maxLength: 3 }), fc.boolean()).map(([groups, hole]) => {
    if (hole && groups.length > 1) delete groups[1];
    return groups;
  })),
  // 12 numbers fit the handles the sequences usually start with (4 vertices).
  targets: mostly(fc.oneof({ weight: 3, arbitrary: fc.array(fc.double({ min: -3, max: 3, noNaN: true }), { minLength: 12, maxLength: 12 }).map((a) => Float64Array.from(a)) },
    { weight: 1, arbitrary: fc.float64Array({ maxLength: 13 }) }, { weight: 1, arbitrary: fc.array(hostileNumber, { maxLength: 6 }) })),
  iterations: fc.oneof(fc.integer({ min: 0, max: 20 }), hostileNumber.filter((v) => !(Number.isInteger(v) && v > 40 && v < 2 ** 31))),
  what: mostly(fc.constantFrom('mesh', 'cage', 'restCage')),
  phase: mostly(fc.constantFrom('local', 'global')),
  threads: mostly(fc.integer({ min: 0, max: 4 })),
};
// Mostly a known type with its own fields (each present 4 times in 5), sometimes a foreign field, an unknown
// type or no payload at all: most requests then get past the protocol into the worker.
const request = fc.record({
  type: fc.oneof({ weight: 12, arbitrary: fc.constantFrom(...REQUEST_TYPES) }, { weight: 1, arbitrary: fc.constantFrom(...PROTOTYPE_KEYS, 'hello', 'solve') },
    { weight: 1, arbitrary: hostileValue }),
  foreign: fc.oneof({ weight: 7, arbitrary: fc.constant(null) }, { weight: 1, arbitrary: fc.constantFrom(...Object.keys(FIELDS)) }),
}).chain(({ type, foreign }) => {
  const own = typeof type === 'string' ? requestFields(type).filter((k) => Object.hasOwn(FIELDS, k)) : [];
  return fc.tuple(fc.record(Object.fromEntries(own.map((k) => [k, FIELDS[k]])), { requiredKeys: [] }),
    foreign === null ? fc.constant({}) : FIELDS[foreign].map((v) => ({ [foreign]: v })))
    .map(([payload, extra]) => ({ ...payload, ...extra, type }));
});

/** Sequences of requests, mostly after a valid model was loaded (so that deep paths are reached). */
export const workerInput = fc.tuple(fc.boolean(), fc.array(request, { minLength: 1, maxLength: 5 }))
  .map(([load, requests]) => (load ? [{ type: 'loadExample', name: 'bar' }, { type: 'setHandles', groups: [[0, 1, 2], [57]] }, ...requests] : requests));

/**
 * The property for one worker: each request of the sequence gets its reply; refusals have a known, non-internal
 * code; the worker still answers afterwards.
 * @param {WorkerUnderTest} worker
 */
export function workerProperty(worker) {
  return async (requests) => {
    for (const message of requests) {
      const reply = await worker.request(message);
      if (reply.ok === true) continue;
      const { code, message: text } = reply.error ?? {};
      if (!ERROR_CODES.includes(code) || code === 'internal' || typeof text !== 'string' || !text) {
        throw new Error(`${describe(message)} was answered ${JSON.stringify(reply.error)}`);
      }
    }
    const alive = await worker.request({ type: 'init' });
    if (!alive.ok) throw new Error(`the worker stopped answering: ${JSON.stringify(alive.error)}`);
  };
}
