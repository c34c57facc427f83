// "Copy link to this pose" (the panel's Export folder in index.html; issue 31, item 4): the current scene (the
// model as a built-in example or a path from the page, the handle groups with their targets, the solver
// options, the basis, the volume parts) and the view (compared methods, camera direction) in the page's URL as
// ?pose= (loading/pose_link.js), put in the address bar and on the clipboard. Opening the link shows the same
// pose. When no link can carry it (a model opened from a file, or a link longer than MAX_LINK_LENGTH), the
// banner says so and why, and points to "save scene".
import { POSE_PARAM, encodePose } from '../loading/pose_link.js';

/**
 * The longest link made: static hosts refuse longer request lines (nginx and Apache allow about 8 KB), and
 * mail, chat and course platforms shorten or cut long links.
 */
export const MAX_LINK_LENGTH = 8000;

const SAVE_INSTEAD = 'Save the scene instead (panel: Export, "save scene (JSON)"): a scene file holds any pose, and opens by dropping it on the page or with ?scene=URL.';

/** `url` as a path from the folder `base` (a URL ending in /), or null when it is not in that folder or below. */
function pathFrom(base, url) {
  const target = new URL(url);
  if (target.origin !== base.origin || !target.pathname.startsWith(base.pathname) || target.search || target.hash) return null;
  return decodeURIComponent(target.pathname.slice(base.pathname.length));
}

/**
 * The link to the app's current pose from the page at `pageUrl`, or why there is none.
 * @param {import('../deformer_app.js').DeformerApp} app
 * @param {string} [pageUrl]
 * @returns {Promise<{ link: string|null, length: number, reason: string }>}
 */
export async function poseLink(app, pageUrl = location.href) {
  if (!app.model) return { link: null, length: 0, reason: 'no model is loaded yet.' };
  const scene = app.sceneJson();
  const source = app.model.source ?? {};
  if (source.files) {
    const base = new URL('.', pageUrl);
    if (!source.urls) {
      return { link: null, length: 0, reason: `${app.model.name} was opened from this computer, and a link cannot carry a file: only a ` +
        'built-in example or a model the page loads by its URL (?mesh=models/a.obj&cage=models/a_cage.obj, or ?scene=).' };
    }
    const paths = source.urls.map((url) => pathFrom(base, url));
    if (paths.some((p) => p === null)) {
      return { link: null, length: 0, reason: `${app.model.name} is not in this page's folder (${base.href}) or below it, and a ` +
        'link names a model by its path from there.' };
    }
    scene.mesh = paths[0];
    if (paths[1]) scene.cage = paths[1];
  }
  const keys = app.views.map((v) => v.key);
  const direction = app.views[0].viewport.viewDirection().toArray().map((x) => Number(x.toFixed(4)));
  scene.view = { ...(app.compare && !keys.some((k) => k.includes(':')) ? { compare: keys } : {}), direction,
    ...(app.stepping.paused ? { paused: true } : {}) };
  const url = new URL(pageUrl);
  url.search = '';
  url.hash = '';
  url.searchParams.set(POSE_PARAM, await encodePose(scene));
  const length = url.href.length;
  if (length > MAX_LINK_LENGTH) {
    return { link: null, length, reason: `the link would be ${length.toLocaleString('en-US')} characters long, more than the ` +
      `${MAX_LINK_LENGTH.toLocaleString('en-US')} that web servers and mail or chat programs pass on (the handle groups hold ` +
      `${app.handles.groups.reduce((n, g) => n + g.vertices.length, 0).toLocaleString('en-US')} vertices; fewer, or runs of neighbouring vertex numbers, make it shorter).` };
  }
  return { link: url.href, length, reason: '' };
}

/**
 * Makes the link, shows it in the address bar, copies it and says so in the banner; or says in the banner why
 * there is no link. Resolves with poseLink's result and whether the clipboard took it.
 * @param {import('../deformer_app.js').DeformerApp} app
 */
export async function copyPoseLink(app) {
  const result = await poseLink(app);
  if (!result.link) {
    app.banner.show(`No link to this pose: ${result.reason}\n${SAVE_INSTEAD}`, { kind: 'warning' });
    return { ...result, copied: false };
  }
  history.replaceState(history.state, '', result.link);
  const copied = await navigator.clipboard?.writeText(result.link).then(() => true, () => false) ?? false;
  const what = `opening it shows this model with its handle groups where they are now, the solver options and this view (${result.length.toLocaleString('en-US')} characters).`;
  app.banner.show(copied ? `Link copied: ${what}` : `The link is in the address bar (the browser did not allow copying it): ${what}`, { kind: 'info' });
  return { ...result, copied };
}
