// Files in Node through the library's one reader and writer (web/lib/node_files.js) and the CLI on top of it:
// only regular files are read, never more than the limit, and outputs are checked before any work. Before,
// a scene naming /dev/zero read 6-10 GB in 18-30 s, a FIFO blocked forever, and `deform --out
// /nonexistent/x.obj` failed as 'internal' after the solve had run.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, symlinkSync, truncateSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { InputError, MAX_FILE_BYTES, checkWritable, loadSolver, makeExample, maxThreads, readFileBytes, writeFileBytes, writeObj } from 'subspace-deform';
import { fetchFile, readFile } from '../../web/app/loading/files.js';
import { thrown } from './support/thrown.js';

const cli = new URL('../../scripts/deform.mjs', import.meta.url).pathname;
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });
let dir, fifo;

beforeAll(async () => {
  dir = mkdtempSync(join(tmpdir(), 'sd-files-'));
  const solver = await loadSolver();
  const { mesh, cage } = makeExample(solver, 'bar');
  writeFileSync(join(dir, 'bar.obj'), writeObj(solver, mesh));
  writeFileSync(join(dir, 'bar_cage.obj'), writeObj(solver, cage));
  fifo = join(dir, 'pipe.obj');
  if (spawnSync('mkfifo', [fifo]).status !== 0) fifo = null;
  // A sparse file one byte over the limit: no disk space, and refused by its size alone.
  writeFileSync(join(dir, 'huge.obj'), '');
  truncateSync(join(dir, 'huge.obj'), MAX_FILE_BYTES + 1);
  mkdirSync(join(dir, 'folder.obj'));
  const scene = (mesh) => JSON.stringify({ mesh, cage: 'bar_cage.obj', handles: [] });
  // A scene names files in its own folder only (an absolute path is refused by that rule): the devices through links.
  symlinkSync('/dev/zero', join(dir, 'zero.obj'));
  symlinkSync('/dev/urandom', join(dir, 'urandom.obj'));
  writeFileSync(join(dir, 'zero.json'), scene('zero.obj'));
  writeFileSync(join(dir, 'urandom.json'), scene('urandom.obj'));
  writeFileSync(join(dir, 'absolute.json'), scene('/dev/zero'));
  writeFileSync(join(dir, 'pipe.json'), scene('pipe.obj'));
  writeFileSync(join(dir, 'bar.json'), JSON.stringify({ mesh: 'bar.obj', cage: 'bar_cage.obj',
    handles: [{ vertices: [0, 1, 2] }, { vertices: [57], translate: [0, 0.3, 0] }] }));
  // ARAP with both tolerances 0 and the largest cap: it would iterate for hours.
  writeFileSync(join(dir, 'endless.json'), JSON.stringify({ example: 'bar',
    handles: [{ vertices: [0, 1, 2] }, { vertices: [57], translate: [0, 0.5, 0] }],
    solver: { method: 'arap', stepTolerance: 0, arapEnergyTolerance: 0, maxIterations: 2147483647 } }));
});

afterAll(() => rmSync(dir, { recursive: true, force: true }));

const codeOf = (body) => {
  const error = thrown(body);
  expect(error).toBeInstanceOf(InputError);
  return error.code;
};

describe('readFileBytes', () => {
  it('refuses devices, FIFOs and folders by their type without reading a byte or waiting', () => {
    expect(thrown(() => readFileBytes('/dev/zero')).message).toBe('cannot read /dev/zero: it is a character device, not a regular file');
    expect(codeOf(() => readFileBytes('/dev/urandom'))).toBe('unreadable_file');
    expect(thrown(() => readFileBytes(join(dir, 'folder.obj'))).message).toMatch(/it is a directory, not a regular file/);
    if (fifo) expect(thrown(() => readFileBytes(fifo)).message).toMatch(/it is a named pipe \(FIFO\), not a regular file/);
    expect(thrown(() => readFileBytes(join(dir, 'missing.obj'))).message).toMatch(/missing\.obj: no such file/);
  });

  it('refuses a file over the limit by its size, with its own code', () => {
    const error = thrown(() => readFileBytes(join(dir, 'huge.obj')));
    expect(error.code).toBe('file_too_large');
    expect(error.message).toMatch(/huge\.obj is 1073741825 bytes: more than the 1073741824 bytes a file may have here$/);
    writeFileSync(join(dir, 'small.obj'), 'x'.repeat(2000));
    expect(codeOf(() => readFileBytes(join(dir, 'small.obj'), { maxBytes: 1000 }))).toBe('file_too_large');
    expect(readFileBytes(join(dir, 'small.obj'), { maxBytes: 2000 })).toHaveLength(2000);
  });

  it('reads a regular file exactly, also one whose size the system reports as 0 (/proc)', () => {
    expect(Buffer.from(readFileBytes(join(dir, 'bar.obj'))).equals(readFileSync(join(dir, 'bar.obj')))).toBe(true);
    if (existsSync('/proc/version')) expect(new TextDecoder().decode(readFileBytes('/proc/version'))).toMatch(/\w/);
  });
});

describe('checkWritable and writeFileBytes', () => {
  it('refuse a missing folder, a folder, and a file that takes no writes, with code unwritable_file', () => {
    expect(thrown(() => checkWritable('/nonexistent/x.obj', '--out')).message)
      .toBe('cannot write --out /nonexistent/x.obj: the folder /nonexistent does not exist');
    expect(codeOf(() => checkWritable(join(dir, 'folder.obj')))).toBe('unwritable_file');
    if (existsSync('/proc/version')) expect(codeOf(() => checkWritable('/proc/version'))).toBe('unwritable_file');
    expect(codeOf(() => writeFileBytes('/nonexistent/x.obj', 'v 0 0 0\n'))).toBe('unwritable_file');
  });

  it('accept a new file, an existing one and /dev/null, and leave nothing behind', () => {
    const before = readdirSync(dir).sort();
    checkWritable(join(dir, 'new.obj'));
    checkWritable(join(dir, 'bar.obj'));
    checkWritable('/dev/null');
    expect(readdirSync(dir).sort()).toEqual(before);
    expect(readFileSync(join(dir, 'bar.obj'), 'utf8')).toMatch(/^# |^v /);
  });
});

describe('the CLI reads and writes through them', () => {
  it('check /dev/zero and a scene naming /dev/zero, /dev/urandom or a FIFO fail at once, naming the file', () => {
    for (const args of [['check', '/dev/zero'], ['deform', join(dir, 'zero.json')], ['deform', join(dir, 'urandom.json')],
      ...(fifo ? [['deform', join(dir, 'pipe.json')], ['check', fifo]] : [])]) {
      const r = run(...args);
      expect(r.status, args.join(' ')).toBe(1);
      expect(r.stderr).toMatch(/^error \(unreadable_file\): cannot read .*not a regular file/);
    }
    expect(run('deform', join(dir, 'absolute.json')).stderr).toMatch(/^error \(unreadable_file\): scene: "mesh" names "\/dev\/zero", an absolute path/);
    const huge = run('check', join(dir, 'huge.obj'));
    expect(huge.status).toBe(1);
    expect(huge.stderr).toMatch(/^error \(file_too_large\): /);
  });

  it('an unwritable --out or --report is refused before the solve runs', () => {
    for (const flag of [['--out', '/nonexistent/x.obj'], ['--report', '/proc/version'], ['--cage-out', join(dir, 'folder.obj')]]) {
      if (flag[1] === '/proc/version' && !existsSync('/proc/version')) continue;
      const r = run('deform', join(dir, 'bar.json'), ...flag);
      expect(r.status, flag.join(' ')).toBe(1);
      expect(r.stderr).toMatch(new RegExp(`^error \\(unwritable_file\\): cannot write ${flag[0]} `));
      expect(r.stdout).toBe(''); // nothing was solved
    }
    for (const [command, ...args] of [['weights', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj')], ['cage', join(dir, 'bar.obj'), '--vertices', '30']]) {
      const r = run(command, ...args, '--out', '/nonexistent/x');
      expect(r.status, command).toBe(1);
      expect(r.stderr).toMatch(/^error \(unwritable_file\)/);
    }
  });

  it('refuses an output that is an input or another output (exit 2, naming both), and a weights --out not .npy', () => {
    writeFileSync(join(dir, 'keep.obj'), readFileSync(join(dir, 'bar.obj')));
    writeFileSync(join(dir, 'keep_cage.obj'), readFileSync(join(dir, 'bar_cage.obj')));
    writeFileSync(join(dir, 'keep.json'), JSON.stringify({ mesh: 'keep.obj', cage: 'keep_cage.obj', handles: [{ vertices: [0] }] }));
    const cases = [
      [['weights', join(dir, 'keep.obj'), join(dir, 'keep_cage.obj'), '--out', join(dir, 'keep_cage.obj')], /--out must name a \.npy file/],
      [['cage', join(dir, 'keep.obj'), '--vertices', '30', '--out', `${dir}/./keep.obj`], /--out '.*keep\.obj' is the same file as the mesh/],
      [['deform', join(dir, 'keep.json'), '--out', join(dir, 'r.obj'), '--cage-out', join(dir, 'r.obj')], /--cage-out '.*r\.obj' is the same file as --out/],
      [['deform', join(dir, 'keep.json'), '--out', join(dir, 'keep.obj')], /--out '.*keep\.obj' is the same file as the scene's mesh/],
      [['deform', join(dir, 'keep.json'), '--report', join(dir, 'keep.json')], /--report '.*keep\.json' is the same file as the scene/],
    ];
    for (const [args, pattern] of cases) {
      const r = run(...args);
      expect(r.status, args.join(' ')).toBe(2);
      expect(r.stderr).toMatch(pattern);
    }
    expect(readFileSync(join(dir, 'keep.obj'))).toEqual(readFileSync(join(dir, 'bar.obj')));
    expect(readFileSync(join(dir, 'keep_cage.obj'))).toEqual(readFileSync(join(dir, 'bar_cage.obj')));
  });

  it('out-of-range flags are bad usage (exit 2) whichever limit they break', () => {
    const cases = [
      ['cage', join(dir, 'bar.obj'), '--vertices', '99999', '--out', join(dir, 'c.obj')],
      ['cage', join(dir, 'bar.obj'), '--vertices', '30', '--resolution', '1000', '--out', join(dir, 'c.obj')],
      ['cage', join(dir, 'bar.obj'), '--vertices', '30', '--offset', '-1', '--out', join(dir, 'c.obj')],
      ['weights', join(dir, 'bar.obj'), join(dir, 'bar_cage.obj'), '--memory-budget', 'lots', '--out', join(dir, 'w.npy')],
      ['deform', join(dir, 'bar.json'), '--parts', '1001'],
      ['deform', join(dir, 'bar.json'), '--max-iterations', '2147483648'],
      ['deform', join(dir, 'bar.json'), '--time-limit', '0'],
      ['deform', join(dir, 'bar.json'), '--modes', '2147483647'],
      ['check', join(dir, 'bar.obj'), '--threads', '5000'],
      ['check', join(dir, 'bar.obj'), '--threads', String(maxThreads() + 1)], // 64 on 2 cores: 13.5 s, 654 MB to start
      ['check', join(dir, 'bar.obj'), '--threads', '0x2'],
    ];
    for (const args of cases) {
      const r = run(...args);
      expect(r.status, args.join(' ')).toBe(2);
      expect(r.stderr).toMatch(/^usage error: --[a-z-]+ must be /);
    }
  });

  it('--time-limit stops a solve that would not end, and the result so far is written', () => {
    const out = join(dir, 'endless.obj'), report = join(dir, 'endless_report.json');
    const r = run('deform', join(dir, 'endless.json'), '--time-limit', '1.5', '--out', out, '--report', report);
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/NOT converged \(stopped by --time-limit\)/);
    const rep = JSON.parse(readFileSync(report, 'utf8'));
    expect(rep.cutShort.by).toBe('time limit');
    expect(rep.iterationCount).toBeGreaterThan(0);
    expect(rep.iterationCount).toBe(rep.iterations.length);
    expect(readFileSync(out, 'utf8')).toMatch(/^# deformed by subspace-deform/);
  });

  it('Ctrl-C (SIGINT) stops it too: exit 130, the mesh and the report of the iterations so far written', async () => {
    const out = join(dir, 'interrupted.obj'), report = join(dir, 'interrupted_report.json');
    const child = spawn(process.execPath, [cli, 'deform', join(dir, 'endless.json'), '--out', out, '--report', report]);
    let stderr = '';
    child.stderr.on('data', (chunk) => { stderr += chunk; });
    // The progress line says the solve is under way (the first comes after 5 s); then interrupt it.
    await new Promise((resolve) => {
      const poll = setInterval(() => {
        if (stderr.includes('iterations in')) { clearInterval(poll); resolve(); }
      }, 100);
    });
    child.kill('SIGINT');
    const status = await new Promise((resolve) => child.on('exit', (code) => resolve(code)));
    expect(status).toBe(130);
    expect(stderr).toMatch(/Ctrl-C stops and writes the result so far/);
    const rep = JSON.parse(readFileSync(report, 'utf8'));
    expect(rep.cutShort.by).toBe('SIGINT');
    expect(rep.iterationCount).toBeGreaterThan(0);
    expect(readFileSync(out, 'utf8')).toMatch(/^# deformed by subspace-deform/);
  });
});

describe("the app's readers (dropped files, URLs) have the same limit", () => {
  it('a dropped file over the limit is refused by its size, before its bytes are read', async () => {
    let read = false;
    const file = { name: 'huge.stl', size: MAX_FILE_BYTES + 1, arrayBuffer: async () => { read = true; return new ArrayBuffer(0); } };
    const error = await readFile(file).catch((e) => e);
    expect(error).toBeInstanceOf(InputError);
    expect(error.code).toBe('file_too_large');
    expect(read).toBe(false);
    expect((await readFile({ name: 'a.obj', size: 3, arrayBuffer: async () => new Uint8Array([1, 2, 3]).buffer })).bytes).toHaveLength(3);
  });

  it('a URL whose response declares more than the limit is refused by that length', async () => {
    const realFetch = globalThis.fetch;
    globalThis.fetch = async () => new Response('v 0 0 0\n', { headers: { 'content-length': String(2 ** 31) } });
    try {
      const error = await fetchFile('model.obj', { base: 'http://example.test/course/' }).catch((e) => e);
      expect(error.code).toBe('file_too_large');
      expect(error.message).toMatch(/^model\.obj is 2\.15 GB: more than the 1\.07 GB/);
    } finally {
      globalThis.fetch = realFetch;
    }
  });
});
