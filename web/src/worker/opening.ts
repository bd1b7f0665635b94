// Another model in the document: a fresh world, a built-in model settled on the ground, a
// sketched balloon, an import's model adopted (worker/importer.ts builds it), a scene opened or
// played again from its start; each one undo step, and each a new model (docstate.ts `newModel`).

import { addModel, stepsPerFrame, useDefaults } from '../engine/models';
import type { ImportFrame } from '../io/import';
import { MODELS, type ModelName } from '../models';
import type { DocState } from './docstate';
import { edit } from './editing';
import { BRUSH_RADIUS } from './importer';
import { sketchBalloon, sketchOpen, sketchWhy, type SketchCommand } from './sketch';
import { SPLITS } from './stepping';

/** A fresh world: no bodies, no scene, no obstacles, the table's defaults. */
export function fresh(d: DocState): void {
  d.world.clear();
  d.world.restore(d.empty!);
  d.session = null;
  d.settings.frame = null;
  d.newModel();
}

/** A model built in the world (an import): its name, the settings from the world's dt, its file's frame. */
export function adopt(d: DocState, model: string, frame: ImportFrame): void {
  d.splitFrames = 0;
  d.settings.dt = d.world.params(0).dt as number;
  d.settings.substeps = stepsPerFrame(d.settings.dt);
  d.settings.model = model;
  d.settings.frame = frame;
}

/** The modeler's default world on body 0, and the settings that go with it. */
function startDefaults(d: DocState, model: string): void {
  d.changes = [];
  if (d.pausedByError) { d.pausedByError = false; d.settings.playing = true; }
  const dt = useDefaults(d.world, 0);
  d.splitFrames = 0;
  d.settings.dt = dt;
  d.settings.substeps = stepsPerFrame(dt);
  d.settings.model = model;
}

/** A built-in model with the default world, settled at rest on the ground. */
export function loadBuiltin(d: DocState, name: string, undoable = true): void {
  if (!(MODELS as readonly string[]).includes(name)) { d.hooks.message(`there is no built-in model '${name}'`, 'error'); return; }
  edit(d, `load ${name}`, undoable, () => {
    const label = `loading ${name}`;
    d.hooks.progress(label, 0);
    fresh(d);
    addModel(d.world, name as ModelName);
    startDefaults(d, name);
    // Let it settle on the ground (a few simulated seconds) so it opens at rest.
    const dt = d.settings.dt, chunk = Math.max(1, Math.round(0.5 / dt));
    for (let t = 0; t < 6; t += dt * chunk) {
      d.world.advance(dt * chunk, 0, 0, SPLITS, true);
      d.hooks.progress(label, t / 6);
    }
  });
  // The brush an import fitted to its file, still unchanged by the user, is not this model's:
  // the built-ins' radius comes back.
  if (d.fittedRadius !== null && d.ui.brush?.radius === d.fittedRadius) {
    d.ui = { ...d.ui, brush: { radius: BRUSH_RADIUS } };
    d.hooks.ui({ brush: { radius: BRUSH_RADIUS } });
  }
  d.fittedRadius = null;
}

/** The sketch tool's outline becomes a balloon replacing the model (undoable; a bad outline is one message). */
export function sketch(d: DocState, cmd: SketchCommand): void {
  d.hooks.progress('inflating the sketch');
  const ok = edit(d, 'sketch', true, () => {
    const { positions, triangles } = sketchBalloon(cmd);
    fresh(d);
    d.world.addMesh(positions, triangles, 1, false);
    startDefaults(d, 'sketch');
  }, 'all', (why) => `sketch: ${sketchWhy(why)} — the model is unchanged`);
  if (ok) d.hooks.message(`sketched a balloon: ${d.world.body(0).vertexCount} vertices, ${d.world.body(0).faceCount} faces${sketchOpen(cmd.points) ? ' — the outline was open: its ends were joined with a straight line' : ''}`);
}

/** Open a scene file (with the mesh files it names); undoable. False if it could not be read. */
export function openScene(d: DocState, name: string, text: string, files: Map<string, Uint8Array> = new Map()): boolean {
  d.hooks.progress(`opening ${name}`);
  let opened = { names: [] as string[], dt: 0, duration: 0 };
  const ok = edit(d, `open ${name}`, true, () => {
    opened = d.world.openScene(text, files);
    d.session = { name, text, files, duration: opened.duration };
    d.settings.frame = null;
    d.settings.dt = opened.dt;
    d.settings.substeps = stepsPerFrame(opened.dt);
    d.settings.model = name;
    // A scene opens paused at t = 0, so its first events are seen when the user plays it.
    d.newModel();
    d.settings.playing = false;
    d.pausedByError = false;
  }, 'all', (why) => `could not open ${name}: ${why} — the current model is unchanged`);
  if (!ok) return false;
  const n = opened.names.length;
  d.hooks.message(`opened scene ${name}: ${n} ${n === 1 ? 'body' : 'bodies'}, ${opened.duration} s of events — paused at t = 0; Space plays it`);
  return true;
}

/** Play the open scene again from its start (undoable like opening it). */
export function restartScene(d: DocState): void {
  if (!d.session) { d.hooks.message('no scene is open (Files › Open scene…)', 'warn'); return; }
  const s = d.session;
  openScene(d, s.name, s.text, s.files);
}
