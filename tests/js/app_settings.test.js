// The app's one validation path (web/app/settings.js, page_options.js), without a page: settings from
// setOptions, mount() options, URL parameters and embed attributes are checked by the same tables. An attack
// found `setOptions({ gizmoMode: 'fly' })` emptying the view, `?method=ARAP` blanking the page, `?compare=`
// with 50 entries starting 100 workers, and NaN drag translations stored and saved as null.
import { describe, expect, it } from 'vitest';
import { AppSettings, DEFAULT_SETTINGS, SETTING_NAMES, SOLVER_CONTROLS, checkSettings, settingSchema } from '../../web/app/settings.js';
import { PAGE_TEXT_NAMES, checkPageOptions, kebabName, pageOptionsFromText } from '../../web/app/page_options.js';
import { COMPARE_METHODS, checkCompare, readCompare } from '../../web/app/methods.js';
import { HandleEditor } from '../../web/app/interaction/handle_editor.js';
import { OPTION_NAMES } from '../../web/lib/options.js';
import { EXAMPLE_NAMES } from '../../web/lib/examples.js';
import { InputError } from '../../web/lib/errors.js';
import { thrown } from './support/thrown.js';

const refused = (body) => {
  const error = thrown(body);
  expect(error).toBeInstanceOf(InputError);
  return error.message;
};

describe('the settings schema', () => {
  it('covers every solver option and every app setting, each default allowed by its own schema', () => {
    for (const name of OPTION_NAMES) expect(SETTING_NAMES).toContain(name);
    for (const [name, value] of Object.entries(DEFAULT_SETTINGS)) expect(checkSettings({ [name]: value }, 't')).toEqual({ [name]: value });
    expect(settingSchema('gizmoMode').choices).toEqual(['translate', 'rotate']);
    expect(settingSchema('constructor')).toBeUndefined();
  });

  it('the panel\'s Solver folder is one table: every row a setting with a default, each slider inside its limits, the solver options among them in every saved scene', () => {
    const solverRows = SOLVER_CONTROLS.filter((row) => OPTION_NAMES.includes(row.key) && row.key !== 'method').map((row) => row.key);
    expect(solverRows).toEqual(expect.arrayContaining(['jacobian', 'volume', 'weighting', 'positionWeight', 'c1', 'c2', 'maxIterations']));
    for (const row of SOLVER_CONTROLS) {
      const schema = settingSchema(row.key);
      expect(schema, row.key).toBeDefined();
      expect(row.key in DEFAULT_SETTINGS, row.key).toBe(true);
      if (row.choices) for (const value of Object.values(row.choices)) expect(checkSettings({ [row.key]: value }, 't')).toEqual({ [row.key]: value });
      else if (schema.kind === 'number' || schema.kind === 'integer') {
        for (const end of [row.min, row.max]) expect(checkSettings({ [row.key]: end }, 't'), row.key).toEqual({ [row.key]: end });
      } else expect(row.min ?? row.max, `${row.key}: a slider range on a ${schema.kind}`).toBeUndefined();
    }
    // A menu lists its default first: 'auto' before the counts (integer labels enumerate first in an object).
    const perRequest = SOLVER_CONTROLS.find((row) => row.key === 'iterationsPerFrame').choices;
    expect(Object.values(perRequest)).toEqual(['auto', 1, 2, 3, 5, 10, 20]);
    expect(Object.keys(perRequest).slice(0, 3)).toEqual(['auto (frame budget)', '1 iteration', '2 iterations']);
    // What a saved scene lists: exactly the solver options with a row (maxIterations per method), in the library's order.
    const scene = new AppSettings().toScene('subspace');
    expect(Object.keys(scene)).toEqual(['method', ...OPTION_NAMES.filter((name) => solverRows.includes(name))]);
  });

  it('a lesson starts from the app\'s first solver settings plus its scene\'s own; display and page settings stay', () => {
    // A tester unticked "volume constraint" in the volume lesson: restart and the next lessons kept it unticked,
    // and after subspace-vs-full (maxIterations 200) every lesson kept 200, so their captions no longer held.
    const settings = new AppSettings({ jacobian: 'exact', threads: 2 }); // the page's own settings
    settings.update({ volume: false, maxIterations: 200, arapMaxIterations: 7, method: 'full', cgTolerance: 0.1, wireframe: true, threads: 3 });
    settings.update(settings.lessonStart({ method: 'subspace' }));
    expect(settings.values).toMatchObject({ volume: true, maxIterations: 100, arapMaxIterations: 1000, method: 'subspace', jacobian: 'exact',
      cgTolerance: 0.03, wireframe: true, threads: 3 });
    settings.update(settings.lessonStart({ method: 'subspace', maxIterations: 200 })); // subspace-vs-full
    expect(settings.values.maxIterations).toBe(200);
    settings.update(settings.lessonStart({ method: 'arap', maxIterations: 50 })); // a scene's cap is its method's
    expect(settings.values).toMatchObject({ maxIterations: 100, arapMaxIterations: 50, method: 'arap' });
    expect(settings.lessonStart({}).method).toBe('subspace');
  });

  it('refuses what the attack found accepted, naming the setting and what it expects, and changes nothing', () => {
    const settings = new AppSettings();
    const before = settings.snapshot();
    const cases = [
      [{ gizmoMode: 'fly' }, `setOptions: gizmoMode must be one of 'translate', 'rotate' (got "fly")`],
      [{ iterationsPerFrame: 0 }, `setOptions: iterationsPerFrame must be 'auto' or an integer from 1 to 1000 (got 0)`],
      [{ iterationsPerFrame: -5 }, /iterationsPerFrame must be/],
      [{ iterationsPerFrame: 'x' }, /iterationsPerFrame must be .* \(got "x"\)/],
      [{ brushRadius: -1 }, 'setOptions: brushRadius must be a number above 0 and up to 0.5 (got -1)'],
      [{ showCage: 'no' }, 'setOptions: showCage must be true or false (got "no")'],
      [{ cageVertices: 1e9 }, 'setOptions: cageVertices must be an integer from 20 to 1000 (got 1000000000)'],
      [{ wireframe: true, method: 'ARAP' }, /method must be one of 'subspace', 'full', 'arap' \(got "ARAP"\)/],
      [{ maxIterations: null }, /maxIterations must be/],
      [{ fly: true }, /^setOptions: unknown setting 'fly' \(known: /],
      [{ constructor: 1 }, /unknown setting 'constructor'/],
      [JSON.parse('{"__proto__": {"x": 1}}'), /unknown setting '__proto__'/],
    ];
    for (const [partial, message] of cases) {
      const text = refused(() => settings.update(partial));
      if (typeof message === 'string') expect(text).toBe(message);
      else expect(text).toMatch(message);
    }
    expect(settings.snapshot()).toEqual(before);
    settings.update({ iterationsPerFrame: 3, gizmoMode: 'rotate', brushRadius: 0.5, threads: 'auto' });
    expect(settings.values).toMatchObject({ iterationsPerFrame: 3, gizmoMode: 'rotate', brushRadius: 0.5 });
  });
});

describe('page options: mount(), attributes and URL parameters', () => {
  const fromUrl = (query) => {
    const params = new URLSearchParams(query);
    return checkPageOptions(pageOptionsFromText((name) => params.get(name)));
  };

  it('a bad method, example or setting is dropped and named; the rest of the page goes on', () => {
    for (const query of ['method=ARAP', 'method=arap%20', 'method=nope']) {
      const { settings, problems } = fromUrl(query);
      expect(settings).toEqual({});
      expect(problems).toHaveLength(1);
      expect(problems[0]).toMatch(/^method must be one of 'subspace', 'full', 'arap' \(got "(ARAP|arap |nope)"\): the default is used$/);
    }
    for (const name of ['__proto__', 'constructor', 'toString', 'nope']) {
      const { options, problems } = fromUrl(`example=${name}`);
      expect(options.example).toBeUndefined();
      expect(problems[0]).toMatch(new RegExp(`^example must be a built-in example: ${EXAMPLE_NAMES.join(', ')} \\(got "${name}"\\)`));
    }
    const mixed = fromUrl('example=sphere&method=full&jacobian=exact&maxIterations=200&wireframe&showCage=false&iterationsPerFrame=auto&brushRadius=x');
    expect(mixed.options).toEqual({ example: 'sphere' });
    expect(mixed.settings).toEqual({ method: 'full', jacobian: 'exact', maxIterations: 200, wireframe: true, showCage: false, iterationsPerFrame: 'auto' });
    expect(mixed.problems).toEqual(['brushRadius must be a number above 0 and up to 0.5 (got "x"): the default is used']);
  });

  it('reads attributes by the same tables (an element passes getAttribute)', () => {
    const attributes = new Map([['method', 'nope'], ['compare', ''], ['panel', 'none'], ['help', 'none'], ['maxiterations', '50']]);
    // HTML attribute names are case-insensitive: getAttribute('maxIterations') finds maxiterations.
    const get = (name) => attributes.get(name.toLowerCase()) ?? null;
    const { options, settings, problems } = checkPageOptions(pageOptionsFromText(get));
    expect(options).toEqual({ compare: COMPARE_METHODS, panel: false, help: false });
    expect(settings).toEqual({ maxIterations: 50 });
    expect(problems).toHaveLength(1);
    for (const name of ['example', 'mesh', 'cage', 'scene', 'compare', 'panel', 'help', 'method', 'jacobian']) expect(PAGE_TEXT_NAMES).toContain(name);
  });

  it('mount() options: unknown keys and wrong types are named, not thrown', () => {
    const { options, settings, problems } = checkPageOptions({ exmple: 'bar', panel: 'wide', settings: { gizmoMode: 'fly', wireframe: true }, example: 'bar' });
    expect(options).toEqual({ example: 'bar' });
    expect(settings).toEqual({ wireframe: true });
    expect(problems).toEqual([
      'unknown option "exmple" (known: example, lesson, mesh, cage, scene, compare, panel, panelBeside, help, tools, paused, labels, shareLink, noCage, settings): ignored',
      `panel must be true, false or 'closed' (attribute: open, closed or none) (got "wide"): the default is used`,
      `gizmoMode must be one of 'translate', 'rotate' (got "fly"): the default is used`,
    ]);
    expect(checkPageOptions(undefined).problems).toEqual([]);
  });

  it('noCage: ask, generate or spectral, from mount(), the attribute no-cage (or nocage) and ?noCage=', () => {
    const attributes = new Map([['no-cage', 'spectral']]);
    expect(checkPageOptions(pageOptionsFromText((name) => attributes.get(name.toLowerCase()) ?? attributes.get(kebabName(name)) ?? null)).options)
      .toEqual({ noCage: 'spectral' });
    expect(checkPageOptions(pageOptionsFromText((name) => (name === 'noCage' ? 'generate' : null))).options).toEqual({ noCage: 'generate' });
    expect(checkPageOptions({ noCage: 'never' }).problems).toEqual(["noCage must be one of 'ask', 'generate', 'spectral' (got \"never\"): the default is used"]);
    expect(checkPageOptions('bar').problems).toEqual(['the options must be an object (got "bar"): the defaults are used']);
  });
});

describe('compare lists', () => {
  it('any number of entries gives each method at most once (50 entries once started 100 workers)', () => {
    const fifty = Array.from({ length: 50 }, (_, i) => COMPARE_METHODS[i % 3]).join(',');
    expect(readCompare(fifty)).toEqual({ methods: ['arap', 'subspace', 'full'], unknown: [] });
    expect(readCompare(Array(50).fill('arap'))).toEqual({ methods: ['arap'], unknown: [] });
    expect(readCompare('arap,bogus,toString')).toEqual({ methods: ['arap'], unknown: ['bogus', 'toString'] });
    expect(checkPageOptions({ compare: 'arap,bogus' })).toMatchObject({ options: { compare: ['arap'] },
      problems: ['compare: "bogus" is no method (methods: arap, subspace, full): left out'] });
  });

  it('setCompare (a script) refuses what is no method', () => {
    expect(refused(() => checkCompare(['arap', 'ARAP']))).toBe('setCompare: "ARAP" is no method (methods: subspace, full, arap)');
    expect(checkCompare(false)).toBeNull();
    expect(checkCompare(['full', 'full'])).toEqual(['full']);
  });
});

describe('handle edits from scripts', () => {
  const editor = () => {
    const e = new HandleEditor();
    e.setModel(new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]));
    e.setGroups([[0], [3]]);
    return e;
  };

  it('drag refuses a NaN, a zero axis or a group that does not exist, storing nothing', () => {
    const e = editor();
    const before = JSON.stringify(e.handles.toScene());
    expect(refused(() => e.move(1, [NaN, 0, 0]))).toBe('drag: translation must be an array of 3 finite numbers (got [null,0,0])');
    expect(refused(() => e.move(1, [0, 0, 0], { axis: [0, 0, 0], angle: 1 }))).toBe('drag: rotation.axis must not be zero');
    expect(refused(() => e.move(1, [0, 0, 0], { axis: [0, 0, 1], angle: Infinity }))).toMatch(/angle must be a finite number/);
    expect(refused(() => e.move(2, [1, 0, 0]))).toBe('drag: index must be a handle group from 0 to 1 (got 2)');
    expect(JSON.stringify(e.handles.toScene())).toBe(before);
    e.move(1, [0.5, 0, 0]);
    expect(e.handles.toScene()[1].translate).toEqual([0.5, 0, 0]);
  });

  it('setHandles refuses an out-of-range moving index and sparse groups; setTargets refuses NaN', () => {
    const e = editor();
    expect(refused(() => e.setGroups([[0], [3]], { moving: [5] }))).toBeTruthy();
    expect(refused(() => e.setGroups([[0], [3]], [5]))).toBe('setHandles: moving must list group indices from 0 to 1 (got [5])');
    // eslint-disable-next-line no-sparse-arrays
    expect(refused(() => e.setGroups([[0], , [3]]))).toBe('setHandles: group 1 is missing (a hole in the array)');
    expect(refused(() => e.checkTargets([0, 0, 0, NaN, 0, 0]))).toBe('setTargets: target 1 is not 3 finite numbers (got NaN)');
    expect(e.checkTargets([0, 0, 0, 1, 0, 0])).toEqual(new Float64Array([0, 0, 0, 1, 0, 0]));
  });

  // An attack: drag(1, [1e300, 0, 0]) and setTargets with 1e300 passed the app's checks; only the worker refused them,
  // as a worker error, with the dragged group's translate already stored. They are refused here now, in the words of
  // the library and of scenes (MAX_MESH_COORDINATE, 1e30), before anything changes.
  it('drag and setTargets refuse targets beyond the 1e30 a mesh may have, storing nothing', () => {
    const e = editor();
    const before = JSON.stringify(e.handles.toScene());
    expect(refused(() => e.move(1, [1e300, 0, 0]))).toBe('drag: handle group 1 moves vertex 3 to a coordinate of 1.00e+300, beyond ' +
      'the 1e30 a mesh may have (volumes would overflow): use a smaller translation, or rescale the model');
    expect(refused(() => e.move(1, [0, 0, -2e30], { axis: [0, 0, 1], angle: 1 }))).toMatch(/^drag: handle group 1 moves vertex 3 to a coordinate of 2\.00e\+30, beyond/);
    expect(JSON.stringify(e.handles.toScene())).toBe(before);
    e.move(1, [1e29, 0, 0]); // within the limit
    expect(e.handles.toScene()[1].translate).toEqual([1e29, 0, 0]);
    expect(refused(() => e.checkTargets([0, 0, 0, 1, 1e300, 0]))).toBe('setTargets: target row 1 has a coordinate of 1.00e+300, beyond ' +
      'the 1e30 a mesh may have (volumes would overflow): use a smaller target, or rescale the model');
    expect(e.checkTargets([0, 0, 0, -1e30, 0, 0])).toEqual(new Float64Array([0, 0, 0, -1e30, 0, 0]));
  });

  // A tester opened a lesson and pressed undo: the groups became the model's defaults, never on screen.
  it('a scene with its own model leaves no undo step; one on the current model undoes to the groups before', () => {
    const scene = [{ vertices: [1], moving: false, translate: [0, 0, 0] }, { vertices: [2], moving: true, translate: [0, 1, 0] }];
    const fresh = editor();
    fresh.fromScene(scene, { freshHistory: true });
    expect(fresh.handles.groups.map((g) => g.vertices)).toEqual([[1], [2]]);
    expect(fresh.handles.undo()).toBe(false);
    const onCurrent = editor();
    onCurrent.fromScene(scene);
    expect(onCurrent.handles.undo()).toBe(true);
    expect(onCurrent.handles.groups.map((g) => g.vertices)).toEqual([[0], [3]]);
  });
});
