// The document, in the worker: one engine world (engine/world.ts) — body 0 first (its parameters
// and statistics are the panel's), an import's other pieces and an open scene's other bodies
// follow; a stroke acts on the body it started on, Freeze, Reset, Subdivide and Remesh on every
// body — the settings it runs with, undo/redo, and every modeling operation. This is the only module of the page that calls the engine: the rest of
// the worker and the whole main thread see the world through the methods below (and strokes
// through `StrokeBody`).
//
// Undo keeps deltas (the engine's `mark` before an operation, `delta` after it): a brush stroke
// keeps what it painted and the state of those vertices ('touched'), a drag or any other
// operation the whole state ('all'; a topology change keeps the whole earlier world). Entries
// are limited to HISTORY_STEPS and HISTORY_BYTES in all, the oldest dropped first.

import { initEngine } from '../engine/wasm';
import { threadsWanted } from '../engine/threads';
import { World, type Advance, type DeltaScope, type FreezeReport, type ParamInfo, type ParamValue, type RemeshReport } from '../engine/world';
import { sig3 } from '../format';
import { addModel, dtFor, stepsPerFrame, useDefaults } from '../engine/models';
import { History, travel } from '../history';
import { parse, ProjectError, serialize } from '../project';
import type { Autosave, AutosaveRecord } from '../storage';
import { MODELS, type ModelName } from '../models';
import { isClosed, sizeFactor, type ImportAnswer, type ImportFrame, type ImportQuestion } from '../io/import';
import { Importer } from './importer';
import type { MessageKind, SceneInfo, Settings, Stats, Topology, UiState, Vec3 } from '../protocol';
import { makeStroke, type Stroke, type StrokeBody, type StrokeStart } from './strokes';
import { explainStop, type Change, type Imported } from './explain';
import { sketchBalloon, sketchOpen, sketchWhy, type SketchCommand } from './sketch';

export const HISTORY_STEPS = 200;
export const HISTORY_BYTES = 512 * 1024 * 1024;
/** Undo steps kept across a reload: the newest that fit in this many bytes (the autosave is written after every operation). */
export const HISTORY_KEPT_BYTES = 48 * 1024 * 1024;
/** The volume change (relative) up to which a subdivision says it kept the shape. */
const SUBDIVIDE_KEPT = 0.02;
/** Frames with split steps before the modeler says so (once per model). */
export const SPLIT_NOTICE = 10;
/**
 * Halvings of a step the implicit solver refuses before the refusal stands (dt/8): the core's
 * `world::SPLITS`, which `World::advance` takes (`crates/softsculpt/src/world/advance.rs`).
 */
export const SPLITS = 3;

/** What a scene was opened from, to restart it (and to bring it back on undo). */
export interface SceneSource { name: string; text: string; files: Map<string, Uint8Array>; duration: number }

/** One undo step: the engine delta, and the page's settings and open scene before it. */
interface Entry { delta: Uint8Array; settings: Settings; scene: SceneSource | null }

/** What the document tells its owner (worker/service.ts turns these into replies). */
export interface DocumentHooks {
  message(text: string, kind?: MessageKind): void;
  /** A long operation is under way (fraction done if known), or ended (null). */
  progress(label: string | null, fraction?: number): void;
  /** The model changed by an operation (the owner autosaves). */
  changed(): void;
  /** An opened project brought the page's state. */
  ui(ui: Partial<UiState>): void;
  /** An imported file needs the user's answers (up axis, pieces): `importAnswer` brings them. */
  ask?(q: ImportQuestion): void;
}

/**
 * Load the engine (the wasm module's bytes, or its URL). From a URL, the threaded build beside
 * it (`softsculpt-threads.wasm`) on `threads` threads where memory can be shared (1: never).
 */
export async function loadEngine(source: BufferSource | string, threads = threadsWanted()): Promise<void> {
  const threaded = typeof source === 'string' && threads > 1 ? { url: source.replace(/softsculpt\.wasm$/, 'softsculpt-threads.wasm'), threads } : undefined;
  await initEngine(source, threaded);
}

/** Implicit steps per 1/60 s frame past which a smaller dt is said to run in slow motion: each is
 * a Newton solve, where the modeler's default (dt = 1/60 s) takes one a frame. */
const SLOW_IMPLICIT_STEPS = 4;

/**
 * Vertices up to which the modeler's steps converge in real time on a machine like this one
 * (BENCHMARKS.md, "Every frame on time": the mushroom subdivided once, 1,442 vertices, runs in
 * real time; twice, 5,762, at a quarter of it while grabbed): past it Subdivide says what to expect.
 */
export const REAL_TIME_VERTICES = 1_500;

export class Document {
  private w: World | null = null;
  /** An empty world's snapshot: what a new model starts from (no obstacles, default settings). */
  private empty: Uint8Array | null = null;
  /** The empty world's snapshot (a scratch world for an import's trial, `trial.ts`). */
  get emptyWorld(): Uint8Array { return this.empty!; }
  /** The open scene, if any (its first body is the active body). */
  private session: SceneSource | null = null;
  readonly history = new History<Entry>({ limit: HISTORY_STEPS, maxBytes: HISTORY_BYTES, size: (e) => e.delta.byteLength });
  readonly settings: Settings = { dt: 1e-3, substeps: 16, realTime: true, playing: true, keepTension: false, model: 'mushroom', frame: null };
  ui: UiState = { brush: { radius: 0.35 }, tool: 'grab', strengths: {} };
  private stroke: Stroke | null = null;
  /** The body the stroke acts on (the one under the cursor when it began). */
  private strokeOn = 0;
  private strokeScope: DeltaScope = 'all';
  /** The world's call count when it was last synced. */
  private syncedAt = -1;
  /** Bumped when the meshes change shape (body replaced, subdivided, scene opened or closed). */
  topologyVersion = 0;
  /** Bumped when masses or pins may have changed. */
  bodyVersion = 0;
  /** Scratch of `strain()`, kept across frames (one per mesh size). */
  private strainSum = new Float64Array(0);
  private strainCount = new Uint32Array(0);
  /** The simulation paused itself on a failure (a new model plays again). */
  pausedByError = false;
  /** Parameters the user changed on this model, with the simulated time (to name a failure's likely cause). */
  private changes: Change[] = [];
  /** Part of the body was below the ground when it was last switched on. */
  private groundUnderBody = false;

  readonly importer: Importer;

  constructor(private readonly hooks: DocumentHooks) {
    this.importer = new Importer(this, { message: hooks.message, progress: hooks.progress, ask: (q) => hooks.ask?.(q) });
  }

  get loaded(): boolean { return this.w !== null && this.w.bodyCount > 0; }
  /** The engine world (for tests and the service; operations go through the methods below). */
  get world(): World {
    if (!this.w) {
      this.w = World.create();
      this.empty = this.w.snapshot();
    }
    return this.w;
  }

  // ----- what the page draws and reads ----------------------------------------------------------

  get vertexCount(): number { return this.world.body(0).vertexCount; }
  /** Floats the frame buffer holds: xyz of every body, the active one first. */
  get renderLength(): number {
    let n = 0;
    for (let i = 0; i < this.world.bodyCount; i++) n += 3 * this.world.body(i).vertexCount;
    return n;
  }
  /** Every body's positions (f32) into `out` (renderLength floats); refreshes the stats. */
  renderInto(out: Float32Array): void {
    const w = this.world;
    this.synced();
    let at = 0;
    for (let i = 0; i < w.bodyCount; i++) {
      const r = w.body(i).render;
      out.set(r, at);
      at += r.length;
    }
  }
  /** The active body's statistics now. */
  stats(): Stats {
    this.synced();
    return this.world.body(0).stats;
  }
  /** Render positions, pins and stats up to date (synced unless nothing was called since). */
  private synced(): void {
    if (this.syncedAt === this.world.epoch) return;
    this.world.sync();
    this.syncedAt = this.world.epoch;
  }
  get sceneInfo(): SceneInfo | null {
    if (!this.session) return null;
    return { name: this.session.name, time: this.stats().time, duration: this.session.duration, bodies: this.world.bodyCount };
  }
  topology(): Topology {
    const w = this.world, b = w.body(0);
    const others = [];
    for (let i = 1; i < w.bodyCount; i++) others.push({ vertexCount: w.body(i).vertexCount, triangles: w.body(i).triangles.slice() });
    const triangles = b.triangles.slice();
    return { vertexCount: b.vertexCount, triangles, springs: b.springs.slice(), others, obstacles: w.obstacles(), closed: isClosed(triangles) };
  }
  bodyData(): { masses: Float64Array; pinned: Uint8Array } {
    this.synced();
    const b = this.world.body(0);
    return { masses: b.masses.slice(), pinned: b.pinned.slice() };
  }
  /**
   * Each vertex's strain: the mean over its springs of l / L − 1 (l the current length, L the
   * rest length; > 0 stretched, < 0 compressed), what would spring back if released.
   */
  strain(): Float32Array {
    const b = this.world.body(0), x = b.positions, e = b.springs, rest = b.rest;
    const n = b.vertexCount;
    if (this.strainSum.length !== n) { this.strainSum = new Float64Array(n); this.strainCount = new Uint32Array(n); }
    const sum = this.strainSum.fill(0), count = this.strainCount.fill(0);
    for (let k = 0; k < rest.length; k++) {
      const i = 3 * e[2 * k], j = 3 * e[2 * k + 1];
      const l = Math.hypot(x[i] - x[j], x[i + 1] - x[j + 1], x[i + 2] - x[j + 2]);
      const s = rest[k] > 0 ? l / rest[k] - 1 : 0;
      sum[e[2 * k]] += s; count[e[2 * k]]++;
      sum[e[2 * k + 1]] += s; count[e[2 * k + 1]]++;
    }
    const out = new Float32Array(n);
    for (let i = 0; i < n; i++) out[i] = count[i] ? sum[i] / count[i] : 0;
    return out;
  }

  /** Every parameter of the active body and the world, by the table's ids. */
  params(): Record<string, ParamValue | null> { return this.world.params(0); }
  /** The engine's parameter table (ids, units, ranges, help). */
  paramTable(): ParamInfo[] { return this.world.paramTable(); }

  // ----- opening --------------------------------------------------------------------------------

  /** Open on the autosave if there is one (and it reads), else the default model. */
  open(autosave: Autosave | null): void {
    if (autosave) {
      try {
        if ('record' in autosave) this.openRecordOrThrow(autosave.record, false);
        else this.openProjectText(autosave.legacyText, false);
        const kept = 'record' in autosave ? this.takeHistory(autosave.record.history) : 0;
        // The same model as before the reload: its load serial too, so undoing into the kept
        // history does not look like another model to the page (which would frame it anew).
        const opened = 'record' in autosave ? (autosave.record.ui as { opened?: unknown }).opened : undefined;
        if (typeof opened === 'number' && Number.isFinite(opened)) this.settings.opened = opened;
        this.hooks.message(`restored your last session (autosaved)${kept > 0 ? `, with ${kept} undo ${kept === 1 ? 'step' : 'steps'}` : ''}`);
        return;
      } catch (e) {
        this.hooks.message(`the autosave could not be read (${errorText(e)}); opened the default model instead`, 'warn');
      }
    }
    this.loadBuiltin('mushroom', false);
  }

  /** A fresh world: no bodies, no scene, no obstacles, the table's defaults. */
  fresh(): void {
    this.world.clear();
    this.world.restore(this.empty!);
    this.session = null;
    this.settings.frame = null;
    this.newModel();
  }

  /**
   * Another model (loaded, imported, sketched, opened): a new `opened` serial (the page frames
   * the view on it even when the file has the old one's name), and nothing of the old model's
   * run carries over: no paused-by-error state, no remembered changes, no rewind points.
   */
  private newModel(): void {
    this.settings.opened = Math.max((this.settings.opened ?? 0) + 1, Date.now());
    this.changes = [];
    this.imported = undefined;
    this.groundUnderBody = false;
    this.relaxedSteps = 0;
    if (this.pausedByError) { this.pausedByError = false; this.settings.playing = true; }
  }

  /** A model built in the world (an import): its name, the settings from the world's dt, its file's frame. */
  adopt(model: string, frame: ImportFrame): void {
    this.splitFrames = 0;
    this.settings.dt = this.world.params(0).dt as number;
    this.settings.substeps = stepsPerFrame(this.settings.dt);
    this.settings.model = model;
    this.settings.frame = frame;
  }

  /** Tell the page new tool state (the brush radius fitted to an imported model). */
  hooksUi(ui: Partial<UiState>): void { this.hooks.ui(ui); }

  private useDefaults(model: string): void {
    this.changes = [];
    if (this.pausedByError) { this.pausedByError = false; this.settings.playing = true; }
    const dt = useDefaults(this.world, 0);
    this.splitFrames = 0;
    this.settings.dt = dt;
    this.settings.substeps = stepsPerFrame(dt);
    this.settings.model = model;
  }

  /** A built-in model with the default world, settled at rest on the ground. */
  loadBuiltin(name: string, undoable = true): void {
    if (!(MODELS as readonly string[]).includes(name)) { this.hooks.message(`there is no built-in model '${name}'`, 'error'); return; }
    this.edit(`load ${name}`, undoable, () => {
      const label = `loading ${name}`;
      this.hooks.progress(label, 0);
      this.fresh();
      addModel(this.world, name as ModelName);
      this.useDefaults(name);
      // Let it settle on the ground (a few simulated seconds) so it opens at rest.
      const dt = this.settings.dt, chunk = Math.max(1, Math.round(0.5 / dt));
      for (let t = 0; t < 6; t += dt * chunk) {
        this.world.advance(dt * chunk, 0, 0, SPLITS, true);
        this.hooks.progress(label, t / 6);
      }
    });
  }

  /** Read a model file; the page is asked what the file does not say (`importAnswer`). */
  importFile(name: string, data: ArrayBuffer, remembered?: Record<string, 'y' | 'z'>): void { this.importer.read(name, data, remembered); }
  /** The imported model turned to another up axis (Model › up axis; undoable). */
  setUp(up: 'y' | 'z'): void { this.importer.reorient(up); }
  /** The page's answers for the file waiting (null: cancelled). */
  importAnswer(a: ImportAnswer | null): void { this.importer.answer(a); }

  /** The sketch tool's outline becomes a balloon replacing the model (undoable; a bad outline is one message). */
  sketch(cmd: SketchCommand): void {
    this.hooks.progress('inflating the sketch');
    const ok = this.edit('sketch', true, () => {
      const { positions, triangles } = sketchBalloon(cmd);
      this.fresh();
      this.world.addMesh(positions, triangles, 1, false);
      this.useDefaults('sketch');
    }, 'all', (why) => `sketch: ${sketchWhy(why)} — the model is unchanged`);
    if (ok) this.hooks.message(`sketched a balloon: ${this.world.body(0).vertexCount} vertices, ${this.world.body(0).faceCount} faces${sketchOpen(cmd.points) ? ' — the outline was open: its ends were joined with a straight line' : ''}`);
  }

  // ----- editing and undo -----------------------------------------------------------------------

  /**
   * Run a modeling operation as one undoable step (a delta of `scope` against the world before
   * it). If it fails, it is reported and the world goes back to how it was. Returns whether it
   * succeeded.
   */
  edit(label: string, undoable: boolean, op: () => void, scope: DeltaScope = 'all', failText?: (why: string) => string): boolean {
    if (this.stroke) this.strokeEnd();
    const w = this.world;
    const settings = { ...this.settings }, scene = this.session;
    const hadModel = w.bodyCount > 0;
    w.mark();
    try {
      op();
    } catch (e) {
      Object.assign(this.settings, settings);
      this.session = scene;
      // Back to the mark: the same meshes, masses and pins as the page has.
      try { w.applyDelta(w.delta('all')); } catch { /* the engine left it as it was */ }
      const why = errorText(e);
      this.hooks.message(failText ? failText(why) : `${label}: ${why}${hadModel ? ' — the model is as it was before' : ''}`, 'error');
      return false;
    } finally {
      this.hooks.progress(null);
    }
    if (undoable && hadModel) this.history.push(label, { delta: w.delta(scope), settings, scene });
    this.touched();
    this.hooks.changed();
    return true;
  }

  /** Anything may have changed: send topology, masses and pins again. */
  private touched(): void {
    this.topologyVersion++;
    this.bodyVersion++;
    this.world.forgetRewind();
  }

  /** Change a parameter by its table id (undoable); a refused value is reported and leaves the old one. */
  setParam(id: import('../engine/params').ParamId, value: ParamValue): boolean {
    if (id === 'ground' && value === true) this.groundUnderBody = this.belowGround();
    // The ground's height moves the plane with what stands on it (the core's `move_ground`): a
    // rooted mushroom rises with it instead of being buried at its pinned foot (a new-user
    // trial: at 0.5 m the step failed). Undo takes the whole world back ('whole'): a delta of
    // what the move changed holds only the y coordinates, and applied after the body has moved
    // on it would mix old heights with new x and z.
    const ok = id === 'ground.height' && typeof value === 'number'
      ? this.edit(`set ${id}`, true, () => this.world.moveGround(value), 'whole')
      : this.edit(`set ${id}`, true, () => this.world.setParam(0, id, value), 'none');
    if (ok) this.changes = [...this.changes.slice(-7), { id, value, time: this.stats().time }];
    if (ok && id === 'dt') {
      this.settings.dt = value as number;
      this.sayIfSlow();
    }
    // Another integrator gets a step it is stable at: 1/60 s implicit, else the explicit limit.
    if (ok && id === 'integrator') {
      this.setDt(dtFor(this.world, value as string));
      this.settings.substeps = stepsPerFrame(this.settings.dt);
      this.hooks.message(`${value}: dt = ${fmt(this.settings.dt)} s`);
    }
    // After a stop, another integrator or dt is the remedy the stop's message names: play again
    // (if it was not, the next step stops and says so again). A new-user trial switched back to
    // implicit after an explicit blow-up and found the page still paused, its grab doing nothing.
    if (ok && this.pausedByError && (id === 'integrator' || id === 'dt')) {
      this.pausedByError = false;
      this.settings.playing = true;
      this.hooks.message(`playing again with ${id === 'dt' ? `dt = ${fmt(this.settings.dt)} s` : `the ${value} integrator`}`);
    }
    return ok;
  }

  setMass(total: number): void { this.setParam('mass', total); }

  /**
   * A material preset of the core on the active body (undoable), at the model's size: an
   * imported model keeps its units, so the preset is scaled by the core's similarity rules
   * (params/similarity.rs) as the modeler preset was on import.
   */
  materialPreset(name: string): void {
    const size = this.settings.frame ? sizeFactor(Array.from({ length: this.world.bodyCount }, (_, i) => this.world.body(i).positions)) : 1;
    // A new material changes how the body responds, not its shape at once. Under gravity the
    // shape as it is becomes the rest shape first, carrying its weight (freeze under load), so a
    // softer or plastic material (clay) does not slump from where it stands; the gas keeps the
    // pressure difference P − P_ref it had (a frozen body's springs balance that), so a preset
    // with less gas does not crush a frozen body. P_ref ≥ 0: with no gas (cloth) it is 0.
    // Except a closed body that the preset leaves without gas (cloth on the mushroom): its
    // weight carried by the freeze held it exactly where it stood, an unstable equilibrium of a
    // gasless shell, so it did not move until touched and then collapsed at once (a new-user
    // trial: 3 s at speed 0, then a small grab took its volume from 2.45 to 1.11 m³). It is
    // frozen plainly instead (the weight no longer carried), so it sags and drapes at once, as
    // the message says. Undo takes the whole world back to before the preset ('whole'), the
    // shape as it stood included: undoing cloth after it folded brought the gas back into the
    // folded shell, which then would not step (a new-user trial: "waiting for a step").
    if (this.edit(`material ${name}`, true, () => {
      const gravity = this.world.params(0).gravity !== 0;
      if (gravity) this.world.freeze(0, true, false);
      const before = this.stats().pressure - (this.world.params(0)['gas.ambient'] as number);
      this.world.applyPresetScaled(0, name, size);
      if (gravity && this.world.params(0)['gas.amount'] === 0 && isClosed(this.world.body(0).triangles)) this.world.freeze(0, false, false);
      this.world.setParam(0, 'gas.ambient', Math.max(0, this.stats().pressure - before));
    }, 'whole')) {
      const gasless = this.world.params(0)['gas.amount'] === 0;
      this.hooks.message(`material: ${name.replace('_', ' ')}${gasless ? ' — no gas: a closed body sags under its weight (it suits open surfaces)' : ''}`);
    }
  }

  /** Whether some vertex of the active body is below the ground's height. */
  private belowGround(): boolean {
    const h = this.world.params(0)['ground.height'];
    const x = this.world.body(0).positions;
    if (typeof h !== 'number') return false;
    for (let i = 1; i < x.length; i += 3) if (x[i] < h - 1e-9) return true;
    return false;
  }

  /** Wind along `direction` at `strength` m/s (0: calm); undoable. */
  wind(direction: Vec3, strength: number): void {
    this.setParam('wind', [direction[0] * strength, direction[1] * strength, direction[2] * strength]);
  }

  /** The time step (s), from the panel (not an undo step). */
  setDt(dt: number): void {
    try {
      this.world.setParam(0, 'dt', dt);
      this.settings.dt = dt;
      this.sayIfSlow();
    } catch (e) {
      this.hooks.message(errorText(e), 'error');
    }
  }

  /**
   * An implicit dt below 1/60 s buys no stability (backward Euler is stable at 1/60 s) and costs
   * a solve per step: say what to expect (a new-user trial ran dt = 1e-6 s at 0.4 % of real
   * time, 16,667 steps a frame, with no word).
   */
  private sayIfSlow(): void {
    const dt = this.settings.dt, n = stepsPerFrame(dt);
    if (n > SLOW_IMPLICIT_STEPS && String(this.world.params(0).integrator) === 'implicit') {
      this.hooks.message(`dt = ${Number(dt.toPrecision(3))} s is ${n.toLocaleString('en-US')} implicit steps for each 1/60 s frame, so expect slow motion; the implicit integrator is stable at dt = 1/60 s`, 'warn');
    }
  }

  private apply(entry: Entry): Entry {
    const w = this.world;
    const now: Entry = { delta: new Uint8Array(0), settings: { ...this.settings }, scene: this.session };
    now.delta = w.applyDelta(entry.delta);
    if (entry.scene !== this.session) this.rejoinScene(entry.scene);
    Object.assign(this.settings, entry.settings);
    this.touched();
    return now;
  }

  /**
   * Undo or redo crossed a scene's opening: the world is back, but the engine's record of the
   * scene (names, obstacles and events as written, for saving) is the other one. Re-open the
   * scene (or forget it) and put the world back into it.
   */
  private rejoinScene(scene: SceneSource | null): void {
    const w = this.world, snap = w.snapshot();
    if (scene) w.openScene(scene.text, scene.files); else w.clear();
    w.restore(snap);
    this.session = scene;
  }

  undo(): void { this.travel('undo'); }
  redo(): void { this.travel('redo'); }

  private travel(dir: 'undo' | 'redo'): void {
    if (this.stroke) return;
    try {
      const item = travel(this.history, dir, (e) => this.apply(e));
      if (!item) { this.hooks.message(`nothing to ${dir}`); return; }
      this.hooks.message(`${dir === 'undo' ? 'undid' : 'redid'} ${item.label}`);
    } catch (e) {
      this.hooks.message(`${dir} failed: ${errorText(e)}`, 'error');
    }
    this.hooks.changed();
  }

  // ----- modeling operations --------------------------------------------------------------------

  /** Every body's index: Freeze, Reset, Subdivide and Remesh act on all of them (see `freeze`). */
  private get everyBody(): number[] { return Array.from({ length: this.world.bodyCount }, (_, i) => i); }

  /**
   * Freeze: under gravity the body keeps carrying its weight (no sag); keeping the tension (an
   * option, off by default: see docs/model.md, "Freeze") the gas keeps pressing and the rest
   * lengths are corrected so this shape holds, taut as it is now; otherwise the skin goes slack
   * (P_ref := P).
   *
   * Freeze, Reset, Subdivide and Remesh act on every body (an import's pieces, a scene's
   * bodies), not the one under the cursor: they are panel buttons and keys with no point on the
   * model, and a multi-piece import is, as Blender selects every object a file brings in, one
   * model whose pieces the user shapes together (Blender's Apply, Subdivide and Remesh act on
   * every selected object). The tools act on the piece under the cursor (`strokeStart`).
   */
  freeze(): void {
    const reports: FreezeReport[] = [];
    if (this.edit('freeze', true, () => {
      const underLoad = this.world.params(0).gravity !== 0;
      for (const b of this.everyBody) reports.push(this.world.freeze(b, underLoad, this.settings.keepTension));
    })) {
      const sum = (k: 'residual' | 'load' | 'clamped') => reports.reduce((s, r) => s + (r?.[k] ?? 0), 0);
      const clamped = sum('clamped');
      const kept = this.settings.keepTension && reports.length ? ` (skin taut; residual ${fmt(sum('residual'))} N of ${fmt(sum('load'))} N${clamped ? `, ${clamped} springs at their limit` : ''})` : ' (skin slack)';
      this.hooks.message(`frozen: this shape is the new rest shape${reports.length > 1 ? ` of all ${reports.length} bodies` : ''}${kept}`);
    }
  }
  reset(): void { this.edit('reset', true, () => { for (const b of this.everyBody) this.world.reset(b); }); }
  /**
   * Remesh: even triangles at the body's mean edge length (isotropic remeshing in the core;
   * masses and pins carried to the nearest new vertices), frozen under load under gravity as
   * Subdivide is, so the shape holds; undoable. Every body, each at its own mean edge length.
   * The core keeps the shape or refuses (docs/meshing.md, "The shape is kept"): a body too coarse
   * for its mean edge (an imported 8-vertex box) is remeshed at a half or a quarter of it, or
   * keeping its sharp edges, and the message says so; one that cannot be kept is one error, and
   * every body is as it was.
   */
  remesh(): void {
    const before = this.everyBody.map((b) => this.world.quality(b));
    const reports: RemeshReport[] = [];
    const done = this.edit('remesh', true, () => {
      this.hooks.progress('remeshing');
      const underLoad = this.world.params(0).gravity !== 0;
      for (const b of this.everyBody) {
        const gas = this.world.params(b)['gas.ambient'];
        reports.push(this.world.remeshReporting(b, before[b].edge_mean, underLoad));
        if (!underLoad && typeof gas === 'number') this.world.setParam(b, 'gas.ambient', gas);
      }
    }, 'all', (why) => `not remeshed: ${why.replace(/^remesh: /, '')} — the model is as it was before`);
    if (!done) return;
    const after = this.everyBody.map((b) => this.world.quality(b));
    const share = (q: typeof before) => Math.max(...q.map((x) => x.small_angle_share));
    const least = (q: typeof before) => Math.min(...q.map((x) => x.min_angle_deg));
    // What the core had to do to keep the shape: the edge it used instead of the mean edge.
    const shortened = reports.filter((r) => r.tries > 1);
    const r = shortened[0];
    const how = r ? `; made at edge ${sig3(r.edge)} m${r.crease_deg !== null ? ', keeping its sharp edges,' : ''} since the mean edge ${sig3(r.requested)} m would have changed the shape (too coarse for it)${r.distance > 1e-6 * r.edge ? `; the surface moved ≤ ${sig3(r.distance)} m` : ''}${shortened.length > 1 ? `; ${shortened.length} bodies so` : ''}` : '';
    this.hooks.message(`remeshed: ${this.totalVertices} vertices${after.length > 1 ? ` in ${after.length} bodies` : ''}; angles below 25°: ${pct(share(before))} → ${pct(share(after))}, smallest ${least(before).toFixed(0)}° → ${least(after).toFixed(0)}°${how}`);
  }

  /** Vertices of every body. */
  get totalVertices(): number { return this.everyBody.reduce((n, b) => n + this.world.body(b).vertexCount, 0); }

  subdivide(): void {
    if (this.totalVertices > 200_000) { this.hooks.message('the mesh is already very fine; not subdividing', 'warn'); return; }
    // What to expect, said before it runs: Loop subdivision makes V + E ≈ 4V − 6 vertices of a
    // closed mesh of V (E = 3V − 6 edges).
    const next = this.everyBody.reduce((n, b) => n + 4 * this.world.body(b).vertexCount - 6, 0);
    if (next > REAL_TIME_VERTICES) this.hooks.message(`subdividing to about ${next.toLocaleString('en-US')} vertices: past ~${REAL_TIME_VERTICES.toLocaleString('en-US')} the steps here cannot all converge in real time while you shape it — expect slow motion and time-limited accuracy then (the HUD says both); Ctrl+Z undoes`, 'warn');
    this.edit('subdivide', true, () => {
      this.hooks.progress('subdividing');
      let dropped = 0, underLoad = false;
      const n0 = this.totalVertices;
      const volume = () => { this.synced(); return this.everyBody.reduce((v, b) => v + this.world.body(b).stats.volume, 0); };
      const v0 = volume();
      for (const b of this.everyBody) {
        const before = this.world.params(b);
        dropped += this.world.subdivide(b);
        // The subdivided body comes plainly frozen at its current shape: springs at rest, the
        // ambient pressure raised to the gas pressure. Under gravity nothing would then carry the
        // weight and it would sag (the mushroom to half its height). As Freeze does under gravity:
        // the gas as it was, and the rest shape frozen under load, so the shape holds.
        if (before.gravity !== 0) {
          this.world.setParam(b, 'gas.ambient', before['gas.ambient'] as number);
          this.world.freeze(b, true);
          underLoad = true;
        }
      }
      // Said, so the last operation's message does not stay on screen as if it were this one's.
      // Loop subdivision moves every vertex towards a smooth limit surface: a fine mesh keeps its
      // shape, a coarse one is rounded (an 8-vertex unit cube loses half its volume), and the
      // message says which.
      const change = volume() / v0 - 1;
      // (An open mesh has no volume to compare: no change said.)
      const kept = !Number.isFinite(change) || !(v0 > 0) || Math.abs(change) <= SUBDIVIDE_KEPT;
      const shape = kept ? `the shape kept${underLoad ? ' under its weight' : ''}` : `smoothing rounded the shape: volume ${change > 0 ? '+' : '−'}${pct(Math.abs(change))}${underLoad ? ', held under its weight' : ''}`;
      this.hooks.message(`subdivided: ${n0.toLocaleString('en-US')} → ${this.totalVertices.toLocaleString('en-US')} vertices, ${shape} (Ctrl+Z undoes)`, kept ? 'info' : 'warn');
      if (dropped > 0) this.hooks.message(`${dropped} pending scene events of the bodies no longer fit their meshes and were dropped`, 'warn');
      // Implicit steps keep dt (the parameters do not depend on the resolution); an explicit
      // integrator needs the finer mesh's stable step.
      const integrator = String(this.world.params(0).integrator);
      if (integrator !== 'implicit') this.setDt(Math.min(this.settings.dt, this.world.stableDt(integrator)));
      this.settings.substeps = stepsPerFrame(this.settings.dt);
    });
  }

  // ----- strokes (the tools' drags) ---------------------------------------------------------------

  strokeStart(s: StrokeStart): void {
    if (this.stroke) this.strokeEnd();
    const b = s.body ?? 0;
    if (!Number.isInteger(b) || b < 0 || b >= this.world.bodyCount) { this.hooks.message(`there is no body ${b} to shape`, 'warn'); return; }
    this.strokeOn = b;
    this.world.forgetRewind();
    this.world.mark();
    this.stroke = makeStroke(s);
    // A brush keeps what it painted and the state of those vertices; a drag moves everything.
    this.strokeScope = s.tool === 'grab' || s.tool === 'press' ? 'all' : 'touched';
    this.stroke.start(this.strokeBody());
    if (this.stroke.paintsBodyData) this.bodyVersion++;
  }
  strokeMove(point: Vec3 | null, inverted: boolean, pressure?: number): void {
    this.stroke?.press(pressure);
    this.stroke?.move(point, inverted, this.strokeBody());
  }
  strokeEnd(): void {
    if (!this.stroke) return;
    const stroke = this.stroke;
    this.stroke = null;
    stroke.end(this.strokeBody());
    this.history.push(stroke.label, { delta: this.world.delta(this.strokeScope), settings: { ...this.settings }, scene: this.session });
    this.hooks.changed();
  }
  get stroking(): boolean { return this.stroke !== null; }

  /** The stroke's body as the strokes see it. */
  private strokeBody(): StrokeBody {
    const w = this.world, b = this.strokeOn;
    return {
      get view() { return w.body(b); },
      applyLoads: () => w.applyLoads(b),
      scaleRest: (f) => w.scaleRest(b, f),
      setMasses: (m) => w.setMasses(b, m),
      setPins: () => w.setPins(b),
      setTargets: (r) => w.setTargets(b, r),
    };
  }

  // ----- stepping -------------------------------------------------------------------------------

  /** The stroke acts for `dt` simulated seconds (before the steps of a tick). */
  updateStroke(dt: number): void {
    if (!this.stroke) return;
    this.stroke.update(this.strokeBody(), dt, this.settings.dt);
    if (this.stroke.paintsBodyData) this.bodyVersion++;
  }

  /**
   * `n` steps of `dt` (s) of the world, contacts and scene events included, as the core's
   * `World::advance` takes them: a step the implicit solver refuses split up to SPLITS times,
   * the relaxed retry before a refusal, and under a wall-clock budget of `seconds` (> 0; 0:
   * every step to the tolerance) each implicit step accepted at its deadline once within the
   * minimum accuracy, explicit steps only while the budget lasts (`lastAdvance.simulated` says
   * how far it got). A grab's anchors move towards the cursor over the steps' simulated time
   * (`anchorpath.ts`). On a blow-up the engine goes back to the last state known good since the
   * user's last change (the core's `world/rewind.rs`); the document pauses and says so. False
   * then, or when a waiting command interrupted a step (the world as before that step).
   */
  advance(dt: number, n: number, seconds = 0): boolean {
    this.lastAdvance = null;
    try {
      if (dt !== this.settings.dt) this.setDt(dt);
      const anchors = this.stroke?.path(this.strokeBody()) ?? null;
      anchors?.aim(dt * n);
      const a = this.world.advance(dt * n, seconds, 0, SPLITS, true, true);
      this.lastAdvance = a;
      anchors?.took(a.simulated);
      anchors?.stepped(this.newtonIterations(), a.splits > 0);
      // The frame's largest residual is an early step's when any was stopped at its deadline (a
      // converged step's is below the tolerance, an early one's above it).
      if (a.early > 0) this.accuracy = Math.max(this.accuracy, a.residual);
      this.noteRelaxed();
      if (a.splits > 0) this.splitFrame(a.splits);
      return true;
    } catch (e) {
      // A command is waiting (protocol.ts `interrupts`): the engine abandoned the step, the world
      // as before it; the command comes next and the steps go on after it.
      if ((e as { fields?: Record<string, unknown> } | null)?.fields?.cause === 'interrupted') return false;
      this.settings.playing = false;
      this.pausedByError = true;
      // The engine went back to the last state known good (its rewind points), or where it had
      // none to the start of the failing step.
      const back = (e as { fields?: Record<string, unknown> } | null)?.fields?.rewound_to;
      const rewoundTo = typeof back === 'number' ? back : undefined;
      if (rewoundTo !== undefined) this.bodyVersion++;
      this.stroke?.rebase(this.strokeBody());
      const integrator = String(this.world.params(0).integrator);
      this.hooks.message(explainStop(e, {
        integrator, dt: this.settings.dt, changes: this.changes, groundUnderBody: this.groundUnderBody, imported: this.imported,
        stableDt: integrator === 'implicit' ? undefined : this.world.stableDt(integrator), rewoundTo,
      }), 'error');
      return false;
    }
  }
  /** The model is an import (set by worker/importer.ts): what a stop soon after it names (explain.ts). */
  imported: Imported | undefined = undefined;
  /** What the last `advance` did (null if it failed or was interrupted). */
  lastAdvance: Advance | null = null;

  /** Whether body 0 steps with the implicit integrator. */
  get implicit(): boolean { return this.world.params(0).integrator === 'implicit'; }
  /** Newton iterations of the last step, the most over the bodies. */
  private newtonIterations(): number {
    return Math.max(0, ...this.everyBody.map((b) => this.world.newtonIterations(b)));
  }

  /** The largest relative residual an implicit step stopped by its deadline was accepted at since `takeAccuracy`. */
  private accuracy = 0;
  /** That residual (0: every step converged); starts again. */
  takeAccuracy(): number {
    const a = this.accuracy;
    this.accuracy = 0;
    return a;
  }

  /** Steps that let go of hinges to finish (since the model was opened: reset in `newModel`). */
  relaxedSteps = 0;
  /** After steps that may have been relaxed (the core's relaxed retry): count it, and say so once. */
  private noteRelaxed(): void {
    const r = Math.max(0, ...this.everyBody.map((b) => this.world.relaxed(b)));
    if (r === 0 || ++this.relaxedSteps !== 1) return;
    this.synced();
    this.hooks.message(`a step at t = ${fmt(this.world.body(0).stats.time)} s could not be finished with the surface's bending where faces are crushed flat; ` +
      `it was taken with ${r === 1 ? "those faces' bending" : 'all hinge bending'} let go for that step, so the simulation goes on (a crushed fold may keep its crease).`, 'warn');
  }

  /** Frames whose implicit step had to be split (since the model was loaded). */
  splitFrames = 0;
  /** A frame's step was split: after SPLIT_NOTICE such frames, say so once. */
  private splitFrame(splits: number): void {
    if (++this.splitFrames !== SPLIT_NOTICE) return;
    this.hooks.message(`implicit steps of ${fmt(this.settings.dt)} s did not converge in ${SPLIT_NOTICE} frames (the last split in ${splits + 1}); ` +
      'those frames ran as shorter steps. More damping, a looser tolerance or a smaller dt avoids it.', 'warn');
  }

  // ----- scenes ---------------------------------------------------------------------------------

  /** Open a scene file (with the mesh files it names); undoable. False if it could not be read. */
  openScene(name: string, text: string, files: Map<string, Uint8Array> = new Map()): boolean {
    this.hooks.progress(`opening ${name}`);
    let opened = { names: [] as string[], dt: 0, duration: 0 };
    const ok = this.edit(`open ${name}`, true, () => {
      opened = this.world.openScene(text, files);
      this.session = { name, text, files, duration: opened.duration };
      this.settings.frame = null;
      this.settings.dt = opened.dt;
      this.settings.substeps = stepsPerFrame(opened.dt);
      this.settings.model = name;
      // A scene opens paused at t = 0, so its first events are seen when the user plays it.
      this.newModel();
      this.settings.playing = false;
      this.pausedByError = false;
    }, 'all', (why) => `could not open ${name}: ${why} — the current model is unchanged`);
    if (!ok) return false;
    const n = opened.names.length;
    this.hooks.message(`opened scene ${name}: ${n} ${n === 1 ? 'body' : 'bodies'}, ${opened.duration} s of events — paused at t = 0; Space plays it`);
    return true;
  }

  /** Play the open scene again from its start (undoable like opening it). */
  restartScene(): void {
    if (!this.session) { this.hooks.message('no scene is open (Files › Open scene…)', 'warn'); return; }
    const s = this.session;
    this.openScene(s.name, s.text, s.files);
  }

  /** The world as scene file text, the shapes as they are now (an open scene's obstacles and events kept). */
  sceneText(): string { return this.world.saveScene(); }

  // ----- project files and the autosave -----------------------------------------------------------

  projectText(): string {
    return serialize({ name: this.settings.model, ui: { ...this.settings, ...this.ui }, snapshot: this.world.snapshot() });
  }

  /** The autosave's record of the world as it is now, with the newest undo steps (HISTORY_KEPT_BYTES). */
  autosaveRecord(now: number): AutosaveRecord {
    return { name: this.settings.model, ui: { ...this.settings, ...this.ui }, snapshot: this.world.snapshot(), savedAt: now, history: this.history.newest(HISTORY_KEPT_BYTES) };
  }

  /** Undo steps from an autosave (taken with its snapshot): well-formed ones only. Returns how many. */
  private takeHistory(h: AutosaveRecord['history']): number {
    if (!h) return 0;
    const ok = (i: { label: string; state: unknown }) => typeof i.label === 'string' && i.state !== null && typeof i.state === 'object' &&
      (i.state as Entry).delta instanceof Uint8Array && typeof (i.state as Entry).settings === 'object';
    if (!h.undo.every(ok) || !h.redo.every(ok)) return 0;
    this.history.load(h.undo as { label: string; state: Entry }[], h.redo as { label: string; state: Entry }[]);
    return this.history.sizes[0];
  }

  private openRecord(r: { name: string; ui: Record<string, unknown>; snapshot: Uint8Array }, undoable: boolean, label?: string): void {
    const ok = this.edit(`open ${label ?? r.name}`, undoable, () => {
      this.fresh();
      this.world.restore(r.snapshot);
      this.takeUi(r.name, r.ui);
    });
    if (!ok) throw new ProjectError('it was not opened');
  }

  /** Open project text (version 2, or a version-1 file migrated by the engine); throws what is wrong. */
  openProjectText(text: string, undoable = true, label?: string): void {
    const p = parse(text);
    if (p.version === 2) { this.openRecordOrThrow(p, undoable, label); return; }
    const w = this.world;
    w.mark();
    let meta: { name: string; ui: Record<string, unknown> };
    try {
      meta = w.openProjectV1(p.text);
    } catch (e) {
      throw new ProjectError(errorText(e));
    }
    // Opened: record it as one undo step like any other.
    const settings = { ...this.settings }, scene = this.session;
    this.session = null;
    this.newModel();
    this.takeUi(meta.name, meta.ui);
    if (undoable) this.history.push(`open ${label ?? meta.name}`, { delta: w.delta('all'), settings, scene });
    this.touched();
    this.hooks.changed();
  }

  /** A version-2 project: its snapshot must restore, or nothing changes and this throws why. */
  private openRecordOrThrow(p: { name: string; ui: Record<string, unknown>; snapshot: Uint8Array }, undoable: boolean, label?: string): void {
    // Check the snapshot in a scratch world first, so a bad file says exactly what is wrong.
    const scratch = World.create();
    try { scratch.restore(p.snapshot); } catch (e) { throw new ProjectError(`the project's model: ${errorText(e)}`); } finally { scratch.free(); }
    this.openRecord(p, undoable, label);
  }

  private takeUi(name: string, ui: Record<string, unknown>): void {
    const u = ui as Partial<Settings & UiState>;
    this.settings.dt = this.world.params(0).dt as number;
    if (typeof u.substeps === 'number' && u.substeps >= 1) this.settings.substeps = u.substeps;
    if (typeof u.playing === 'boolean') this.settings.playing = u.playing;
    if (typeof u.realTime === 'boolean') this.settings.realTime = u.realTime;
    if (typeof u.keepTension === 'boolean') this.settings.keepTension = u.keepTension;
    this.settings.model = name;
    this.settings.frame = validFrame(u.frame);
    const page: Partial<UiState> = {};
    if (u.brush && typeof u.brush.radius === 'number') page.brush = { radius: u.brush.radius };
    if (typeof u.tool === 'string') page.tool = u.tool;
    if (u.strengths && typeof u.strengths === 'object') page.strengths = u.strengths;
    if (Array.isArray(u.symmetry) && u.symmetry.length === 3 && u.symmetry.every((a) => typeof a === 'boolean')) page.symmetry = u.symmetry;
    if (typeof u.material === 'string') page.material = u.material;
    this.ui = { ...this.ui, ...page };
    this.hooks.ui(page);
  }

  openProject(name: string, text: string): void {
    try {
      this.openProjectText(text, true, name);
      this.hooks.message(`opened ${name}`);
    } catch (e) {
      this.hooks.message(`could not open ${name}: ${errorText(e)} — the current model is unchanged`, 'error');
    }
  }
}

/** An import frame from a project file, if it is one. */
function validFrame(f: unknown): ImportFrame | null {
  const x = f as ImportFrame | null | undefined;
  if (!x || (x.up !== 'y' && x.up !== 'z') || !Array.isArray(x.offset) || x.offset.length !== 3 || !x.offset.every(Number.isFinite)) return null;
  return { up: x.up, offset: [x.offset[0], x.offset[1], x.offset[2]], ...(typeof x.format === 'string' ? { format: x.format } : {}), ...(typeof x.file === 'string' ? { file: x.file } : {}) };
}

function fmt(t: number | undefined): string {
  return t === undefined ? '?' : t.toPrecision(3);
}

const pct = (x: number) => `${(100 * x).toFixed(x < 0.01 ? 1 : 0)} %`;

export function errorText(e: unknown): string {
  return e instanceof Error ? e.message : String(e);
}
