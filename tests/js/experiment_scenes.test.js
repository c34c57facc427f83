// The experiments' scene files (docs/experiments/*.json, written by scripts/experiments.mjs) stay valid under the
// rule that a scene names files only in its own folder: their real models are plain file names, linked beside
// the scene to run it (docs/experiments/README.md), as a researcher does; the models themselves are not shipped.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, symlinkSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { parseScene } from 'subspace-deform';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const experiments = new URL('../../docs/experiments/', import.meta.url).pathname;
const sharedData = new URL('../../../shared/data', import.meta.url).pathname;
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });

// Scene files only: results.json, refinement.json and coordinates.json are results, with no handles.
const scenes = readdirSync(experiments).filter((f) => f.endsWith('.json'))
  .map((f) => ({ file: f, json: JSON.parse(readFileSync(join(experiments, f), 'utf8')) }))
  .filter(({ json }) => Array.isArray(json.handles));
const real = scenes.filter(({ json }) => json.mesh);
let dir;

beforeAll(() => {
  dir = mkdtempSync(join(tmpdir(), 'sd-experiments-'));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('docs/experiments scene files', () => {
  it('are there, the real-model ones among them', () => {
    expect(scenes.length).toBeGreaterThanOrEqual(6);
    expect(real.length).toBeGreaterThanOrEqual(5);
  });

  it.each(scenes.map((s) => [s.file, s.json]))('%s parses and names its models in its own folder', (file, json) => {
    expect(() => parseScene(json)).not.toThrow();
    for (const path of [json.mesh, json.cage].filter((p) => p !== undefined)) expect(path).toMatch(/^[\w.-]+$/);
    if (json.mesh) expect(json.description).toContain(`Link or copy ${json.mesh} and ${json.cage} beside this file first`);
    expect(json.description).toContain(`node scripts/deform.mjs deform docs/experiments/${file}`);
  });

  // Run in place without its models, a real-model scene says how to get them, not only that a file is missing.
  const inPlace = real.find(({ json }) => !existsSync(join(experiments, json.mesh)));
  it.skipIf(!inPlace)('a real-model scene run in place without its models says to link them from ../shared/data', () => {
    const r = run('deform', join(experiments, inPlace.file), '--max-iterations', '1', '--quiet');
    expect(r.status).toBe(1);
    expect(r.stderr).toContain(`cannot read ${join(experiments, inPlace.json.mesh)}: no such file`);
    expect(r.stderr).toContain('the experiments\' real models are not shipped: link them beside the scene first');
    expect(r.stderr).toContain('ln -s "$PWD"/../shared/data/');
    expect(r.stderr).toContain('docs/experiments/README.md');
  });

  // The README's recipe in a temp folder: the scene copied, its models linked beside it from ../shared/data.
  for (const { file, json } of real) {
    const models = [json.mesh, json.cage];
    it.skipIf(!models.every((m) => existsSync(join(sharedData, m))))(
      `${file} runs with its models linked beside it (skipped without ../shared/data)`, () => {
        copyFileSync(join(experiments, file), join(dir, file));
        for (const m of models) if (!existsSync(join(dir, m))) symlinkSync(join(sharedData, m), join(dir, m));
        const report = join(dir, `${file}.report.json`);
        const r = run('deform', join(dir, file), '--max-iterations', '1', '--quiet', '--report', report);
        expect(r.status, r.stderr).toBe(0);
        expect(JSON.parse(readFileSync(report, 'utf8')).iterationCount).toBe(1);
      });
  }
});
