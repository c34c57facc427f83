// Output files that are one of the inputs, or one another: `weights m.obj c.obj --out c.obj` overwrote the cage
// with .npy bytes, `cage m.obj --out m.obj` the mesh, and `deform --out r.obj --cage-out r.obj --report r.obj`
// wrote three results into one file, each destroying the last. Refused as bad usage (exit 2) before any work,
// naming both; paths are compared resolved (./a.obj and a.obj are one file; so are two names of one file).
// A .gltf input brings its external files too (its .bin and textures: `--report model.bin` overwrote one).
import { readFileSync, realpathSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
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
  const given = Object.entries(inputs).filter(([, path]) => path).flatMap(([what, path]) => [[what, path], ...gltfFiles(what, path)]);
  const seen = new Map(given.map(([what, path]) => [canonical(path), what]));
  for (const [flag, path] of Object.entries(outputs)) {
    if (!path) continue;
    const key = canonical(path);
    if (seen.has(key)) throw new UsageError(`${flag} '${path}' is the same file as ${seen.get(key)}: refusing to overwrite it`);
    seen.set(key, flag);
  }
}

/**
 * The external files a .gltf names (buffers' and images' uris that are not data: URIs), as [what, path]; none for
 * another file, or one that cannot be read or parsed (the reader says why, later).
 * @param {string} what @param {string} path @returns {[string, string][]}
 */
function gltfFiles(what, path) {
  if (!/\.gltf$/i.test(path)) return [];
  let json;
  try {
    json = JSON.parse(readFileSync(path, 'utf8'));
  } catch {
    return [];
  }
  const uris = [...(json?.buffers ?? []), ...(json?.images ?? [])].map((item) => item?.uri)
    .filter((uri) => typeof uri === 'string' && !uri.startsWith('data:'));
  return uris.map((uri) => {
    let file = uri;
    try { file = decodeURIComponent(uri); } catch { /* kept as written */ }
    return [`${what}'s file '${uri}'`, resolve(dirname(path), file)];
  });
}
