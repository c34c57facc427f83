// The one subspace value (web/lib/subspace.js): every form scenes, Deformer.create and the worker's requests accept,
// every refusal with its code and each boundary's own wording, the defaults, and the words the app and worker show.
import { describe, expect, it } from 'vitest';
import {
  BASES, DEFAULT_SUBSPACE, SUBSPACE_FIELDS, WORDINGS, describeSubspace, isSpectral, normaliseSubspace, parseSubspace,
} from '../../web/lib/subspace.js';
import { BASES as LIBRARY_BASES, InputError } from 'subspace-deform';

const scene = WORDINGS.scene;
const create = WORDINGS.deformerCreate;
const request = WORDINGS.request('loadFiles.subspace');

/** The error parseSubspace throws for `input` (fails the test when it throws none). */
function refusal(input, wording) {
  try {
    parseSubspace(input, wording);
  } catch (error) {
    return error;
  }
  throw new Error(`accepted ${JSON.stringify(input)}`);
}

describe('parseSubspace', () => {
  it('accepts every form, keeping only the fields given', () => {
    const accepted = [
      [undefined, { basis: 'cage' }],
      [null, { basis: 'cage' }],
      [{}, { basis: 'cage' }],
      [{ basis: 'cage' }, { basis: 'cage' }],
      [{ coordinates: 'harmonic' }, { basis: 'cage', coordinates: 'harmonic' }],
      [{ basis: 'cage', coordinates: 'pmvc', pmvcResolution: 16 }, { basis: 'cage', coordinates: 'pmvc', pmvcResolution: 16 }],
      [{ basis: 'cage', coordinates: 'harmonic', harmonicResolution: 0 }, { basis: 'cage', coordinates: 'harmonic', harmonicResolution: 0 }],
      [{ basis: 'cage', coordinates: 'mvc', modes: undefined }, { basis: 'cage', coordinates: 'mvc' }],
      [{ basis: 'spectral', modes: 40 }, { basis: 'spectral', modes: 40 }],
      [{ basis: 'spectral', modes: 2147483647 }, { basis: 'spectral', modes: 2147483647 }],
    ];
    for (const [input, value] of accepted) {
      expect(parseSubspace(input, scene)).toEqual(value);
      expect(parseSubspace(input, create)).toEqual(value);
    }
    // A request names its basis; with one, the same values.
    expect(parseSubspace({ basis: 'cage', coordinates: 'pmvc' }, request)).toEqual({ basis: 'cage', coordinates: 'pmvc' });
    expect(parseSubspace({ basis: 'spectral', modes: 3 }, request)).toEqual({ basis: 'spectral', modes: 3 });
    // The value returned is a new object: the default is never handed out to be changed.
    const absent = parseSubspace(undefined);
    absent.coordinates = 'pmvc';
    expect(DEFAULT_SUBSPACE).toEqual({ basis: 'cage' });
  });

  it('refuses in one order, each boundary in its own words, always an InputError with code invalid_argument', () => {
    // [input, scene's message, Deformer.create's message, a request's message]
    const refused = [
      [[1], 'scene: "subspace" must be { "basis": "cage" } or { "basis": "spectral", "modes": k }',
        'Deformer.create: options must be an object', 'loadFiles.subspace must be an object'],
      ['spectral', 'scene: "subspace" must be { "basis": "cage" } or { "basis": "spectral", "modes": k }',
        'Deformer.create: options must be an object', 'loadFiles.subspace must be an object'],
      [{ basis: 'wavelets', modes: 3 }, 'scene: subspace.basis must be "cage" or "spectral" (got "wavelets")',
        'Deformer.create: basis must be \'cage\' or \'spectral\' (got "wavelets")', 'loadFiles.subspace.basis must be \'cage\', \'spectral\' (got "wavelets")'],
      [{ basis: null }, 'scene: subspace.basis must be "cage" or "spectral" (got null)',
        'Deformer.create: basis must be \'cage\' or \'spectral\' (got null)', 'loadFiles.subspace.basis must be \'cage\', \'spectral\' (got null)'],
      [{ basis: 'spectral' }, 'scene: subspace.modes must be an integer >= 1 (got undefined)',
        'Deformer.create: the spectral basis needs modes, an integer >= 1 (got undefined)',
        'loadFiles.subspace.modes must be an integer from 1 to 2147483647 (got undefined)'],
      [{ basis: 'spectral', modes: 0 }, 'scene: subspace.modes must be an integer >= 1 (got 0)',
        'Deformer.create: the spectral basis needs modes, an integer >= 1 (got 0)',
        'loadFiles.subspace.modes must be an integer from 1 to 2147483647 (got 0)'],
      [{ basis: 'spectral', modes: 2.5 }, /modes must be an integer >= 1 \(got 2.5\)/, /needs modes, an integer >= 1 \(got 2.5\)/, /from 1 to 2147483647 \(got 2.5\)/],
      [{ basis: 'spectral', modes: 2147483648 }, /got 2147483648/, /got 2147483648/, /got 2147483648/],
      [{ basis: 'spectral', modes: '8' }, /got "8"/, /got "8"/, /got "8"/],
      [{ basis: 'cage', coordinates: 'green' }, /^scene: subspace: coordinates must be one of 'mvc', 'pmvc', 'harmonic'/,
        /^Deformer.create: coordinates must be one of/, /^loadFiles.subspace: coordinates must be one of/],
      [{ basis: 'cage', coordinates: 'pmvc', harmonicResolution: 16 }, "scene: subspace: harmonicResolution is for coordinates 'harmonic' (the coordinates are 'pmvc')",
        "Deformer.create: harmonicResolution is for coordinates 'harmonic' (the coordinates are 'pmvc')",
        "loadFiles.subspace: harmonicResolution is for coordinates 'harmonic' (the coordinates are 'pmvc')"],
      [{ basis: 'cage', coordinates: 'pmvc', pmvcResolution: 1 }, /pmvcResolution must be an integer from 2 to 1024 \(got 1\)/,
        /pmvcResolution must be an integer from 2 to 1024/, /pmvcResolution must be an integer from 2 to 1024/],
      [{ basis: 'cage', modes: 3 }, 'scene: subspace.modes is for the "spectral" basis', "Deformer.create: modes is for the 'spectral' basis",
        "loadFiles.subspace.modes is for the 'spectral' basis"],
      [{ basis: 'cage', modes: null }, 'scene: subspace.modes is for the "spectral" basis', "Deformer.create: modes is for the 'spectral' basis",
        "loadFiles.subspace.modes is for the 'spectral' basis"],
      [{ basis: 'spectral', modes: 8, coordinates: 'harmonic' },
        'scene: subspace.coordinates are for the "cage" basis (the spectral basis has no cage)',
        "Deformer.create: coordinates are for the 'cage' basis (the spectral basis has no cage)",
        "loadFiles.subspace.coordinates are for the 'cage' basis (the spectral basis has no cage)"],
      // A resolution without its type is checked before the basis: the coordinates are the default's (mean value).
      [{ basis: 'spectral', modes: 8, pmvcResolution: 16 }, /pmvcResolution is for coordinates 'pmvc'/, /pmvcResolution is for coordinates 'pmvc'/,
        /pmvcResolution is for coordinates 'pmvc'/],
    ];
    for (const [input, ...messages] of refused) {
      [scene, create, request].forEach((wording, k) => {
        const error = refusal(input, wording);
        expect(error).toBeInstanceOf(InputError);
        expect(error.code).toBe('invalid_argument');
        if (typeof messages[k] === 'string') expect(error.message).toBe(messages[k]);
        else expect(error.message).toMatch(messages[k]);
      });
    }
  });

  it('refuses an unknown field in scenes and requests (Deformer.create takes its fields out of its options)', () => {
    expect(refusal({ basis: 'cage', kind: 'cage' }, scene).message)
      .toBe(`scene: subspace has unknown field "kind" (known: ${SUBSPACE_FIELDS.join(', ')})`);
    expect(refusal({ basis: 'cage', float32: true }, request).message).toBe('loadFiles.subspace: unknown field "float32"');
    expect(parseSubspace({ basis: 'cage', float32: true }, create)).toEqual({ basis: 'cage' });
  });

  it('takes a missing basis as the cage\'s, except in a request, which names it', () => {
    expect(parseSubspace({ coordinates: 'pmvc' }, scene)).toEqual({ basis: 'cage', coordinates: 'pmvc' });
    expect(refusal({ coordinates: 'pmvc' }, request).message).toBe("loadFiles.subspace.basis must be 'cage', 'spectral' (got undefined)");
    expect(refusal({ modes: 4 }, create).message).toBe("Deformer.create: modes is for the 'spectral' basis");
  });

  it('uses the bases the library exports', () => {
    expect(BASES).toEqual(['cage', 'spectral']);
    expect(LIBRARY_BASES).toBe(BASES);
  });
});

describe('isSpectral', () => {
  it('reads the basis of a subspace or of anything that names one', () => {
    expect(isSpectral({ basis: 'spectral', modes: 4 })).toBe(true);
    expect(isSpectral({ basis: 'spectral', basisSize: 44, name: 'bar' })).toBe(true); // a worker Model
    expect(isSpectral({ basis: 'cage' })).toBe(false);
    expect(isSpectral({})).toBe(false);
    expect(isSpectral(null)).toBe(false);
    expect(isSpectral(undefined)).toBe(false);
  });
});

describe('normaliseSubspace', () => {
  it('writes out the defaults: mean value coordinates, and each type\'s resolution', () => {
    expect(normaliseSubspace()).toEqual({ basis: 'cage', coordinates: 'mvc' });
    expect(normaliseSubspace(null)).toEqual({ basis: 'cage', coordinates: 'mvc' });
    expect(normaliseSubspace({ basis: 'cage' })).toEqual({ basis: 'cage', coordinates: 'mvc' });
    expect(normaliseSubspace({ basis: 'cage', coordinates: 'pmvc' })).toEqual({ basis: 'cage', coordinates: 'pmvc', pmvcResolution: 32 });
    expect(normaliseSubspace({ basis: 'cage', coordinates: 'pmvc', pmvcResolution: 8 }))
      .toEqual({ basis: 'cage', coordinates: 'pmvc', pmvcResolution: 8 });
    expect(normaliseSubspace({ basis: 'cage', coordinates: 'harmonic' })).toEqual({ basis: 'cage', coordinates: 'harmonic', harmonicResolution: 0 });
    expect(normaliseSubspace({ basis: 'cage', coordinates: 'harmonic', harmonicResolution: 16 }))
      .toEqual({ basis: 'cage', coordinates: 'harmonic', harmonicResolution: 16 });
    expect(normaliseSubspace({ basis: 'spectral', modes: 12 })).toEqual({ basis: 'spectral', modes: 12 });
  });

  it('gives a value parseSubspace accepts as it is', () => {
    for (const s of [undefined, { basis: 'cage', coordinates: 'pmvc' }, { basis: 'cage', coordinates: 'harmonic' }, { basis: 'spectral', modes: 5 }]) {
      const normal = normaliseSubspace(s);
      expect(parseSubspace(normal, WORDINGS.request('at'))).toEqual(normal);
    }
  });
});

describe('describeSubspace', () => {
  it('says what a subspace binds, as the app and the worker show it', () => {
    expect(describeSubspace({ basis: 'spectral', modes: 40 })).toBe('the spectral basis (40 modes)');
    expect(describeSubspace({ basis: 'spectral', modes: 40 }, { modes: false })).toBe('the spectral basis');
    expect(describeSubspace(undefined)).toBe('mean value coordinates');
    expect(describeSubspace({ basis: 'cage' })).toBe('mean value coordinates');
    expect(describeSubspace({ basis: 'cage', coordinates: 'pmvc', pmvcResolution: 8 })).toBe('positive mean value coordinates');
    expect(describeSubspace({ basis: 'cage', coordinates: 'harmonic' }, { modes: false })).toBe('harmonic coordinates');
  });
});
