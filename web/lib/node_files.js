// @ts-check
/// <reference types="node" />
// Files in Node, read and written in one place (the CLI, scripts, and any reader of a file format, e.g. mesh
// files or the buffers a scene names): every read is of a regular file, bounded by MAX_FILE_BYTES, and
// every failure is an InputError with a code:
//   unreadable_file   missing, not permitted, or not a regular file (a directory, a FIFO, a device such as
//                     /dev/zero or /dev/urandom: refused at once, never read or waited on)
//   file_too_large    more than the limit (file_limits.js)
//   unwritable_file   an output that cannot be written (a missing folder, a directory, a read-only file)
// checkWritable lets a command refuse a bad output path before it spends minutes computing what goes there.
import { closeSync, constants, fstatSync, openSync, readSync, statSync, unlinkSync, writeFileSync, writeSync } from 'node:fs';
import { basename, dirname, join } from 'node:path';
import { InputError } from './errors.js';
import { MAX_FILE_BYTES, checkFileSize } from './file_limits.js';

// Opening a FIFO for reading blocks until a writer comes; O_NONBLOCK makes the open return at once (the
// file is then refused by its type). Not every platform has it.
const OPEN_FOR_READING = constants.O_RDONLY | (constants.O_NONBLOCK ?? 0);

/**
 * What a non-regular file is, for messages.
 * @param {import('node:fs').Stats} stats
 */
function kindOf(stats) {
  if (stats.isDirectory()) return 'a directory';
  if (stats.isFIFO()) return 'a named pipe (FIFO)';
  if (stats.isCharacterDevice()) return 'a character device';
  if (stats.isBlockDevice()) return 'a block device';
  if (stats.isSocket()) return 'a socket';
  return 'not a regular file';
}

/**
 * @param {string} path
 * @param {string} reason
 * @param {unknown} [cause]
 */
function unreadable(path, reason, cause) {
  return new InputError(`cannot read ${path}: ${reason}`, { code: 'unreadable_file', cause });
}

/**
 * The code of an error Node's fs functions threw (ENOENT, ...).
 * @param {unknown} error
 * @returns {string|undefined}
 */
function codeOf(error) {
  return /** @type {NodeJS.ErrnoException} */ (error).code;
}

/** @param {unknown} error what an fs function threw */
function reasonOf(error) {
  switch (codeOf(error)) {
    case 'ENOENT': return 'no such file';
    case 'EACCES': case 'EPERM': return 'permission denied';
    case 'EISDIR': return 'it is a directory';
    case 'ENOTDIR': return 'a folder on its path is a file';
    default: return /** @type {Error} */ (error).message;
  }
}

/**
 * The bytes of a regular file. Directories, FIFOs, devices and sockets are refused before any byte is read,
 * a file over `maxBytes` as soon as that shows (its size, or the bytes read: /proc files report 0).
 * @param {string} path
 * @param {{ maxBytes?: number }} [options] maxBytes: the limit (default MAX_FILE_BYTES, 1 GiB)
 * @returns {Uint8Array}
 */
export function readFileBytes(path, { maxBytes = MAX_FILE_BYTES } = {}) {
  if (typeof path !== 'string' || path === '') throw new InputError('readFileBytes: path must be a non-empty string');
  if (!(Number.isInteger(maxBytes) && maxBytes >= 0)) throw new InputError('readFileBytes: maxBytes must be an integer >= 0');
  let fd;
  try {
    const stats = statSync(path);
    if (!stats.isFile()) throw unreadable(path, `it is ${kindOf(stats)}, not a regular file`);
    checkFileSize(stats.size, path, maxBytes);
    fd = openSync(path, OPEN_FOR_READING);
    const opened = fstatSync(fd); // the file may have been replaced since the first look
    if (!opened.isFile()) throw unreadable(path, `it is ${kindOf(opened)}, not a regular file`);
    return readBounded(fd, opened.size, path, maxBytes);
  } catch (error) {
    if (error instanceof InputError) throw error;
    throw unreadable(path, reasonOf(error), error);
  } finally {
    if (fd !== undefined) closeSync(fd);
  }
}

/**
 * Reads to the end, growing the buffer as needed, and refuses once more than maxBytes arrive.
 * @param {number} fd
 * @param {number} sizeHint the size the file reported
 * @param {string} path
 * @param {number} maxBytes
 * @returns {Uint8Array}
 */
function readBounded(fd, sizeHint, path, maxBytes) {
  let buffer = Buffer.allocUnsafe(Math.min(Math.max(sizeHint, 64 * 1024), maxBytes + 1));
  let length = 0;
  for (;;) {
    if (length === buffer.length) {
      checkFileSize(length, path, maxBytes, { exact: false });
      const grown = Buffer.allocUnsafe(Math.min(2 * buffer.length, maxBytes + 1));
      buffer.copy(grown, 0, 0, length);
      buffer = grown;
    }
    const read = readSync(fd, buffer, length, buffer.length - length, null);
    if (read === 0) break;
    length += read;
  }
  checkFileSize(length, path, maxBytes, { exact: false });
  return new Uint8Array(buffer.buffer, buffer.byteOffset, length);
}

/**
 * @param {string} path
 * @param {string} reason
 * @param {unknown} [cause]
 */
function unwritable(path, reason, cause) {
  return new InputError(`cannot write ${path}: ${reason}`, { code: 'unwritable_file', cause });
}

/**
 * Throws an InputError with code 'unwritable_file' unless `path` can be written: an existing regular file
 * that accepts writes, a device or pipe (e.g. /dev/null, /dev/stdout), or a new file in an existing folder
 * that lets us create one. Writes nothing, and leaves no file behind.
 * @param {string} path
 * @param {string} [what] the option or role, for the message (e.g. '--out')
 */
export function checkWritable(path, what = '') {
  const at = what ? `${what} ${path}` : path;
  let stats = null;
  try {
    stats = statSync(path);
  } catch (error) {
    if (codeOf(error) !== 'ENOENT') throw unwritable(at, reasonOf(error), error);
  }
  if (stats?.isDirectory()) throw unwritable(at, 'it is a directory');
  if (stats?.isFIFO() || stats?.isSocket()) return; // opening it could wait for a reader
  if (stats) return probeExisting(path, at);
  probeNew(path, at);
}

/**
 * An existing file: opened for writing without truncating it, and written zero bytes to (files of /proc
 * and /sys open, and then refuse the write).
 * @param {string} path
 * @param {string} at the path as messages name it
 */
function probeExisting(path, at) {
  let fd;
  try {
    fd = openSync(path, constants.O_WRONLY | constants.O_APPEND);
    writeSync(fd, Buffer.alloc(0));
  } catch (error) {
    throw unwritable(at, codeOf(error) === 'EIO' ? 'it does not accept writes' : reasonOf(error), error);
  } finally {
    if (fd !== undefined) closeSync(fd);
  }
}

/**
 * A new file: its folder must exist and let us create a file (made and removed at once).
 * @param {string} path
 * @param {string} at the path as messages name it
 */
function probeNew(path, at) {
  const folder = dirname(path);
  let stats;
  try {
    stats = statSync(folder);
  } catch (error) {
    throw unwritable(at, codeOf(error) === 'ENOENT' ? `the folder ${folder} does not exist` : reasonOf(error), error);
  }
  if (!stats.isDirectory()) throw unwritable(at, `${folder} is not a folder`);
  const probe = join(folder, `.${basename(path)}.${process.pid}.probe`);
  try {
    closeSync(openSync(probe, 'wx'));
    unlinkSync(probe);
  } catch (error) {
    throw unwritable(at, `cannot create a file in ${folder} (${reasonOf(error)})`, error);
  }
}

/**
 * Writes a file (text or bytes); a failure is an InputError with code 'unwritable_file' naming it.
 * @param {string} path
 * @param {string|Uint8Array} data
 */
export function writeFileBytes(path, data) {
  try {
    writeFileSync(path, data);
  } catch (error) {
    throw unwritable(path, codeOf(error) === 'EIO' ? 'it does not accept writes' : reasonOf(error), error);
  }
}
