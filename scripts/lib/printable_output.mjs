// What the CLI prints, made safe for a terminal. Its messages quote input files (a glTF's buffer URI, a scene's
// unknown field, a JSON parser's excerpt of a binary file), and a file from a stranger could hold escape
// sequences that clear the screen, retitle the window or hide text. Every character that is not printable is
// shown as its \uXXXX escape instead, in one place: the process's stdout and stderr, so that no message (a
// finding, a warning, an error, a path) can miss it. \uXXXX is also JSON's own escape, so --json output stays
// valid JSON (JSON.stringify leaves DEL, C1 controls and bidirectional overrides raw; they only occur in strings).

// The control characters (C0, DEL, C1) but tab and newline, and the bidirectional overrides and isolates that reorder
// what is shown ("Trojan Source").
const UNPRINTABLE = /(?![\t\n])[\p{Cc}\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069]/gu;

/**
 * The text with every non-printable character written as \uXXXX (e.g. ESC as \u001b).
 * @param {string} text
 * @returns {string}
 */
export function printable(text) {
  return text.replace(UNPRINTABLE, (c) => `\\u${c.charCodeAt(0).toString(16).padStart(4, '0')}`);
}

/**
 * Makes every string written to the stream printable (console.log and console.error write through it).
 * @param {NodeJS.WriteStream} stream process.stdout or process.stderr
 */
export function escapeUnprintable(stream) {
  const write = stream.write.bind(stream);
  stream.write = (chunk, ...rest) => write(typeof chunk === 'string' ? printable(chunk) : chunk, ...rest);
}

/**
 * When the reader closes the pipe early (`deform scene.json | head -1`), stops writing quietly, as a Unix tool
 * does: Node raised an unhandled 'error' event (EPIPE), printed its stack and exited 1, sometimes, as the race
 * fell. The command itself goes on to its end and status, so the files it was asked to write are still written.
 * @param {NodeJS.WriteStream} stream process.stdout or process.stderr
 */
export function quietWhenPipeCloses(stream) {
  let closed = false;
  const write = stream.write.bind(stream);
  stream.write = (...args) => closed || write(...args);
  stream.on('error', (error) => {
    if (error.code !== 'EPIPE') throw error;
    closed = true;
  });
}
