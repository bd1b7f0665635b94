// The document, in the worker: the class the worker (service.ts) and the tests hold, the only
// way into the engine from the page — the rest of the worker and the whole main thread see the
// world through its methods (and strokes through `StrokeBody`). Its state is docstate.ts's; each
// method is one line into the file of its job:
//
//   reading.ts     what the page draws and reads (positions, topology, masses and pins, strain)
//   opening.ts     another model: built-in, sketched, imported (importer.ts), a scene
//   projects.ts    project files and the autosave
//   editing.ts     every operation one undo step; undo and redo
//   parameters.ts  parameters, material presets, wind, the time step
//   meshops.ts     Freeze, Reset, Remesh, Subdivide (every body)
//   stroking.ts    the tools' drags (the body under the cursor)
//   stepping.ts    the steps of a tick, and what they met
//
// Body 0 comes first (its parameters and statistics are the panel's), an import's other pieces
// and an open scene's other bodies follow.

import { initEngine } from '../engine/wasm';
import { threadsWanted } from '../engine/threads';
import type { DeltaScope, ParamInfo, ParamValue } from '../engine/world';
import type { ImportAnswer, ImportFrame } from '../io/import';
import type { SceneInfo, Topology, UiState, Vec3 } from '../protocol';
import type { Autosave, AutosaveRecord } from '../storage';
import { DocState, type DocumentHooks } from './docstate';
import { edit, travel } from './editing';
import { Importer } from './importer';
import { freeze, remesh, reset, subdivide } from './meshops';
import { adopt, fresh, loadBuiltin, openScene, restartScene, sketch } from './opening';
import { materialPreset, setDt, setParam, wind } from './parameters';
import { autosaveRecord, open, openProject, openProjectText, projectText } from './projects';
import { bodyData, renderInto, renderLength, sceneInfo, strain, topology } from './reading';
import type { SketchCommand } from './sketch';
import { advance, takeAccuracy } from './stepping';
import { strokeEnd, strokeMove, strokeStart, updateStroke } from './stroking';
import type { StrokeStart } from './strokes';
import type { ParamId } from '../engine/params';

export { HISTORY_BYTES, HISTORY_STEPS, errorText, type DocumentHooks, type SceneSource } from './docstate';
export { HISTORY_KEPT_BYTES } from './projects';
export { REAL_TIME_VERTICES } from './meshops';
export { SPLITS, SPLIT_NOTICE } from './stepping';

/**
 * Load the engine (the wasm module's bytes, or its URL). From a URL, the threaded build beside
 * it (`softsculpt-threads.wasm`) on `threads` threads where memory can be shared (1: never).
 */
export async function loadEngine(source: BufferSource | string, threads = threadsWanted()): Promise<void> {
  const threaded = typeof source === 'string' && threads > 1 ? { url: source.replace(/softsculpt\.wasm$/, 'softsculpt-threads.wasm'), threads } : undefined;
  await initEngine(source, threaded);
}

export class Document extends DocState {
  readonly importer: Importer;

  constructor(hooks: DocumentHooks) {
    super(hooks);
    this.importer = new Importer(this, { message: hooks.message, progress: hooks.progress, ask: (q) => hooks.ask?.(q) });
  }

  // ----- what the page draws and reads (reading.ts) -------------------------------------------

  get vertexCount(): number { return this.world.body(0).vertexCount; }
  /** Floats the frame buffer holds: xyz of every body, the active one first. */
  get renderLength(): number { return renderLength(this); }
  /** Every body's positions (f32) into `out` (renderLength floats); refreshes the stats. */
  renderInto(out: Float32Array): void { renderInto(this, out); }
  get sceneInfo(): SceneInfo | null { return sceneInfo(this); }
  topology(): Topology { return topology(this); }
  bodyData(): { masses: Float64Array; pinned: Uint8Array } { return bodyData(this); }
  /** Each vertex's strain: the mean over its springs of l / L − 1 (> 0 stretched, < 0 compressed). */
  strain(): Float32Array { return strain(this); }
  /** Every parameter of the active body and the world, by the table's ids. */
  params(): Record<string, ParamValue | null> { return this.world.params(0); }
  /** The engine's parameter table (ids, units, ranges, help). */
  paramTable(): ParamInfo[] { return this.world.paramTable(); }

  // ----- another model (opening.ts, importer.ts) ----------------------------------------------

  /** A fresh world: no bodies, no scene, no obstacles, the table's defaults. */
  fresh(): void { fresh(this); }
  /** A model built in the world (an import): its name, the settings from the world's dt, its file's frame. */
  adopt(model: string, frame: ImportFrame): void { adopt(this, model, frame); }
  /** Tell the page new tool state (the brush radius fitted to an imported model). */
  hooksUi(ui: Partial<UiState>): void { this.hooks.ui(ui); }
  /** A built-in model with the default world, settled at rest on the ground. */
  loadBuiltin(name: string, undoable = true): void { loadBuiltin(this, name, undoable); }
  /** Read a model file; the page is asked what the file does not say (`importAnswer`). */
  importFile(name: string, data: ArrayBuffer, remembered?: Record<string, 'y' | 'z'>): void { this.importer.read(name, data, remembered); }
  /** The imported model turned to another up axis (Model › up axis; undoable). */
  setUp(up: 'y' | 'z'): void { this.importer.reorient(up); }
  /** The page's answers for the file waiting (null: cancelled). */
  importAnswer(a: ImportAnswer | null): void { this.importer.answer(a); }
  /** The sketch tool's outline becomes a balloon replacing the model (undoable; a bad outline is one message). */
  sketch(cmd: SketchCommand): void { sketch(this, cmd); }
  /** Open a scene file (with the mesh files it names); undoable. False if it could not be read. */
  openScene(name: string, text: string, files: Map<string, Uint8Array> = new Map()): boolean { return openScene(this, name, text, files); }
  /** Play the open scene again from its start (undoable like opening it). */
  restartScene(): void { restartScene(this); }
  /** The world as scene file text, the shapes as they are now (an open scene's obstacles and events kept). */
  sceneText(): string { return this.world.saveScene(); }

  // ----- project files and the autosave (projects.ts) -----------------------------------------

  /** Open on the autosave if there is one (and it reads), else the default model. */
  open(autosave: Autosave | null): void { open(this, autosave); }
  projectText(): string { return projectText(this); }
  /** The autosave's record of the world as it is now, with the newest undo steps (HISTORY_KEPT_BYTES). */
  autosaveRecord(now: number): AutosaveRecord { return autosaveRecord(this, now); }
  /** Open project text (version 2, or a version-1 file migrated by the engine); throws what is wrong. */
  openProjectText(text: string, undoable = true, label?: string): void { openProjectText(this, text, undoable, label); }
  openProject(name: string, text: string): void { openProject(this, name, text); }

  // ----- editing and undo (editing.ts), parameters (parameters.ts) ----------------------------

  /** Run a modeling operation as one undoable step; reported and undone if it fails. Whether it succeeded. */
  edit(label: string, undoable: boolean, op: () => void, scope: DeltaScope = 'all', failText?: (why: string) => string): boolean {
    return edit(this, label, undoable, op, scope, failText);
  }
  undo(): void { travel(this, 'undo'); }
  redo(): void { travel(this, 'redo'); }
  /** Change a parameter by its table id (undoable); a refused value is reported and leaves the old one. */
  setParam(id: ParamId, value: ParamValue): boolean { return setParam(this, id, value); }
  setMass(total: number): void { setParam(this, 'mass', total); }
  /** A material preset of the core on the active body (undoable), at the model's size. */
  materialPreset(name: string): void { materialPreset(this, name); }
  /** Wind along `direction` at `strength` m/s (0: calm); undoable. */
  wind(direction: Vec3, strength: number): void { wind(this, direction, strength); }
  /** The time step (s), from the panel (not an undo step). */
  setDt(dt: number): void { setDt(this, dt); }

  // ----- modeling operations on every body (meshops.ts) ---------------------------------------

  freeze(): void { freeze(this); }
  reset(): void { reset(this); }
  remesh(): void { remesh(this); }
  subdivide(): void { subdivide(this); }

  // ----- strokes, the tools' drags (stroking.ts) ----------------------------------------------

  strokeStart(s: StrokeStart): void { strokeStart(this, s); }
  strokeMove(point: Vec3 | null, inverted: boolean, pressure?: number): void { strokeMove(this, point, inverted, pressure); }
  strokeEnd(): void { strokeEnd(this); }
  get stroking(): boolean { return this.stroke !== null; }
  /** The stroke acts for `dt` simulated seconds (before the steps of a tick). */
  updateStroke(dt: number): void { updateStroke(this, dt); }

  // ----- stepping (stepping.ts) ---------------------------------------------------------------

  /** `n` steps of `dt` (s) under a wall-clock budget of `seconds` (0: none); false on a stop or an interrupt. */
  advance(dt: number, n: number, seconds = 0): boolean { return advance(this, dt, n, seconds); }
  /** Whether body 0 steps with the implicit integrator. */
  get implicit(): boolean { return this.world.params(0).integrator === 'implicit'; }
  /** The largest residual an implicit step stopped by its deadline was accepted at (0: every step converged); starts again. */
  takeAccuracy(): number { return takeAccuracy(this); }
}
