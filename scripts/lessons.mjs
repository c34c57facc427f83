#!/usr/bin/env node
// Writes the app's built-in lessons (web/app/lessons/<id>.json): the report's experiments (figures 3-5 and its
// future work, docs/experiments/README.md) as scene files (docs/scene-format.md) on the models the project
// ships (Spot, the npm bunny, the procedural bar). Handle regions come from geometric queries on the rest mesh
// (scripts/experiments/scenes.mjs), so the files are reproducible; tests/js/lessons.test.js checks that they
// are up to date and that what each caption says holds. Each file: "name" (title), "description" (caption),
// the model, its handles already moved, solver options, and "view" (what the app compares and from where).
//
//   node scripts/lessons.mjs [--check]     --check: exit 1 if a file differs from what would be written
import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Deformer, handleTargets, loadExample, loadSolver, parseSceneHandles } from 'subspace-deform';
import { bounds, point, verticesBelow, verticesNear, SCENES } from './experiments/scenes.mjs';
import { sceneText } from '../web/app/loading/saved_scene.js';
import { STRAINED } from '../web/app/skeleton/skeleton_text.js';

export const LESSONS_DIR = join(dirname(fileURLToPath(import.meta.url)), '..', 'web', 'app', 'lessons');

// Looking at Spot's left side (it faces -z, y up), a little from the front and above.
const SPOT_SIDE = [-1, -0.35, 0.25];

/** Vertices whose coordinate `axis` is at least `threshold`. */
function verticesAbove(positions, axis, threshold) {
  const out = [];
  for (let i = 0; i < positions.length / 3; ++i) if (positions[3 * i + axis] >= threshold) out.push(i);
  return out;
}

/**
 * Solves a lesson's scene (subspace, the app's cap of 100 iterations, and `options`) with its skeleton kept, or without it;
 * either way the skeleton's report after the solve: { joints, bones: [{ lengthError, straightnessError, ... }] }
 * (without: the bones measured on the pose the volume alone gave, by setting them once the solve is done).
 */
export function bonesAfterSolve(solver, model, scene, { keep = true, options = {} } = {}) {
  const d = Deformer.create(solver, model.mesh, model.cage);
  try {
    d.setOptions({ method: 'subspace', maxIterations: 100, ...options });
    const { groups, targets } = handleTargets(model.mesh.positions, parseSceneHandles(scene.handles));
    d.setHandles(groups);
    d.setTargets(targets);
    if (keep) d.setSkeleton(scene.skeleton);
    const result = d.solve();
    if (!keep) d.setSkeleton(scene.skeleton); // reported where the volume alone put them (the next step would restore them)
    return { report: d.skeletonReport(), result };
  } finally {
    d.dispose();
  }
}

/** The largest |length error| (with its sign) and |straightness error| over the bones of a report. */
export function worstBones(report) {
  const worst = (key) => report.bones.reduce((w, b) => (Math.abs(b[key]) > Math.abs(w) ? b[key] : w), 0);
  return { length: worst('lengthError'), straightness: Math.abs(worst('straightnessError')) };
}

const percent = (x) => `${Number((100 * Math.abs(x)).toPrecision(2))}%`;

/**
 * The skeleton lesson's examples of the solver option straightnessWeight (docs/method.md section 5.4): 3, and the
 * panel slider's end (30), where the bones sag by less than the 2% that draws them red.
 */
export const LESSON_STRAIGHTNESS = 3;
export const LESSON_STRAIGHTER = 30;

/** Each lesson: its example, and from the rest positions (and the model, to measure) the scene's other fields. */
export const LESSON_BUILDERS = [
  {
    id: 'subspace-vs-full',
    example: 'spot',
    build(p) {
      const b = bounds(p);
      const hooves = verticesBelow(p, 1, b.lo[1] + 0.05 * b.size[1]);
      const head = verticesNear(p, point(p, b.argLo[2]), 0.08 * b.diagonal);
      return {
        name: 'Subspace against full space (the report\'s figure 3)',
        // It starts paused at rest, so that the caption's "step" is the first thing a student can do (it used to
        // say "pause, then step" while both solves ran to convergence before the caption was read).
        description: 'Spot\'s hooves are fixed and its head is pulled sideways; the lesson starts paused at rest: press ' +
          'step (N) to follow both solves one iteration at a time, or run (S) to let them finish. The subspace solves for ' +
          'the 120 vertices of a cage and converges in about ten iterations; the full space solves for all 2,930 vertices ' +
          'and needs about ten times as many iterations, each far slower. The report found the full space trapped in a bad ' +
          'local minimum; here it is not, and ends at a lower energy (compare the merits).',
        handles: [{ vertices: hooves }, { vertices: head, translate: round([0.3 * b.diagonal, 0.1 * b.diagonal, 0]) }],
        solver: { method: 'subspace', maxIterations: 200 }, // the full space needs more than the app's 100
        view: { compare: ['subspace', 'full'], paused: true },
      };
    },
  },
  {
    id: 'arap-vs-subspace',
    example: 'bar',
    build(p) {
      const scene = SCENES.find((s) => s.id === 'large_rotation_bar').build(p);
      return {
        name: 'ARAP against the subspace on a large rotation (the report\'s figure 4)',
        description: 'The right end of the bar is turned by 120 degrees about its fixed left end. ARAP starts from ' +
          'rotations that are all the identity and never recovers: after hundreds of iterations its bar has thinned, kinks ' +
          'at the fixed end and has lost more than a quarter of its volume. The subspace bends it through the whole turn ' +
          'with the volume exact.',
        handles: scene.handles.map((h) => ({ ...h, ...(h.rotate ? { rotate: { ...h.rotate, center: round(h.rotate.center) } } : {}) })),
        solver: { method: 'subspace' },
        view: { compare: ['arap', 'subspace'] },
      };
    },
  },
  {
    id: 'volume',
    example: 'spot',
    build(p) {
      const b = bounds(p);
      const hooves = verticesBelow(p, 1, b.lo[1] + 0.04 * b.size[1]);
      const meanZ = hooves.reduce((s, v) => s + p[3 * v + 2], 0) / hooves.length;
      const front = hooves.filter((v) => p[3 * v + 2] < meanZ); // Spot faces -z
      const snout = verticesNear(p, point(p, b.argLo[2]), 0.03 * b.diagonal);
      return {
        name: 'Volume kept or lost (the report\'s figure 5)',
        description: 'Spot\'s front hooves are fixed and its snout is pulled up and forward. The subspace keeps the ' +
          'volume exactly; ARAP, which has no volume constraint, gains about 6%. Untick "volume constraint" in the ' +
          'panel\'s Solver folder and the subspace gains half its volume: the hard constraint keeps it, not the energy.',
        handles: [{ vertices: front }, { vertices: snout, translate: round([0, 0.25 * b.diagonal, -0.25 * b.diagonal]) }],
        solver: { method: 'subspace' },
        view: { compare: ['arap', 'subspace'], direction: SPOT_SIDE },
      };
    },
  },
  {
    id: 'spectral',
    example: 'bunny',
    build(p) {
      const b = bounds(p);
      const feet = verticesBelow(p, 1, b.lo[1] + 0.05 * b.size[1]);
      const ears = verticesAbove(p, 1, b.lo[1] + 0.85 * b.size[1]);
      return {
        name: 'The spectral subspace (the report\'s future work)',
        description: 'No cage here: the bunny deforms in the subspace of its own 40 smoothest vibration modes, the ' +
          'lowest eigenvectors of its Laplacian, plus the affine maps: 44 unknowns per coordinate. Its feet are fixed ' +
          'and its ears pulled; the full space beside it solves for all 1,839 vertices.',
        handles: [{ vertices: feet }, { vertices: ears, translate: round([0.25 * b.diagonal, -0.1 * b.diagonal, 0]) }],
        solver: { method: 'subspace' },
        subspace: { basis: 'spectral', modes: 40 },
        view: { compare: ['subspace', 'full'] },
      };
    },
  },
  {
    id: 'volume-parts',
    example: 'spot',
    build(p) {
      const b = bounds(p);
      const body = verticesBelow(p, 1, b.lo[1] + 0.45 * b.size[1]);
      const head = verticesNear(p, point(p, b.argLo[2]), 0.06 * b.diagonal);
      return {
        name: 'Volume per part (the report\'s future work)',
        // The stats give only the volumes kept (one global volume: "1, max 0"), so the head's growth is named as measured.
        description: 'Spot\'s legs and belly are fixed and its head is pulled forward. With one global volume (the panel\'s ' +
          'Volume parts folder) only the total is kept, exactly, while the head grows by about 4% and the body shrinks ' +
          '(measured by the library on these parts; the stats show only the volume kept). Here each of the 6 coloured ' +
          'parts keeps its own volume: the stats give the largest change.',
        handles: [{ vertices: body }, { vertices: head, translate: round([0, 0.04 * b.diagonal, -0.12 * b.diagonal]) }],
        solver: { method: 'subspace' },
        volumeParts: { auto: 6 },
        view: { direction: SPOT_SIDE },
      };
    },
  },
  {
    id: 'skeleton',
    example: 'bar',
    build(p, { solver, model }) {
      // The arm: the bar (length 5 along x) with its left end fixed and its right end folded down by
      // (-1.2, -2.2, 0); joints on its axis at x = -2 (shoulder), 0 (elbow) and 2 (wrist).
      const b = bounds(p);
      const left = verticesBelow(p, 0, b.lo[0] + 0.06 * b.size[0]);
      const right = verticesAbove(p, 0, b.hi[0] - 0.06 * b.size[0]);
      const s = b.size[0] / 5;
      const axis = (x) => round([b.lo[0] + (x + 2.5) * s, (b.lo[1] + b.hi[1]) / 2, (b.lo[2] + b.hi[2]) / 2]);
      const scene = {
        handles: [{ vertices: left }, { vertices: right, translate: round([-1.2 * s, -2.2 * s, 0]) }],
        skeleton: { joints: [axis(-2), axis(0), axis(2)], bones: [[0, 1], [1, 2]] },
      };
      const without = worstBones(bonesAfterSolve(solver, model, scene, { keep: false }).report);
      const kept = worstBones(bonesAfterSolve(solver, model, scene).report);
      const stiffness = (w) => worstBones(bonesAfterSolve(solver, model, scene, { options: { straightnessWeight: w } }).report);
      const [stiff, stiffer] = [stiffness(LESSON_STRAIGHTNESS), stiffness(LESSON_STRAIGHTER)];
      const within = (x) => (x < 1e-9 ? '1e-9' : x.toExponential(0));
      // Only what the app shows: the bones' errors are reported while they are kept (the view's stats), and a bone
      // sagging by more than 2% is drawn red, so the caption says so rather than call red bones a success.
      return {
        name: 'A figure posed by its skeleton (the paper\'s skeleton constraint)',
        description: 'The arm\'s left end is fixed and its hand folded down; without bones (untick "use bones" in the ' +
          `panel's Skeleton folder) its two halves ${without.length < 0 ? 'shorten' : 'stretch'} and sag like cloth, as ` +
          'the sticks carried by the mesh show. With joints at the shoulder, elbow and wrist each bone keeps its length ' +
          `to within ${within(Math.abs(kept.length))} and the arm bends at the elbow, but near the joints its halves ` +
          `still sag by ${percent(kept.straightness)} of their length (the stats' straightness), over the ` +
          `${percent(STRAINED.straightness)} that draws a bone red. "bone straightness" in the Solver folder pulls them ` +
          `straight, for a softer elbow: ${percent(stiff.straightness)} at ${LESSON_STRAIGHTNESS}, ` +
          `${percent(stiffer.straightness)} at ${LESSON_STRAIGHTER}, where they are red no more.`,
        ...scene,
        solver: { method: 'subspace' },
        view: { direction: [-0.15, -0.2, -1] },
      };
    },
  },
];

function round(v) {
  return v.map((x) => Number(x.toPrecision(6)));
}

/** Every lesson's scene file text, by id (the models are loaded once each). */
export async function lessonTexts(solver) {
  const models = new Map();
  const texts = new Map();
  for (const lesson of LESSON_BUILDERS) {
    if (!models.has(lesson.example)) models.set(lesson.example, await loadExample(solver, lesson.example));
    const model = models.get(lesson.example);
    const { name, description, ...fields } = lesson.build(model.mesh.positions, { solver, model });
    texts.set(lesson.id, `${sceneText({ name, description, example: lesson.example, ...fields })}\n`);
  }
  return texts;
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const check = process.argv.includes('--check');
  const texts = await lessonTexts(await loadSolver());
  let stale = 0;
  for (const [id, text] of texts) {
    const file = join(LESSONS_DIR, `${id}.json`);
    let old = null;
    try {
      old = readFileSync(file, 'utf8');
    } catch {
      // a new lesson
    }
    if (old === text) continue;
    if (check) {
      console.error(`lessons: ${file} is not what scripts/lessons.mjs writes`);
      ++stale;
    } else {
      writeFileSync(file, text);
      console.log(`lessons: wrote ${file}`);
    }
  }
  process.exit(stale ? 1 : 0);
}
