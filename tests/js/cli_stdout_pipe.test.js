// The CLI's stdout closed early by its reader (`deform scene.json | head -1`): like a Unix tool it stops writing
// quietly (no unhandled 'error' event, no stack) and ends with the command's own status.
import { describe, expect, it } from 'vitest';
import { spawn } from 'node:child_process';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const scene = new URL('../../docs/experiments/large_rotation_bar.json', import.meta.url).pathname;

describe('deform with its stdout closed by the reader', () => {
  it('exits 0 with nothing on stderr', async () => {
    const child = spawn(process.execPath, [cli, 'deform', scene, '--max-iterations', '3', '--threads', '1'], { stdio: ['ignore', 'pipe', 'pipe'] });
    // Closed before the first line: every write meets a closed pipe (EPIPE), not only a late one.
    child.stdout.destroy();
    let stderr = '';
    child.stderr.on('data', (chunk) => { stderr += chunk; });
    const status = await new Promise((done) => child.on('close', (code) => done(code)));
    expect(stderr).toBe('');
    expect(status).toBe(0);
  });
});
