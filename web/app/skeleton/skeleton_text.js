// The skeleton's numbers as text, from a solver report ({ joints, bones: [{ lengthError, straightnessError,
// lambda, straightHard }], kept }; errors relative to each bone's rest length): one line for a view's stats (the
// largest errors and multiplier), one line per bone for the step-through's box and the panel's row.

const MAX_TRACE_BONES = 6;

/** Relative errors over which a bone is drawn red (skeleton_view.js); the skeleton lesson's caption quotes them. */
export const STRAINED = { length: 1e-6, straightness: 2e-2 };

/** |x| (or the largest |x_i| of a list: a bone may carry one multiplier per constraint). */
function magnitude(x) {
  if (Array.isArray(x) || ArrayBuffer.isView(x)) return Math.max(0, ...Array.from(x, Math.abs));
  return Math.abs(Number(x) || 0);
}

/** A relative error as people read it: "0" below rounding (1e-15), else 2 significant digits. */
export function errorText(x) {
  const a = Math.abs(x);
  return a < 1e-15 ? '0' : a.toExponential(1);
}

/** A multiplier: 4 significant digits, exponent form outside 1e-3 .. 1e4. */
export function multiplierText(x) {
  if (x === 0) return '0';
  return Math.abs(x) >= 1e-3 && Math.abs(x) < 1e4 ? String(Number(x.toPrecision(4))) : x.toExponential(3);
}

/** The largest errors and multiplier over the bones, and how many are straight only softly. */
export function bonesSummary(report) {
  const bones = report?.bones ?? [];
  return {
    count: bones.length,
    length: Math.max(0, ...bones.map((b) => Math.abs(b.lengthError))),
    straightness: Math.max(0, ...bones.map((b) => Math.abs(b.straightnessError))),
    lambda: Math.max(0, ...bones.map((b) => magnitude(b.lambda))),
    soft: bones.filter((b) => b.straightHard === false).length,
  };
}

/** The view's stats line for the bones, or '' without a report. */
export function skeletonStatsLine(report) {
  const s = bonesSummary(report);
  if (!s.count) return '';
  if (report.kept === false) {
    // ARAP ignores the skeleton: its bones' errors are measured, and no multiplier or softness applies.
    return `bones ${s.count}: not kept by this method   length error ${errorText(s.length)}   straightness ${errorText(s.straightness)}`;
  }
  const soft = s.soft ? `, ${s.soft} straight only softly` : '';
  return `bones ${s.count}: length error ${errorText(s.length)}   straightness ${errorText(s.straightness)}   |\u03bb| ${multiplierText(s.lambda)}${soft}`;
}

/** One line per bone for the step-through's box (its multiplier and errors), at most six, then how many more. */
export function skeletonTraceLines(report) {
  const bones = report?.bones ?? [];
  const lines = bones.slice(0, MAX_TRACE_BONES).map((b, k) => `bone ${k}: multiplier ${Array.isArray(b.lambda) ? b.lambda.map(multiplierText).join(', ')
    : multiplierText(Number(b.lambda) || 0)}   length error ${errorText(b.lengthError)}   straightness ${errorText(b.straightnessError)}` +
    (b.straightHard === false ? ' (soft)' : ''));
  if (bones.length > MAX_TRACE_BONES) lines.push(`... and ${bones.length - MAX_TRACE_BONES} more bones`);
  return lines;
}

/** The panel's row: the largest length and straightness errors, or what to do without bones. */
export function skeletonPanelText(report, { bones, enabled }) {
  if (!bones) return 'none: bone tool (B)';
  const counted = `${bones} bone${bones === 1 ? '' : 's'}`;
  if (!enabled) return `${counted}, not kept`;
  const s = bonesSummary(report);
  return s.count ? `len ${errorText(s.length)} str ${errorText(s.straightness)}` : counted;
}
