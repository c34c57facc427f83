// The worker's rule for storing a basis in single precision (web/lib/basis_precision.js).
import { describe, expect, it } from 'vitest';
import { FLOAT32_ABOVE_BYTES, singlePrecisionPays } from 'subspace-deform';

describe('singlePrecisionPays', () => {
  it('stores a basis in float32 only above FLOAT32_ABOVE_BYTES in double', () => {
    expect(FLOAT32_ABOVE_BYTES).toBe(128e6);
    expect(singlePrecisionPays(5042, 28)).toBe(false); // the built-in bar: 1.1 MB
    expect(singlePrecisionPays(160000, 100)).toBe(false); // exactly 128 MB
    expect(singlePrecisionPays(160001, 100)).toBe(true);
    expect(singlePrecisionPays(998562, 42)).toBe(true); // the 1M sphere of scripts/bench/big.mjs: 335 MB
  });
});
