// The command lines of the benchmark and experiment scripts (scripts/bench/*.mjs, scripts/experiments/*.mjs):
// lib/command_line.mjs' rules, every refusal exit 2 before any work with one line "<tool>: <why>": alone for a bad
// value, followed by the script's help for a command line it cannot read (an unknown flag, a missing value, an
// extra argument), as the usage shows then what it takes. Before this, several read their flags by position and
// ignored what they did not know, so a typo ran the default case, a word where a number belonged ran n = 2, and a
// misspelt model name measured nothing and exited 0.
import { CommandLineError, numberValue, parseCommandLine } from './command_line.mjs';

/** Prints "<tool>: <message>" on stderr and exits 2 (bad usage). */
export function refuse(tool, message) {
  console.error(`${tool}: ${message}`);
  process.exit(2);
}

/**
 * The script's flags and positionals; --help (-h) prints `help` and exits 0; an unknown flag, a missing value
 * or more positionals than `maxPositionals` is refused (exit 2): one line saying why, then `help`.
 * @param {string} tool e.g. 'refinement'
 * @param {string[]} argv
 * @param {Record<string, 'string'|'boolean'>} spec
 * @param {string} help
 * @param {{ maxPositionals?: number }} [options]
 * @returns {{ positionals: string[], flags: Record<string, string|boolean> }}
 */
export function readScriptOptions(tool, argv, spec, help, { maxPositionals = 0 } = {}) {
  const options = { help: { type: 'boolean', short: 'h' } };
  for (const [name, type] of Object.entries(spec)) options[name] = { type };
  let parsed;
  try {
    parsed = parseCommandLine(argv, options);
  } catch (error) {
    if (!(error instanceof CommandLineError)) throw error;
    refuse(tool, `${error.message}\n${help}`);
  }
  if (parsed.flags.help) {
    console.log(help);
    process.exit(0);
  }
  if (parsed.positionals.length > maxPositionals) refuse(tool, `unknown argument '${parsed.positionals[maxPositionals]}'\n${help}`);
  return parsed;
}

/** A numeric value (lib/command_line.mjs' numberValue), else refused naming the flag and its range. */
export function numberOption(tool, text, name, range) {
  try {
    return numberValue(text, name, range);
  } catch (error) {
    if (!(error instanceof CommandLineError)) throw error;
    return refuse(tool, error.message);
  }
}

/** A comma-separated list whose every item is one of `known`, else refused naming the item and the known ones. */
export function namesOption(tool, text, name, known) {
  const names = text.split(',');
  const unknown = names.find((item) => !known.includes(item));
  if (unknown !== undefined) refuse(tool, `${name}: unknown name '${unknown}' (known: ${known.join(', ')})`);
  return names;
}
