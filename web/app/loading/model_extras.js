// What a loaded model brings besides its meshes: a glTF model's file (kept for later bindings and exports) and
// its look (its materials and textures, gltf_look.js), and the notes of its check for the banner; and the
// meshes with that file for binding the model in another worker.
import { isModelName } from '../../lib/formats.js';
import { loadGltfLook } from '../view/gltf_look.js';

/**
 * A glTF model's file: the dropped file of that name and the other dropped files, which it may refer to (its
 * .bin, its textures).
 * @param {string} name
 * @param {{ name: string, bytes: Uint8Array }[]} files
 */
export function gltfFileOf(name, files) {
  const file = files.find((f) => f.name === name);
  if (!file) return undefined;
  const resources = Object.fromEntries(files.filter((f) => !isModelName(f.name)).map((f) => [f.name, f.bytes]));
  return { name, bytes: file.bytes, resources };
}

/**
 * The parsed meshes of a bound model, for binding it in another worker (no cage: the spectral basis's), with a
 * glTF model's file (its export keeps the file's layout and materials).
 */
export function meshesOf(model) {
  const cage = model.cage.positions.length ? model.cage : undefined;
  return { name: model.name, description: model.description, mesh: model.mesh, cage, gltf: model.gltfFile };
}

/** A glTF model's own look; null (drawn plainly, with a console note) when it cannot be loaded. */
export async function gltfLookOf(file, instances) {
  try {
    return await loadGltfLook(file, instances);
  } catch (error) {
    console.warn(`${file.name}: its materials could not be loaded (${error.message}); drawn plainly`);
    return null;
  }
}

/**
 * The model's notes (what loading did to it): a quiet line in the status bar (banner.note), and the banner as
 * well where one is a warning and `inBanner`. Notes alone (seams welded, holes capped, several components) are
 * routine: a banner for them covered a course figure's model on every load.
 * @param {{ show: Function, note?: (text: string, summary?: string) => void }} banner
 * @param {{ name: string, notes?: { severity: string, message: string }[] }} model
 * @param {{ inBanner?: boolean }} [options]
 */
export function showNotes(banner, model, { inBanner = true } = {}) {
  const notes = model.notes ?? [];
  banner.note?.(notes.length ? notesText(model) : '', notes.map((f) => f.message.replace(/^mesh: /, '')).join(' \u00b7 '));
  if (inBanner && notes.some((f) => f.severity === 'warning')) banner.show(notesText(model), { kind: 'info' });
}

/** What loading did to the model, for the banner: the check's notes and warnings, one per line. */
export function notesText(model) {
  return `${model.name}:\n${model.notes.map((f) => `\u2022 ${f.message.replace(/^mesh: /, '')}`).join('\n')}`;
}
