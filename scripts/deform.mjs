#!/usr/bin/env node
// subspace-deform command-line tool (docs/scene-format.md for scenes and reports). Runs the same .wasm as
// the app, through the library package (web/lib, imported as 'subspace-deform').
//   node scripts/deform.mjs <command> [args]    commands: deform, weights, cage, check
// Exit status: 0 success, 1 invalid input or failed run ("error (code): message" on stderr, with the
// library's error code), 2 bad usage.
import { escapeUnprintable, quietWhenPipeCloses } from './lib/printable_output.mjs';
import { requireBuild } from './lib/require_build.mjs';

// Messages quote the input files: a control character in one must not reach the terminal (printable_output.mjs).
escapeUnprintable(process.stdout);
escapeUnprintable(process.stderr);
quietWhenPipeCloses(process.stdout);
quietWhenPipeCloses(process.stderr); // `deform ... 2>&1 | head -1` closes it too (progress, warnings, errors)

// A Map: the command name is the user's first argument ('constructor' must not find Object's).
const COMMANDS = new Map(Object.entries({
  deform: { module: './cli/deform_command.mjs', run: 'deformCommand', summary: 'solve a scene file: deformed mesh, cage and a convergence report' },
  weights: { module: './cli/weights.mjs', run: 'weightsCommand', summary: 'mean value coordinates W of a mesh in a cage, as a NumPy .npy file' },
  cage: { module: './cli/cage.mjs', run: 'cageCommand', summary: 'generate a cage with about K vertices around a mesh (open ones too)' },
  check: { module: './cli/check.mjs', run: 'checkCommand', summary: 'validate a mesh (and a cage around it)' },
}));

function usage() {
  const lines = [...COMMANDS].map(([name, c]) => `  ${name.padEnd(8)} ${c.summary}`);
  return [
    'usage: node scripts/deform.mjs <command> [options]',
    '',
    'commands:',
    ...lines,
    '',
    "Run 'node scripts/deform.mjs <command> --help' for a command's options.",
  ].join('\n');
}

async function main(argv) {
  const [name, ...rest] = argv;
  if (!name || name === '--help' || name === '-h' || name === 'help') {
    console.log(usage());
    return name ? 0 : 2;
  }
  const command = COMMANDS.get(name);
  if (!command) {
    console.error(`unknown command '${name}'\n\n${usage()}`);
    return 2;
  }
  // The usage above needs no build; the commands run the library (lib/require_build.mjs).
  requireBuild('deform');
  const { runCommand } = await import('./lib/cli_support.mjs');
  const module = await import(new URL(command.module, import.meta.url));
  return runCommand(() => module[command.run](rest));
}

process.exitCode = await main(process.argv.slice(2)).catch(async (error) => {
  const { failure } = await import('./lib/cli_support.mjs');
  const { status, message } = failure(error);
  console.error(message);
  return status;
});
