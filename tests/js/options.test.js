// The one options schema: generated from the C++ table, the same on both sides of the boundary. Every
// option round-trips C++ -> JS -> C++ with its default; values outside the limits or of the wrong type
// are refused in JS (Deformer.setOptions, the scene parser) and at the C++ boundary with the same message,
// which names the real limit.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import {
  DEFAULT_OPTIONS, Deformer, InputError, JACOBIANS, METHODS, OPTIONS, OPTION_NAMES, checkSolverOptions, loadSolver, makeExample,
  optionAllows, parseScene,
} from 'subspace-deform';
import { thrown } from './support/thrown.js';

let solver;
let d;

beforeAll(async () => {
  solver = await loadSolver();
  const bar = makeExample(solver, 'bar');
  d = Deformer.create(solver, bar.mesh, bar.cage);
});
afterAll(() => d?.dispose());

// A valid value other than the default.
function otherValue(option) {
  if (option.kind === 'choice') return option.choices.find((c) => c !== option.default);
  if (option.kind === 'boolean') return !option.default;
  if (option.kind === 'integer') return option.default + 1 <= option.max ? option.default + 1 : option.default - 1;
  const doubled = 2 * option.default;
  return optionAllows(option, doubled) ? doubled : option.default / 2;
}

// Values each kind must refuse: past each limit, non-finite, not an integer, the wrong type.
function badValues(option) {
  switch (option.kind) {
    case 'choice': return ['magic', 3, true];
    case 'boolean': return [1, 'true'];
    case 'integer': return [option.min - 1, option.max + 1, 1.5, 1e300, Number.NaN, Infinity, '3'];
    default: {
      const values = [Number.NaN, Infinity, -Infinity, 'x'];
      if (option.min !== null) values.push(option.minOpen ? option.min : option.min - 1);
      if (option.max !== null) values.push(option.maxOpen ? option.max : option.max + 1);
      return values;
    }
  }
}

describe('the options schema', () => {
  it('lists every option once with a valid default, a doc and what it expects', () => {
    expect(new Set(OPTION_NAMES).size).toBe(OPTIONS.length);
    expect(OPTIONS.length).toBeGreaterThanOrEqual(14);
    for (const option of OPTIONS) {
      expect(optionAllows(option, option.default), option.name).toBe(true);
      expect(option.doc.length, option.name).toBeGreaterThan(10);
      expect(option.expects, option.name).toMatch(/^(a |an |one of )/);
      expect(DEFAULT_OPTIONS[option.name]).toEqual(option.default);
    }
    expect(METHODS).toEqual(['subspace', 'full', 'arap']);
    expect(JACOBIANS[0]).toBe(DEFAULT_OPTIONS.jacobian);
    expect(OPTIONS.find((o) => o.name === 'maxIterations').expects).toBe('an integer from 1 to 2147483647');
  });

  it('round-trips every option C++ -> JS -> C++ with its default, and each other value through its member', () => {
    expect(d.options()).toEqual(DEFAULT_OPTIONS); // C++ defaults, as the schema has them
    d.setOptions(d.options()); // JS -> C++: all keys at once
    expect(d.options()).toEqual(DEFAULT_OPTIONS);
    for (const option of OPTIONS) {
      const value = otherValue(option);
      d.setOptions({ [option.name]: value });
      expect(d.options(), option.name).toEqual({ ...DEFAULT_OPTIONS, [option.name]: value });
      d.setOptions({ [option.name]: option.default });
    }
    expect(d.options()).toEqual(DEFAULT_OPTIONS);
  });

  it('refuses values outside the limits or of the wrong type in JS and in C++, with the same message', () => {
    for (const option of OPTIONS) {
      for (const value of badValues(option)) {
        const js = thrown(() => d.setOptions({ [option.name]: value }));
        expect(js, `${option.name} = ${String(value)}`).toBeInstanceOf(InputError);
        expect(js.code).toBe('invalid_argument');
        expect(js.message).toMatch(new RegExp(`^setOptions: ${option.name} must be ${escape(option.expects)} \\(got `));
        // The raw session, past the JS check: the C++ table refuses it with the same text.
        const cpp = thrown(() => d._session.setOptions({ [option.name]: value }));
        expect(cpp.code, `${option.name} = ${String(value)}`).toBe('invalid_argument');
        expect(cpp.message).toBe(js.message);
      }
    }
    expect(thrown(() => d.setOptions({ maxIterations: 2 ** 31 })).message)
      .toBe('setOptions: maxIterations must be an integer from 1 to 2147483647 (got 2147483648)');
    expect(thrown(() => d._session.setOptions({ maxIterations: 1e300 })).message)
      .toBe('setOptions: maxIterations must be an integer from 1 to 2147483647 (got 1e+300)');
    expect(d.options()).toEqual(DEFAULT_OPTIONS); // nothing refused was applied
  });

  it('refuses unknown options on both sides, naming the known ones', () => {
    const js = thrown(() => checkSolverOptions({ maxIters: 3 }, 'setOptions'));
    const cpp = thrown(() => d._session.setOptions({ maxIters: 3 }));
    expect(js.message).toBe(`setOptions: unknown option 'maxIters' (known: ${OPTION_NAMES.join(', ')})`);
    expect(cpp.message).toBe(js.message);
    expect(cpp.code).toBe('invalid_argument');
  });

  it('the scene parser refuses the same values, naming the same limit', () => {
    for (const option of OPTIONS) {
      expect(parseScene({ example: 'bar', handles: [], solver: { [option.name]: option.default } }).solver)
        .toEqual({ [option.name]: option.default });
      for (const value of badValues(option)) {
        const error = thrown(() => parseScene({ example: 'bar', handles: [], solver: { [option.name]: value } }));
        expect(error, `${option.name} = ${String(value)}`).toBeInstanceOf(InputError);
        expect(error.message).toMatch(new RegExp(`^scene: solver\\.${option.name} must be ${escape(option.expects)} \\(got `));
      }
    }
  });
});

function escape(text) {
  return text.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');
}
