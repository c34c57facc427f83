// Command lines of the scripts (the CLI's commands, bench.mjs, experiments.mjs), read by Node's util.parseArgs.
// It runs in its lenient mode and this file applies the scripts' rules to its tokens, so that the messages stay
// the scripts' own: --name value and --name=value; a value may start with one dash (--offset -1, which the strict
// mode refuses as ambiguous) but not with two (--out --report: the value is missing); words of one dash that name
// no short flag ('-', '-1', '-x') are positionals; "--" ends the flags.
import { parseArgs } from 'node:util';

const MESSAGES = {
  unknown: (flag) => `unknown option ${flag}`,
  missing: (flag) => `${flag} needs a value`,
  // --float32=false used to write float32 and --json=no to print JSON: a switch given a value is refused.
  value: (flag) => `${flag} is a switch and takes no value (give ${flag.replace(/=.*/, '')} alone, or leave it out)`,
};

/** A command line that does not fit the flags: kind 'unknown', 'missing' or 'value', the flag as typed. */
export class CommandLineError extends Error {
  /** @param {'unknown'|'missing'|'value'} kind @param {string} flag e.g. '--out' */
  constructor(kind, flag) {
    super(MESSAGES[kind](flag));
    this.name = 'CommandLineError';
    this.kind = kind;
    this.flag = flag;
  }
}

/**
 * Splits argv into positionals and flags.
 * @param {string[]} argv
 * @param {Record<string, { type: 'string'|'boolean', short?: string }>} options util.parseArgs' options
 * @returns {{ positionals: string[], flags: Record<string, string|boolean> }} flags has no prototype, so a flag
 *   named by the user (--constructor, --__proto__) is never one of Object's properties; a flag given twice keeps
 *   its last value; a boolean flag given a value (--json=no) is refused.
 * @throws {CommandLineError}
 */
export function parseCommandLine(argv, options) {
  const { tokens } = parseArgs({ args: argv, options, strict: false, allowPositionals: true, tokens: true });
  const positionals = [];
  const flags = Object.create(null);
  const wordsTaken = new Set(); // argv indices already taken as positionals ("-ab" gives a token per letter)
  for (const token of tokens) {
    if (token.kind === 'positional') {
      positionals.push(token.value);
    } else if (token.kind === 'option') {
      const known = Object.hasOwn(options, token.name);
      if (!known && !token.rawName.startsWith('--')) {
        if (!wordsTaken.has(token.index)) positionals.push(argv[token.index]);
        wordsTaken.add(token.index);
        continue;
      }
      if (!known) throw new CommandLineError('unknown', token.rawName);
      if (options[token.name].type === 'boolean') {
        if (token.inlineValue) throw new CommandLineError('value', `${token.rawName}=${token.value}`);
        flags[token.name] = true;
      } else {
        const value = token.value;
        if (value === undefined || (!token.inlineValue && value.startsWith('--'))) throw new CommandLineError('missing', token.rawName);
        flags[token.name] = value;
      }
    }
  }
  return { positionals, flags };
}
