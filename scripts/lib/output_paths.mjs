// Output files that are one of the inputs, or one another: `weights m.obj c.obj --out c.obj` overwrote the cage
// with .npy bytes, `cage m.obj --out m.obj` the mesh, and `deform --out r.obj --cage-out r.obj --report r.obj`
// wrote three results into one file, each destroying the last. Refused as bad usage (exit 2) before any work,
// naming both; paths are compared resolved (./a.obj and a.obj are one file; so are two names of one file).
import { realpathSync } from 'node:fs';
import { resolve } from 'node:path';
import { UsageError } from './cli_support.mjs';

// The path as the file system will reach it: through links where the file exists, else as written, resolved.
function canonical(path) {
  try {
    return realpathSync(path);
  } catch {
    return resolve(path);
  }
}

/**
 * @param {Record<string, string|undefined>} outputs flag -> path, e.g. { '--out': 'W.npy' } (undefined: not given)
 * @param {Record<string, string|undefined>} inputs what -> path, e.g. { 'the cage': 'c.obj' }
 */
export function checkOutputPaths(outputs, inputs) {
  const seen = new Map(Object.entries(inputs).filter(([, path]) => path).map(([what, path]) => [canonical(path), what]));
  for (const [flag, path] of Object.entries(outputs)) {
    if (!path) continue;
    const key = canonical(path);
    if (seen.has(key)) throw new UsageError(`${flag} '${path}' is the same file as ${seen.get(key)}: refusing to overwrite it`);
    seen.set(key, flag);
  }
}
