// @ts-check
// Paths a file names relative to itself (a .gltf's buffers and images, a scene's mesh and cage) stay inside the
// file's own folder and below: a site that converts strangers' files must not read files of its own and embed
// them in its output. Checked on the text alone, the same in Node and in a browser: an absolute path, a drive
// letter, a URI scheme (file:, http:) or a '..' that climbs above the folder is refused; a glTF URI's percent
// escapes are decoded first (so '..%2Fx' is '../x'). Symbolic links are not followed here.
import { InputError } from './errors.js';

const SCHEME = /^[a-z][a-z0-9+.-]*:/i; // also a Windows drive letter ("C:")

/**
 * The path with '.' and 'a/..' removed, '/'-separated, or an InputError (code 'unreadable_file') naming it and
 * the rule when it would leave its folder.
 * @param {string} path as the file gives it
 * @param {string} what the file and the entry, for the message (e.g. 'robot.gltf: buffer 0')
 * @param {string} [shown] the path as the file wrote it, for the message
 * @returns {string}
 */
export function containedPath(path, what, shown = path) {
  const refuse = (/** @type {string} */ why) => {
    throw new InputError(`${what} names "${shown}", ${why}: a file may name only files in its own folder and below`,
      { code: 'unreadable_file' });
  };
  if (path.includes('\0')) refuse('which holds a NUL character');
  if (SCHEME.test(path)) refuse('an absolute URI or drive');
  if (/^[/\\]/.test(path)) refuse('an absolute path');
  const parts = [];
  for (const part of path.split(/[/\\]/)) { // a backslash separates folders on Windows
    if (part === '..') {
      if (!parts.length) refuse('which climbs out of its folder');
      parts.pop();
    } else if (part !== '.' && part !== '') {
      parts.push(part);
    }
  }
  if (!parts.length) refuse('which is no file');
  return parts.join('/');
}

/**
 * A glTF URI (not a data: URI) as a contained path: its percent escapes decoded (a malformed one is an
 * InputError, code 'parse_error', naming the URI), then containedPath.
 * @param {string} uri
 * @param {string} what
 * @returns {string}
 */
export function containedUri(uri, what) {
  let path;
  try {
    path = decodeURIComponent(uri);
  } catch {
    throw new InputError(`${what} has the uri "${uri}", whose % escapes are malformed (each % must start a valid ` +
      'UTF-8 escape such as %20)', { code: 'parse_error' });
  }
  return containedPath(path, what, uri);
}
