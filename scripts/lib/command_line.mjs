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

/**
 * A command line that does not fit the flags: kind 'unknown', 'missing' or 'value', the flag as typed; 'number'
 * for a flag's value out of its range (numberValue).
 */
export class CommandLineError extends Error {
  /** @param {'unknown'|'missing'|'value'|'number'} kind @param {string} flag e.g. '--out' @param {string} [message] */
  constructor(kind, flag, message = MESSAGES[kind](flag)) {
    super(message);
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

/**
 * A numeric flag's value, else a CommandLineError (kind 'number') naming the flag and the range, e.g.
 * "--vertices must be an integer from 4 to 20000 (got 'abc')".
 * @param {string} text
 * @param {string} name e.g. '--vertices'
 * @param {{ min?: number, max?: number, integer?: boolean, minOpen?: boolean }} range minOpen: min itself excluded
 */
export function numberValue(text, name, { min = -Infinity, max = Infinity, integer = false, minOpen = false } = {}) {
  const n = /^\s*$/.test(text) ? NaN : Number(text);
  const inRange = Number.isFinite(n) && (minOpen ? n > min : n >= min) && n <= max && (!integer || Number.isInteger(n));
  if (!inRange) {
    const kind = integer ? 'an integer' : 'a number';
    const lower = Number.isFinite(min) ? (minOpen ? `above ${min}` : `from ${min}`) : '';
    const upper = Number.isFinite(max) ? `${lower ? ' ' : ''}to ${max}` : '';
    const range = lower || upper ? ` ${lower}${upper}`.replace(/^ above (\S+) to/, ' above $1 and up to') : '';
    throw new CommandLineError('number', name, `${name} must be ${kind}${range} (got '${text}')`);
  }
  return n;
}
