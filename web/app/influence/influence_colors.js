// Colours for "what one cage vertex controls": a basis column (the weight of one cage vertex, or one spectral
// column, at every mesh vertex) as vertex colours, and the legend that states the scale.
//   positive weights: pale yellow (0) through orange to dark red (the largest weight shown);
//   negative weights: their own colour, blue from a clearly visible light blue to deep blue (the most negative),
//   so even a weight of -1e-3 reads as negative at a glance. Values within NOISE of the largest weight from
//   zero count as zero (rounding in the solves, e.g. -1e-16 in harmonic coordinates, is not "negative").
// Several views share one scale (compare mode), so equal colours mean equal weights.
import { Color, SRGBColorSpace } from 'three';

export const NOISE = 1e-6;
const POSITIVE_STOPS = ['#fff7d6', '#fdb34b', '#e4491c', '#8b0a26'];
const NEGATIVE_STOPS = ['#9fbfff', '#4f7fe0', '#1a2f9c'];
// Three's colours work in linear space: the stops, written in sRGB, converted once.
const linear = (stops) => stops.map((hex) => new Color().setStyle(hex, SRGBColorSpace));
const POSITIVE = linear(POSITIVE_STOPS);
const NEGATIVE = linear(NEGATIVE_STOPS);

/**
 * The common scale of several columns: the largest weight and the most negative one (0 when none is below
 * -NOISE x the largest).
 * @param {{ min: number, max: number }[]} ranges
 * @returns {{ min: number, max: number }}
 */
export function sharedScale(ranges) {
  const max = Math.max(1e-30, ...ranges.map((r) => r.max));
  const lowest = Math.min(0, ...ranges.map((r) => r.min));
  return { max, min: lowest < -NOISE * max ? lowest : 0 };
}

function ramp(stops, t, out, k) {
  const x = Math.min(1, Math.max(0, t)) * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(x));
  const f = x - i;
  const a = stops[i], b = stops[i + 1];
  out[k] = a.r + (b.r - a.r) * f;
  out[k + 1] = a.g + (b.g - a.g) * f;
  out[k + 2] = a.b + (b.b - a.b) * f;
}

/**
 * RGB per vertex (linear, for MeshStandardMaterial's vertexColors) of the weights on a scale.
 * @param {Float32Array} values one weight per mesh vertex
 * @param {{ min: number, max: number }} scale from sharedScale
 * @returns {{ colors: Float32Array, negative: number }} negative: vertices drawn as negative
 */
export function influenceColors(values, scale) {
  const colors = new Float32Array(3 * values.length);
  const noise = NOISE * scale.max;
  let negative = 0;
  for (let i = 0; i < values.length; ++i) {
    const w = values[i];
    if (w < -noise && scale.min < 0) {
      ramp(NEGATIVE, w / scale.min, colors, 3 * i);
      ++negative;
    } else {
      ramp(POSITIVE, w / scale.max, colors, 3 * i);
    }
  }
  return { colors, negative };
}

/** CSS gradients of the legend's two parts, in the stops' own (sRGB) colours. */
export const LEGEND_GRADIENTS = {
  negative: `linear-gradient(to right, ${[...NEGATIVE_STOPS].reverse().join(', ')})`,
  positive: `linear-gradient(to right, ${POSITIVE_STOPS.join(', ')})`,
};

/** A weight as the legend prints it: 3 significant digits, a real minus sign. */
export function legendNumber(x) {
  if (x === 0) return '0';
  return Number(x.toPrecision(3)).toString().replace('-', '\u2212');
}
