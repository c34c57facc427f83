// Checks of the parts of a glTF document beyond its geometry (gltf_check.js checks buffers, accessors, meshes
// and nodes): every reference between materials, textures, images, samplers, cameras, skins and animations
// points at something, cameras have their projection, and no key is one of Object.prototype's. glTF-Transform
// reads these without checking, so a broken one surfaced as its own TypeError ("Cannot read properties of
// undefined (reading 'yfov')") or was dropped silently; here it is an InputError naming the object.

const isIndex = (value, length) => Number.isInteger(value) && value >= 0 && value < length;

/**
 * @param {any} json a document that passed checkGltfShape
 * @param {(message: string) => never} fail
 */
export function checkGltfReferences(json, fail) {
  checkKeys(json, fail);
  const count = (key) => json[key]?.length ?? 0;
  const ref = (where, value, key) => {
    if (value !== undefined && !isIndex(value, count(key))) fail(`${where} refers to ${key.slice(0, -1)} ${JSON.stringify(value)}, which does not exist`);
  };
  (json.nodes ?? []).forEach((node, i) => {
    ref(`node ${i}`, node.camera, 'cameras');
    ref(`node ${i}`, node.skin, 'skins');
  });
  (json.meshes ?? []).forEach((mesh, m) => mesh.primitives.forEach((primitive, p) => {
    const where = `mesh ${m} primitive ${p}`;
    ref(where, primitive.material, 'materials');
    if (primitive.targets !== undefined && !(Array.isArray(primitive.targets) && primitive.targets.every((t) => t && typeof t === 'object' &&
      Object.values(t).every((a) => isIndex(a, count('accessors')))))) {
      fail(`${where} has morph targets that are not objects of accessor indices`);
    }
  }));
  (json.materials ?? []).forEach((material, i) => forEachTexture(material, (info, name) => ref(`material ${i}: ${name}`, info.index, 'textures')));
  (json.textures ?? []).forEach((texture, i) => {
    ref(`texture ${i}`, texture.source, 'images');
    ref(`texture ${i}`, texture.sampler, 'samplers');
  });
  (json.skins ?? []).forEach((skin, i) => {
    ref(`skin ${i}`, skin.inverseBindMatrices, 'accessors');
    ref(`skin ${i}`, skin.skeleton, 'nodes');
    if (!Array.isArray(skin.joints) || skin.joints.length === 0) fail(`skin ${i} has no joints`);
    skin.joints.forEach((joint) => ref(`skin ${i}: a joint`, joint, 'nodes'));
  });
  (json.cameras ?? []).forEach((camera, i) => checkCamera(camera, i, fail));
  (json.animations ?? []).forEach((animation, i) => checkAnimation(animation, i, count, ref, fail));
}

// Every own key of the document outside extras (user data, copied as it is) that names a member of
// Object.prototype: glTF-Transform keeps attributes and extensions in plain objects, where "constructor" or
// "__proto__" finds the prototype's ("prevRef.dispose is not a function"). Walked iteratively.
function checkKeys(json, fail) {
  const stack = [[json, '']];
  while (stack.length) {
    const [value, path] = stack.pop();
    for (const key of Object.keys(value)) {
      if (key === 'extras') continue;
      if (key === '__proto__' || key in Object.prototype) fail(`${path || 'the document'} has the key "${key}", which this reader cannot keep`);
      const child = value[key];
      if (child && typeof child === 'object') stack.push([child, `${path}${Array.isArray(value) ? `[${key}]` : `${path ? '.' : ''}${key}`}`]);
    }
  }
}

// Calls visit(info, name) for each texture reference of a material: the core ones and those of extensions
// (KHR_materials_*: every object under a key ending in "Texture").
function forEachTexture(material, visit) {
  const stack = [[material, '']];
  while (stack.length) {
    const [value, name] = stack.pop();
    if (/Texture$/.test(name) && value.index !== undefined) visit(value, name);
    for (const [key, child] of Object.entries(value)) if (key !== 'extras' && child && typeof child === 'object') stack.push([child, key]);
  }
}

function checkCamera(camera, i, fail) {
  const positive = (v) => typeof v === 'number' && v > 0 && Number.isFinite(v);
  if (camera.type === 'perspective') {
    const p = camera.perspective;
    if (!p || typeof p !== 'object' || !positive(p.yfov) || !positive(p.znear)) {
      fail(`camera ${i} is perspective but has no "perspective" with a positive yfov and znear`);
    }
  } else if (camera.type === 'orthographic') {
    const o = camera.orthographic;
    if (!o || typeof o !== 'object' || ![o.xmag, o.ymag, o.znear, o.zfar].every((v) => typeof v === 'number' && Number.isFinite(v))) {
      fail(`camera ${i} is orthographic but has no "orthographic" with numbers xmag, ymag, znear and zfar`);
    }
  } else {
    fail(`camera ${i} has type ${JSON.stringify(camera.type)} (perspective or orthographic)`);
  }
}

function checkAnimation(animation, i, count, ref, fail) {
  const { channels, samplers } = animation;
  if (!Array.isArray(channels) || !Array.isArray(samplers)) fail(`animation ${i} needs arrays of channels and samplers`);
  samplers.forEach((sampler, s) => {
    if (!sampler || typeof sampler !== 'object') fail(`animation ${i} sampler ${s} is not an object`);
    if (!isIndex(sampler.input, count('accessors')) || !isIndex(sampler.output, count('accessors'))) {
      fail(`animation ${i} sampler ${s} needs input and output accessors that exist`);
    }
  });
  channels.forEach((channel, c) => {
    const where = `animation ${i} channel ${c}`;
    if (!channel || typeof channel !== 'object' || !channel.target || typeof channel.target !== 'object' || typeof channel.target.path !== 'string') {
      fail(`${where} has no target with a path`);
    }
    if (!isIndex(channel.sampler, samplers.length)) fail(`${where} refers to sampler ${JSON.stringify(channel.sampler)}, which its animation does not have`);
    ref(where, channel.target.node, 'nodes');
  });
}
