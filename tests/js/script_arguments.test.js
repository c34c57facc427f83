// The experiment and benchmark scripts' command lines: a typo must be refused with one clear line and a non-zero
// exit before any work, and must never overwrite the committed results with an empty run.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { cpSync, existsSync, mkdtempSync, rmSync, symlinkSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const repo = new URL('../../', import.meta.url).pathname;
const scripts = join(repo, 'scripts');
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

describe('the benchmarks', () => {
  it('bench.mjs refuses an unknown --models name, naming the known ones', () => {
    const r = run('bench.mjs', '--models', 'cwo', '--no-native', '--no-scaling', '--no-integration', '--cases', '5000:24');
    expect(r.status).toBe(2);
    expect(r.stderr.trim()).toBe("bench: --models: unknown name 'cwo' (known: handbones, gargoyle, moomoo, cow, spikybox, boy)");
  });

  it('model_threads.mjs refuses unknown flags and model names, and says when none is present (exit 1)', () => {
    const flag = run('bench/model_threads.mjs', '--model', 'cow');
    expect(flag.status).toBe(2);
    expect(flag.stderr).toMatch(/^model_threads: unknown option --model\n/);
    const name = run('bench/model_threads.mjs', '--models', 'cwo');
    expect(name.status).toBe(2);
    expect(name.stderr).toMatch(/^model_threads: --models: unknown name 'cwo' \(known: handbones, /);
    const absent = run('bench/model_threads.mjs', '--models', 'cow', '--data', dir);
    expect(absent.status).toBe(1);
    expect(absent.stderr).toMatch(/none of cow is in .*: nothing to measure/);
  });
});

// Each refused before any work with one line naming the flag (exit 2), where it used to run something else.
describe('the argument checks of the experiment and bench scripts', () => {
  it.each([
    ['experiments/refinement.mjs', ['--scales', 'abc'], "refinement: --scales must be an integer from 1 to 16 (got 'abc')"],
    ['experiments/refinement.mjs', ['--scale', '2'], /^refinement: unknown option --scale\n/],
    ['bench/coordinates.mjs', ['--case', 'nope'], "bench/coordinates: --case: unknown name 'nope' (known: box, bent)"],
    ['bench/coordinates.mjs', ['--repeat', 'x'], "bench/coordinates: --repeat must be an integer from 1 (got 'x')"],
    ['bench/mvc.mjs', ['abc'], "bench/mvc: a size must be an integer from 1 (got 'abc')"],
    ['bench/mvc.mjs', ['--float64'], /^bench\/mvc: unknown option --float64\n/],
    ['bench/cage.mjs', ['abc'], "bench/cage: K must be an integer from 4 to 20000 (got 'abc')"],
    ['experiments/skeleton_arm.mjs', ['--outdir', 'x'], /^skeleton_arm: unknown option --outdir\n/],
  ])('%s %j is refused', (script, args, message) => {
    const r = run(script, ...args);
    expect(r.status).toBe(2);
    if (typeof message === 'string') expect(r.stderr.trim()).toBe(message);
    else expect(r.stderr).toMatch(message);
    expect(r.stdout).toBe('');
  });

  it('skeleton_arm.mjs prints --help', () => {
    const r = run('experiments/skeleton_arm.mjs', '--help');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/^usage: node scripts\/experiments\/skeleton_arm\.mjs \[--out DIR\]/);
  });
});

// A clone before its first build: the scripts, the library and package.json, no build/ (node_modules linked).
describe('the scripts in a clone with no build', () => {
  let clone;
  beforeAll(() => {
    clone = join(dir, 'clone');
    for (const part of ['scripts', 'web', 'package.json']) cpSync(join(repo, part), join(clone, part), { recursive: true });
    symlinkSync(join(repo, 'node_modules'), join(clone, 'node_modules'));
  });

  it.each([
    ['deform.mjs', 'check', 'x.obj'],
    ['deform.mjs', 'check', '--help'],
    ['bench.mjs', '--quick'],
    ['experiments.mjs', '--quick'],
  ])('%s %s says in one line to build first', (script, ...args) => {
    const r = spawnSync(process.execPath, [join(clone, 'scripts', script), ...args], { encoding: 'utf8', timeout: 60000 });
    expect(r.status).toBe(1);
    expect(r.stderr.trim().split('\n')).toHaveLength(1);
    expect(r.stderr).toMatch(/build\/wasm\/solver_schema\.js is missing\): run 'npm test'.*bash scripts\/build\.sh'/);
  });

  it('deform.mjs --help still prints the commands', () => {
    const r = spawnSync(process.execPath, [join(clone, 'scripts', 'deform.mjs'), '--help'], { encoding: 'utf8' });
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/^usage: /);
  });
});
