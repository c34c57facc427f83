// The CLI's stdout closed early by its reader (`deform scene.json | head -1`): like a Unix tool it stops writing
// quietly (no unhandled 'error' event, no stack) and ends with the command's own status; so with its stderr closed.
import { describe, expect, it } from 'vitest';
import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

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

// Its stderr too (`deform ... 2>&1 | head -1`): the cage command's progress lines met the closed pipe, and the
// unhandled EPIPE made a run that wrote its cage exit 1.
describe('cage with its stderr closed by the reader', () => {
  it('writes the cage and exits 0', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'sd-stderr-pipe-'));
    try {
      const out = join(dir, 'cage.obj');
      const mesh = new URL('../data/cube.off', import.meta.url).pathname;
      const child = spawn(process.execPath, [cli, 'cage', mesh, '--vertices', '60', '--out', out, '--threads', '1'], { stdio: ['ignore', 'pipe', 'pipe'] });
      child.stderr.destroy(); // before the first progress line
      let stdout = '';
      child.stdout.on('data', (chunk) => { stdout += chunk; });
      const status = await new Promise((done) => child.on('close', (code) => done(code)));
      expect(stdout).toMatch(/^cage: 60 vertices/);
      expect(existsSync(out)).toBe(true);
      expect(status).toBe(0);
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }
  });
});
