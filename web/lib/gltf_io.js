// @ts-check
// glTF-Transform's reader and writer with the extensions this library keeps: gltf.js reads with it and
// gltf_write.js writes with it. A module of its own that no public function's type names, so that the
// package's declarations do not import glTF-Transform's (a strict consumer's type check, without
// skipLibCheck, would otherwise reach them: they need the ES2025 Float16Array).
import { WebIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { COMPRESSION_EXTENSIONS } from './gltf_check.js';

/**
 * @param {{ debug: () => void, info: () => void, warn: (text: string) => void, error: (text: string) => void }} [logger]
 *   where glTF-Transform's messages go (gltf_unknown.js collects them: a library prints nothing itself)
 */
export function gltfIO(logger) {
  // Every extension glTF-Transform knows is kept on the way back, except the compressed geometry ones, whose
  // decoders are not bundled (checkGltfJson refuses files that require them).
  const extensions = ALL_EXTENSIONS.filter((e) => !COMPRESSION_EXTENSIONS.includes(e.EXTENSION_NAME));
  const io = new WebIO().registerExtensions(extensions);
  return logger ? io.setLogger(/** @type {any} */ (logger)) : io;
}
