// The side panel (lil-gui): every tool, parameter and operation, each with a tooltip that names
// its unit and shortcut. Parameter and settings edits are sent to the simulation (validated and
// undoable there); the panel shows the page's mirror of its state and refreshes when it changes.
// The parameters' controls are made from the engine's parameter table when it arrives
// (panel-params.ts).

import GUI, { type Controller, type OptionController } from 'lil-gui';
import type { App } from './app';
import { addParams, decimalsFor, scaleSliders, takeParams } from './panel-params';
import { CUSTOM, MaterialTracker, MODELER } from './panel-material';
import { brushUnit, nice } from './tools/scale';
import type { ParamValue } from './protocol';
import { MODELS, type ModelName } from './models';
import { sig3 } from './format';
import { alongView, viewWindSpeed } from './tools/wind';
import { showSignificantDigits } from './panel-numbers';

export interface PanelActions {
  importFile(): void;
  openProject(): void;
  /** Pick a scene file (.toml) and the mesh files it names. */
  openScene(): void;
}

export function buildPanel(app: App, actions: PanelActions): GUI {
  showSignificantDigits();
  const gui = new GUI({ title: 'SoftSculpt', width: 290 });
  const tip = (c: Controller, text: string) => { c.domElement.title = text; c.domElement.setAttribute('data-tip', text); return c; };
  /** The parameters' values the controllers bind to (table ids). */
  const p: Record<string, ParamValue> = {};
  let paramsBuilt = false;
  const view: Record<string, any> = {
    tool: app.tools.tool.name,
    model: (MODELS as readonly string[]).includes(app.mirror.settings.model) ? app.mirror.settings.model : '',
    pressure: '', volume: '',
    windStrength: 0,
  };

  const tools = gui.addFolder('Tool');
  const toolNames = Object.fromEntries(app.tools.tools.map((t) => [`${t.label} (${t.key.toUpperCase()})`, t.name]));
  tip(tools.add(view, 'tool', toolNames).name('tool').onChange((v: string) => app.tools.select(v)),
    app.tools.tools.map((t) => t.tooltip).join('\n'));
  const radius = tip(tools.add(app.brush, 'radius', 0.02, 2, 0.01).name('brush radius (m)').onFinishChange(() => app.sendUi()),
    'Brush radius in metres ([ and ] keys); its range follows the model\'s size (0.02–2 m on the built-in models)');
  /** The brush's length unit the sliders were made for (tools/scale.ts). */
  let shownUnit = 1;
  const showUnit = () => {
    const u = brushUnit.unit;
    if (u === shownUnit) return;
    shownUnit = u;
    radius.min(nice(0.02 * u)).max(nice(2 * u)).step(nice(0.01 * u)).decimals(decimalsFor(2 * u, nice(0.01 * u)));
    scaleSliders(gui.controllersRecursive(), u); // the gas amount and the contact thickness
    showStrength();
  };
  // The strength slider belongs to the active tool: rebuilt when the tool changes, in the same
  // place (right below the radius: the rows do not move under the mouse).
  let strength: Controller | null = null;
  const showStrength = () => {
    strength?.destroy();
    strength = null;
    const t = app.tools.tool;
    if (!t.strengthInfo) return;
    strength = tip(tools.add(t, 'strength', t.strengthInfo.min, t.strengthInfo.max).decimals(decimalsFor(t.strengthInfo.max)).name(t.strengthInfo.label).onFinishChange(() => app.sendUi()), `${t.label} strength: ${t.strengthInfo.label}`);
    radius.domElement.after(strength.domElement);
  };
  showStrength();
  // Mirror symmetry: strokes also act at the mirror images (X on for a symmetric model).
  const sym = { x: false, y: false, z: false };
  (['x', 'y', 'z'] as const).forEach((a, d) => tip(tools.add(sym, a).name(`mirror ${a.toUpperCase()}`).onChange((v: boolean) => app.setSymmetry(d as 0 | 1 | 2, v)),
    `Mirror symmetry across the ${a.toUpperCase()} plane through the model's centre: every tool acts on the mirror image too`));
  const keysTip = document.createElement('div');
  keysTip.className = 'panel-note';
  keysTip.textContent = '[ ] radius, { } strength; B / Shift+B: set by moving the mouse';
  tools.$children.appendChild(keysTip);

  const model = gui.addFolder('Model');
  const builtIn = tip(model.add(view, 'model', [...MODELS]).name('built-in'), 'Load a built-in model (undoable); choosing the loaded one again starts it over');
  // Every choice loads, the loaded model's too: a fresh start, undoable. lil-gui calls onChange
  // only for another value, and a <select> fires no change for the option already selected, so
  // the list's own change is heard, and its selection is cleared when the user opens it (the
  // name shown is lil-gui's, over the list) and put back when it closes without a choice.
  /** The list's entry for a model that is not built in (`otherModel`), if it has one now. */
  let shownOther: string | null = null;
  const select = (builtIn as OptionController).$select;
  select.addEventListener('mousedown', () => { select.selectedIndex = -1; });
  select.addEventListener('blur', () => builtIn.updateDisplay());
  select.addEventListener('change', () => {
    const name = MODELS[select.selectedIndex] as ModelName | undefined;
    if (name) app.loadBuiltin(name);
  });
  // Material presets, from the core (balloon, jelly, clay, cloth, stiff rubber): when they arrive.
  // The list shows the body's material: the modeler's own, a preset, or custom (panel-material.ts).
  const material = { name: '' };
  const materials = new MaterialTracker();
  let shownModel: string | null = null;
  let materialList: Controller | null = null;
  const showMaterials = () => {
    if (materialList || app.mirror.presets.length === 0) return;
    const names = { 'modeler\'s own': MODELER, ...Object.fromEntries(app.mirror.presets.map((p) => [p.name.replace('_', ' '), p.name])), 'custom (edited)': CUSTOM };
    materialList = tip(model.add(material, 'name', names).name('material').onChange((v: string) => {
      if (v === MODELER || v === CUSTOM) {
        app.message(v === MODELER ? 'the modeler\'s material comes with a newly loaded model; Undo (Ctrl+Z) goes back to it' : 'custom: edit the material in Simulation and Gas');
        refresh();
        return;
      }
      materials.expect(v, app.mirror.history);
      app.send({ type: 'preset', name: v });
    }),
    `The body's material: the modeler's own (what a model is loaded with), a preset, or custom (a parameter edited). A preset (undoable) is the same at any mesh resolution:\n${app.mirror.presets.map((p) => `${p.name.replace('_', ' ')}: ${p.help.replace(/^material: /, '')}`).join('\n')}`);
    // Just below the model list.
    model.$children.insertBefore(materialList.domElement, model.$children.children[1] ?? null);
  };
  tip(model.add({ f: () => app.freeze() }, 'f').name('Freeze (F)'), 'The current shape becomes the rest shape (F)');
  tip(model.add(app.mirror.settings, 'keepTension').name('freeze keeps tension').onChange((v: boolean) => app.setSettings({ keepTension: v })), 'Freeze keeps the skin taut: the gas keeps pressing and the rest lengths are corrected so the shape holds, so a press dents as before the freeze (on coarse meshes; see docs/model.md); off: the skin goes slack');
  tip(model.add({ f: () => app.reset() }, 'f').name('Reset (R)'), 'Back to the last frozen shape (R)');
  tip(model.add({ f: () => app.subdivide() }, 'f').name('Subdivide (U)'), 'Loop subdivision of the current shape; masses and pins carried over; the result is frozen (U)');
  tip(model.add({ f: () => app.remesh() }, 'f').name('Remesh (even triangles)'), 'Isotropic remeshing at the mean edge length (at a shorter one, or keeping sharp edges, if the model is too coarse for it; refused if the shape would still change): long thin triangles make poor springs (an import says when); masses and pins carried over; undoable');
  // (pieces) An imported model's up axis, to fix a wrong guess: re-built from the file, undoable.
  const upAxis = { up: 'y' };
  const upControl = tip(model.add(upAxis, 'up', { 'Y up': 'y', 'Z up (turned upright)': 'z' }).name('up axis')
    .onChange((v: 'y' | 'z') => { if (v !== (app.mirror.settings.frame?.up ?? 'y')) app.setUpAxis(v); }),
  'Which way is up in the imported file (OBJ, PLY, STL guess it from the file; this fixes a wrong guess and is remembered for the format). Built again from the file; undoable');
  tip(model.add({ f: () => app.undo() }, 'f').name('Undo (Ctrl+Z)'), 'Undo the last modeling operation (Ctrl+Z)');
  tip(model.add({ f: () => app.redo() }, 'f').name('Redo (Ctrl+Shift+Z)'), 'Redo (Ctrl+Shift+Z)');

  const files = gui.addFolder('Files');
  tip(files.add({ f: () => actions.importFile() }, 'f').name('Import… (Ctrl+I)'), 'Import OBJ, PLY, STL, glTF/GLB (or drop a file on the page)');
  tip(files.add({ f: () => app.export('obj') }, 'f').name('Export OBJ (E)'), 'Download the current shape as OBJ (E)');
  tip(files.add({ f: () => app.export('stl') }, 'f').name('Export STL'), 'Download the current shape as binary STL');
  tip(files.add({ f: () => app.export('glb') }, 'f').name('Export GLB'), 'Download the current shape as glTF binary');
  // Recording (worker/recorder.ts): the button's label follows the mirror's state.
  const rec = tip(files.add({ f: () => app.record() }, 'f').name('● Record'), 'Record the bodies while the simulation plays (30 frames per simulated second); press again to stop');
  tip(files.add({ f: () => app.exportRecording() }, 'f').name('Export recording (GLB)'), 'Download the recording as GLB morph targets (Blender: shape keys), as `softsculpt run --frames` writes');
  tip(files.add({ f: () => app.saveProject() }, 'f').name('Save project (Ctrl+S)'), 'Download a project file: mesh, rest lengths, masses, pins, every parameter');
  tip(files.add({ f: () => actions.openProject() }, 'f').name('Open project (Ctrl+O)'), 'Open a saved project file');
  tip(files.add({ f: () => actions.openScene() }, 'f').name('Open scene…'),
    'Open a scene file (.toml: bodies, obstacles, timed events; see docs/scenes.md). Select the mesh files it names together with it');
  tip(files.add({ f: () => app.saveScene() }, 'f').name('Save scene'),
    'Download the bodies as a scene file (.toml), their shapes as they are now; an open scene keeps its obstacles and events');

  const sim = gui.addFolder('Simulation');
  const settings = app.mirror.settings;
  tip(sim.add(settings, 'playing').name('play (Space)').onChange((v: boolean) => app.setSettings({ playing: v })), 'Play / pause the simulation (Space)');
  tip(sim.add({ f: () => app.step() }, 'f').name('single step (.)'), 'Advance one frame of steps while paused (.)');
  // Only while a scene is open (before, it showed on a plain model and did nothing).
  const restart = tip(sim.add({ f: () => app.restartScene() }, 'f').name('restart scene'), 'Play the open scene again from its start').hide();
  tip(sim.add(settings, 'dt', 1e-6, 0.02).decimals(5).name('dt (s)').onFinishChange((v: number) => app.setSettings({ dt: v })), 'Time step in seconds: implicit (the default) is stable at 1/60 s; the explicit integrators need small steps (picked when chosen)');
  tip(sim.add(settings, 'realTime').name('real time').onChange((v: boolean) => app.setSettings({ realTime: v })), 'Simulated time follows the clock (steps per frame follow the frame rate); off: a fixed number of steps per frame');
  tip(sim.add(settings, 'substeps', 1, 500, 1).name('steps per frame').onFinishChange((v: number) => app.setSettings({ substeps: v })), 'Steps per frame when not in real time');

  const world = gui.addFolder('Gravity & ground');
  // On/off remembers the last g, so switching gravity back on restores it.
  const g = () => (typeof p.gravity === 'number' ? p.gravity : 0);
  const gravity = { on: true, last: 9.81 };
  tip(world.add(gravity, 'on').name('gravity on').onChange((on: boolean) => {
    if (!on && g() !== 0) gravity.last = g();
    app.setParam('gravity', on ? gravity.last : 0);
  }), 'Gravity on or off (keeps g)');

  const gas = gui.addFolder('Gas');
  tip(gas.add(view, 'pressure').name('P = nRT/V (Pa)').disable(), 'Live gas pressure');
  tip(gas.add(view, 'volume').name('V (m³)').disable(), 'Live volume used by the gas law');

  const wind = gui.addFolder('Wind');
  tip(wind.add(view, 'windStrength', 0, 30, 0.1).decimals(2).name('strength (m/s)').onFinishChange((s: number) => app.setWindStrength(s)),
    'Wind speed; the wind keeps its direction (from calm it blows across the view; the arrow shows it)');
  tip(wind.add({ f: () => app.windAcrossView(view.windStrength || viewWindSpeed(app)) }, 'f').name('blow across the view (W)'),
    'The wind blows across the view, level, from the left of the screen to the right (W): the model leans where you see it; from calm, at a speed whose drag is a fifth of the body\'s weight');
  tip(wind.add({ f: () => app.windFromView(view.windStrength || viewWindSpeed(app, alongView(app.viewport.camera))) }, 'f').name('blow from view'),
    'The wind blows along the view direction, away from you (the model leans away from you); from calm, at a speed whose drag is a fifth of the body\'s weight');
  tip(wind.add({ f: () => { view.windStrength = 0; app.windAcrossView(0); } }, 'f').name('calm (Shift+W)'), 'No wind (Shift+W)');

  const display = gui.addFolder('View');
  tip(display.add(app, 'wireframe').name('springs (wireframe, X)').onChange(() => app.syncScene()), 'Show the springs (X)');
  tip(display.add({ f: () => app.viewport.resetView() }, 'f').name('frame model (V)'), 'Fit the model in the view, horizon level (V)');
  const cam = { mode: app.viewport.rig.mode };
  tip(display.add(cam, 'mode', { 'turntable (level horizon)': 'turntable', 'free trackball': 'trackball' }).name('camera').onChange((m: 'turntable' | 'trackball') => { app.viewport.rig.setMode(m); }),
    'Turntable: drag turns the view about the vertical axis and tilts it, the horizon stays level (Blender, SculptGL). Free trackball: the paper\'s rotation in any direction');
  const strain = { on: false };
  tip(display.add(strain, 'on').name('strain view').onChange((v: boolean) => app.setStrainView(v)),
    'Colour each vertex by its springs\' stretch l/L − 1: blue compressed, white at rest, red stretched (full colour at ±10 %): what would spring back if released');
  if (app.viewport.software) {
    // Without a GPU the drawing shares the CPU with the simulation (viewport.ts, SOFTWARE_PIXELS).
    tip(display.add(app.viewport, 'fullResolution').name('full resolution (no GPU)'),
      'WebGL runs without a GPU here, on the CPU the simulation needs: the view is drawn at a reduced resolution (about 640 × 480 pixels) so that the simulation runs faster. Tick to draw at the screen\'s full resolution');
  }
  tip(display.add({ f: () => app.hud.toggleHelp() }, 'f').name('help (?)'), 'Tools and shortcuts (?)');


  // Rarely used folders start closed, so the panel fits the window.
  for (const f of [sim, world, wind, display]) f.close();

  function refresh(): void {
    if (!paramsBuilt && app.mirror.table.length > 0) {
      takeParams(p, app.mirror.params);
      addParams(app.mirror.table, { sim, world, gas, wind }, p, (id, v) => app.setParam(id, v), tip);
      scaleSliders(gui.controllersRecursive(), shownUnit);
      paramsBuilt = true;
    }
    takeParams(p, app.mirror.params);
    // The material list, once the presets have come (they may come after the parameter table).
    showMaterials();
    // An open surface (cloth-like) has no gas: its controls stay off, the folder says why.
    const closed = app.mirror.closed;
    gas.title(closed ? 'Gas' : 'Gas — off: open surface (cloth-like)');
    for (const c of gas.controllers) if (typeof c.property === 'string' && c.property.startsWith('gas.')) c.enable(closed);
    rec.name(app.mirror.recording ? '■ Stop recording' : '● Record');
    restart.show(app.mirror.scene !== null);
    gravity.on = g() !== 0;
    if (g() !== 0) gravity.last = g();
    if (view.tool !== app.tools.tool.name) showStrength();
    showUnit();
    view.tool = app.tools.tool.name;
    // The material the body has now; a new model (not a scene) starts with the modeler's.
    // (pieces) A load of its own, even of a file of the old one's name (settings.opened).
    if (app.mirror.vertexCount > 0) {
      const loadKey = `${app.mirror.settings.model}#${app.mirror.settings.opened ?? ''}`;
      const fresh = shownModel !== loadKey && app.mirror.scene === null;
      shownModel = loadKey;
      // An opened project names its material (UiState.material): given to the model it brings.
      // (Only a name the list has: a project from a later page may name a preset this one lacks.)
      const ui = fresh ? app.materialFromUi : null;
      const given = ui && [MODELER, CUSTOM, ...app.mirror.presets.map((p) => p.name)].includes(ui) ? ui : null;
      if (fresh) app.materialFromUi = null;
      material.name = materials.name(app.mirror.params, app.mirror.history, fresh, given);
      // The worker keeps the page's state for projects and the autosave: told when the name
      // changes, so a reload is not handed a stale name.
      if (material.name !== app.materialName) { app.materialName = material.name; app.sendUi(); }
    }
    // The list names the model: a built-in, or after the built-ins an entry for an import, a
    // scene or a project (blank before: the list looked broken after an import). Choosing a
    // built-in loads it as always; the entry itself loads nothing.
    const other = otherModel(app);
    if (other !== shownOther) { shownOther = other; builtIn.options(other ? [...MODELS, other] : [...MODELS]); }
    view.model = other ?? app.mirror.settings.model;
    view.windStrength = app.windStrength;
    // (pieces) The up axis: an import's, shown and changeable; off for built-in models and scenes.
    upAxis.up = app.mirror.settings.frame?.up ?? 'y';
    upControl.enable(!!app.mirror.settings.frame);
    [sym.x, sym.y, sym.z] = app.symmetryAxes;
    cam.mode = app.viewport.rig.mode;
    strain.on = app.strainView;
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
  }
  app.onChange(refresh);
  // Live readouts of the frame the HUD shows, with the same digits (updated with the readout).
  const live = gas.controllers.filter((c) => c.property === 'pressure' || c.property === 'volume');
  app.hud.onShow(() => {
    const s = app.mirror.stats;
    // An open surface encloses no volume (its triangles' signed volume means nothing).
    const [pressure, volume] = [sig3(s.pressure), app.mirror.closed ? sig3(s.volume) : '— (open surface)'];
    if (pressure === view.pressure && volume === view.volume) return;
    view.pressure = pressure;
    view.volume = volume;
    for (const c of live) c.updateDisplay();
  });
  return gui;
}

/**
 * The model list's entry for the model when it is not a built-in ("(imported: cube.obj)", a
 * scene's, a sketch's, an opened project's), or null.
 */
export function otherModel(app: Pick<App, 'mirror'>): string | null {
  const m = app.mirror, name = m.settings.model;
  if (m.scene) return `(scene: ${name})`;
  if (m.settings.frame) return `(imported: ${name})`;
  if ((MODELS as readonly string[]).includes(name)) return null;
  return name === 'sketch' ? '(sketched balloon)' : `(opened: ${name})`;
}
