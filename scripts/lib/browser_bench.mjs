// What the browser benchmarks (bench/browser.mjs, bench/compare.mjs) share: their command-line options and
// the built site they measure.
import { spawnSync } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

export const repo = join(dirname(fileURLToPath(import.meta.url)), '..', '..');

/** `option(name, fallback)`: the value after `--name` in `args`, else `fallback`. */
export function optionReader(args) {
  return (name, fallback) => {
    const i = args.indexOf(`--${name}`);
    return i >= 0 ? args[i + 1] : fallback;
  };
}

/**
 * The site to measure: SD_E2E_DIST, else dist/ built now by Vite (SD_E2E_CONFIG or web/vite.config.js)
 * unless `--no-build` is in `args`. Exits on a failed build.
 */
export function siteToMeasure(args) {
  if (!args.includes('--no-build')) {
    const config = process.env.SD_E2E_CONFIG ?? join(repo, 'web', 'vite.config.js');
    const vite = join(repo, 'node_modules/vite/bin/vite.js');
    const r = spawnSync(process.execPath, [vite, 'build', '--config', config, '--logLevel', 'warn'], { cwd: repo, stdio: 'inherit' });
    if (r.status !== 0) process.exit(1);
  }
  return process.env.SD_E2E_DIST ?? join(repo, 'dist');
}
