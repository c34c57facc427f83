// The experiment and benchmark scripts' command lines: a typo must be refused with one clear line and a non-zero
// exit before any work, and must never overwrite the committed results with an empty run.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const scripts = new URL('../../scripts/', import.meta.url).pathname;
const run = (script, ...args) => spawnSync(process.execPath, [join(scripts, script), ...args], { encoding: 'utf8', timeout: 60000 });
let dir;

beforeAll(() => {
  dir = mkdtempSync(join(tmpdir(), 'sd-script-args-'));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('experiments.mjs', () => {
  it('refuses an unknown --only scene, naming the known ones, and writes nothing', () => {
    const r = run('experiments.mjs', '--only', 'two_vertex_pul', '--out', dir);
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(/unknown scene 'two_vertex_pul'/);
    expect(r.stderr).toMatch(/two_vertex_pull/);
    expect(r.stderr).toMatch(/neck_pull/);
    expect(existsSync(join(dir, 'results.json'))).toBe(false);
  });
});
