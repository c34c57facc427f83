// The influence view's colours (web/app/influence/influence_colors.js): negative weights get their own colour
// (blue) however small, rounding noise does not count as negative, several views share one scale.
import { describe, expect, it } from 'vitest';
import { NOISE, influenceColors, legendNumber, sharedScale } from '../../web/app/influence/influence_colors.js';

const isBlue = (colors, i) => colors[3 * i + 2] > colors[3 * i] + 0.05;

describe('influence colours', () => {
  it('shares one scale between views and ignores rounding noise below zero', () => {
    expect(sharedScale([{ min: -0.01, max: 0.3 }, { min: 0, max: 0.5 }])).toEqual({ min: -0.01, max: 0.5 });
    // -1e-16 next to a largest weight of 0.4 is rounding, not a negative weight.
    expect(sharedScale([{ min: -1e-16, max: 0.4 }])).toEqual({ min: 0, max: 0.4 });
    expect(sharedScale([{ min: -2 * NOISE, max: 1 }]).min).toBe(-2 * NOISE);
  });

  it('draws every negative weight blue and every other one in the warm ramp, darker as it grows', () => {
    const values = new Float32Array([-0.01, -0.0001, 0, 1e-17, 0.1, 0.5]);
    const { colors, negative } = influenceColors(values, sharedScale([{ min: -0.01, max: 0.5 }]));
    expect(negative).toBe(2);
    expect([0, 1, 2, 3, 4, 5].map((i) => isBlue(colors, i))).toEqual([true, true, false, false, false, false]);
    // The most negative is the deepest blue; the largest weight the darkest red.
    expect(colors[0] + colors[1] + colors[2]).toBeLessThan(colors[3] + colors[4] + colors[5]);
    expect(colors[15] + colors[16] + colors[17]).toBeLessThan(colors[12] + colors[13] + colors[14]);
    // Without negative weights on the scale nothing is blue.
    expect(influenceColors(new Float32Array([-1e-9, 0.2]), { min: 0, max: 0.2 }).negative).toBe(0);
  });

  it('prints the scale with real minus signs and three digits', () => {
    expect(legendNumber(-0.0083412)).toBe('\u22120.00834');
    expect(legendNumber(0)).toBe('0');
    expect(legendNumber(0.378)).toBe('0.378');
  });
});
