// @ts-check
// Checks of the parts of a glTF document beyond its geometry (gltf_check.js checks buffers, accessors, meshes
// and nodes): every reference between materials, textures, images, samplers, cameras, skins and animations
// points at something, cameras have their projection, and no key is one of Object.prototype's. glTF-Transform
// reads these without checking, so a broken one surfaced as its own TypeError ("Cannot read properties of
// undefined (reading 'yfov')") or was dropped silently; here it is an InputError naming the object.

/** @typedef {import('./gltf_check.js').Fail} Fail */
/** @typedef {(key: string) => number} Count  the length of a top-level list (0 when absent) */
/** @typedef {(where: string, value: unknown, key: string) => void} Ref  fails unless value is absent or an index into json[key] */

/** @type {(value: any, length: number) => boolean} */
const isIndex = (value, length) => Number.isInteger(value) && value >= 0 && value < length;

/**
 * @param {any} json a document that passed checkGltfShape
 * @param {Fail} fail
 */
export function checkGltfReferences(json, fail) {
  checkKeys(json, fail);
  /** @type {Count} */
  const count = (key) => json[key]?.length ?? 0;
  /** @type {Ref} */
  const ref = (where, value, key) => {
    if (value !== undefined && !isIndex(value, count(key))) fail(`${where} refers to ${key.slice(0, -1)} ${JSON.stringify(value)}, which does not exist`);
  };
  (json.nodes ?? []).forEach((/** @type {any} */ node, /** @type {number} */ i) => {
    ref(`node ${i}`, node.camera, 'cameras');
    ref(`node ${i}`, node.skin, 'skins');
  });
  (json.meshes ?? []).forEach((/** @type {any} */ mesh, /** @type {number} */ m) => mesh.primitives.forEach((/** @type {any} */ primitive, /** @type {number} */ p) => {
    const where = `mesh ${m} primitive ${p}`;
    ref(where, primitive.material, 'materials');
    if (primitive.targets !== undefined && !(Array.isArray(primitive.targets) && primitive.targets.every((/** @type {any} */ t) => t && typeof t === 'object' &&
      Object.values(t).every((a) => isIndex(a, count('accessors')))))) {
      fail(`${where} has morph targets that are not objects of accessor indices`);
    }
  }));
  (json.materials ?? []).forEach((/** @type {any} */ material, /** @type {number} */ i) => forEachTexture(material, (info, name) => ref(`material ${i}: ${name}`, info.index, 'textures')));
  (json.textures ?? []).forEach((/** @type {any} */ texture, /** @type {number} */ i) => {
    ref(`texture ${i}`, texture.source, 'images');
    ref(`texture ${i}`, texture.sampler, 'samplers');
  });
  (json.skins ?? []).forEach((/** @type {any} */ skin, /** @type {number} */ i) => {
    ref(`skin ${i}`, skin.inverseBindMatrices, 'accessors');
    ref(`skin ${i}`, skin.skeleton, 'nodes');
    if (!Array.isArray(skin.joints) || skin.joints.length === 0) fail(`skin ${i} has no joints`);
    skin.joints.forEach((/** @type {unknown} */ joint) => ref(`skin ${i}: a joint`, joint, 'nodes'));
  });
  (json.cameras ?? []).forEach((/** @type {any} */ camera, /** @type {number} */ i) => checkCamera(camera, i, fail));
  (json.animations ?? []).forEach((/** @type {any} */ animation, /** @type {number} */ i) => checkAnimation(animation, i, count, ref, fail));
}

/**
 * Every own key of the document outside extras (user data, copied as it is) that names a member of
 * Object.prototype: glTF-Transform keeps attributes and extensions in plain objects, where "constructor" or
 * "__proto__" finds the prototype's ("prevRef.dispose is not a function"). Walked iteratively.
 * @param {any} json
 * @param {Fail} fail
 */
function checkKeys(json, fail) {
  /** @type {[any, string][]} */
  const stack = [[json, '']];
  while (stack.length) {
    const [value, path] = /** @type {[any, string]} */ (stack.pop());
    for (const key of Object.keys(value)) {
      if (key === 'extras') continue;
      if (key === '__proto__' || key in Object.prototype) fail(`${path || 'the document'} has the key "${key}", which this reader cannot keep`);
      const child = value[key];
      if (child && typeof child === 'object') stack.push([child, `${path}${Array.isArray(value) ? `[${key}]` : `${path ? '.' : ''}${key}`}`]);
    }
  }
}

/**
 * Calls visit(info, name) for each texture reference of a material: the core ones and those of extensions
 * (KHR_materials_*: every object under a key ending in "Texture").
 * @param {any} material
 * @param {(info: any, name: string) => void} visit
 */
function forEachTexture(material, visit) {
  /** @type {[any, string][]} */
  const stack = [[material, '']];
  while (stack.length) {
    const [value, name] = /** @type {[any, string]} */ (stack.pop());
    if (/Texture$/.test(name) && value.index !== undefined) visit(value, name);
    for (const [key, child] of Object.entries(value)) if (key !== 'extras' && child && typeof child === 'object') stack.push([child, key]);
  }
}

/**
 * @param {any} camera
 * @param {number} i
 * @param {Fail} fail
 */
function checkCamera(camera, i, fail) {
  /** @type {(v: unknown) => boolean} */
  const positive = (v) => typeof v === 'number' && v > 0 && Number.isFinite(v);
  if (camera.type === 'perspective') {
    const p = camera.perspective;
    if (!p || typeof p !== 'object' || !positive(p.yfov) || !positive(p.znear)) {
      fail(`camera ${i} is perspective but has no "perspective" with a positive yfov and znear`);
    }
  } else if (camera.type === 'orthographic') {
    const o = camera.orthographic;
    if (!o || typeof o !== 'object' || ![o.xmag, o.ymag, o.znear, o.zfar].every((/** @type {unknown} */ v) => typeof v === 'number' && Number.isFinite(v))) {
      fail(`camera ${i} is orthographic but has no "orthographic" with numbers xmag, ymag, znear and zfar`);
    }
  } else {
    fail(`camera ${i} has type ${JSON.stringify(camera.type)} (perspective or orthographic)`);
  }
}

/**
 * @param {any} animation
 * @param {number} i
 * @param {Count} count
 * @param {Ref} ref
 * @param {Fail} fail
 */
function checkAnimation(animation, i, count, ref, fail) {
  const { channels, samplers } = animation;
  if (!Array.isArray(channels) || !Array.isArray(samplers)) fail(`animation ${i} needs arrays of channels and samplers`);
  samplers.forEach((/** @type {any} */ sampler, /** @type {number} */ s) => {
    if (!sampler || typeof sampler !== 'object') fail(`animation ${i} sampler ${s} is not an object`);
    if (!isIndex(sampler.input, count('accessors')) || !isIndex(sampler.output, count('accessors'))) {
      fail(`animation ${i} sampler ${s} needs input and output accessors that exist`);
    }
  });
  channels.forEach((/** @type {any} */ channel, /** @type {number} */ c) => {
    const where = `animation ${i} channel ${c}`;
    if (!channel || typeof channel !== 'object' || !channel.target || typeof channel.target !== 'object' || typeof channel.target.path !== 'string') {
      fail(`${where} has no target with a path`);
    }
    if (!isIndex(channel.sampler, samplers.length)) fail(`${where} refers to sampler ${JSON.stringify(channel.sampler)}, which its animation does not have`);
    ref(where, channel.target.node, 'nodes');
  });
}
