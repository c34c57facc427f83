// What the banner offers after a load that needs the user's choice, each a banner with the action that retries:
// a lone mesh without a cage (Generate cage, or deform it with the spectral basis), spectral modes over the
// memory budget (retry with fewer), a cage that controls its mesh poorly (Generate cage). The actions load
// through the callbacks they are given (ModelLoader's), each a new request of the user's.
import { CAGE_VERTICES_RANGE, SPECTRAL_MODES_RANGE } from '../settings.js';
import { notesText } from './model_extras.js';

/**
 * The "has no cage" banner with a cage-size field and a "Generate cage" button, and beside it deforming the mesh
 * at once with the spectral basis (no cage needed), with a modes field (no_cage.js loads the choice).
 * @param {{ banner: object, settings: import('../settings.js').AppSettings }} ui
 * @param {string} message what happened, first in the banner (its last line: `kept`, whether a model stays)
 * @param {(choice: 'generate'|'spectral', sizes: { vertices?: number, modes?: number }) => Promise<unknown>} choose
 *   loads the kept file again that way
 */
export function offerCage({ banner, settings }, message, kept, choose) {
  // A choice to make, not an error: styled as information.
  banner.show(`${message}\n${kept}`, {
    kind: 'info',
    actions: [{
      label: 'Generate cage',
      input: { label: 'cage vertices', value: settings.values.cageVertices, ...CAGE_VERTICES_RANGE },
      run: (vertices) => choose('generate', { vertices }).catch(() => {}),
    }, {
      label: 'Deform without a cage (spectral basis)',
      input: { label: 'modes', value: settings.values.spectralModes, ...SPECTRAL_MODES_RANGE },
      run: (modes) => choose('spectral', { modes }).catch(() => {}),
    }],
  });
}

/**
 * The spectral basis' modes did not fit the memory budget: the banner offers the same load with fewer (half,
 * editable), and the setting drops to that, so that loading the file again does not ask for the refused count.
 * @param {(modes: number) => Promise<unknown>} retry
 */
export function offerFewerModes({ banner, settings }, error, modes, kept, retry) {
  const fewer = Math.max(SPECTRAL_MODES_RANGE.min, Math.floor(modes / 2));
  settings.update({ spectralModes: fewer });
  banner.show(`${error.message}\n${kept}`, {
    actions: [{
      label: 'Retry with fewer modes',
      input: { label: 'modes', value: fewer, min: SPECTRAL_MODES_RANGE.min, max: modes - 1 },
      run: (k) => {
        settings.update({ basis: 'spectral', spectralModes: k });
        retry(k).catch(() => {});
      },
    }],
  });
}

/**
 * A cage that controls its mesh poorly (docs/cage.md, cage quality): say why, and offer a generated one.
 * @param {(vertices: number) => Promise<unknown>} generateCage
 */
export function warnPoorCage({ banner, settings }, model, generateCage) {
  const reasons = model.cageQuality.warnings.map((w, k) => `\u2022 ${w} (${model.cageQuality.warningCodes[k]})`).join('\n');
  const notes = model.notes?.length ? `\n\n${notesText(model)}` : '';
  banner.show(`The cage of ${model.name} looks poor:\n${reasons}\nA generated cage fits the mesh closely.${notes}`, {
    kind: 'warning',
    actions: [{
      label: 'Generate cage',
      input: { label: 'cage vertices', value: settings.values.cageVertices, ...CAGE_VERTICES_RANGE },
      run: (vertices) => {
        settings.update({ cageVertices: vertices });
        generateCage(vertices).catch(() => {});
      },
    }],
  });
}
