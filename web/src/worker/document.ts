// The document, in the worker: the body (or an open scene's bodies, the first one active), the
// settings it runs with, undo/redo, and every modeling operation. This is the only module of
// the page that calls the engine (src/engine/*): the rest of the worker and the whole main
// thread see the body through the methods below (and strokes through `StrokeBody`), so a change
// of the binding touches this module and src/engine/ only.

import { initEngine } from '../engine/wasm';
import { SoftBody } from '../engine/softbody';
import { Scene } from '../engine/scene';
import { SceneSession, type SceneSource } from '../engine/session';
import { Param, type ParamName } from '../engine/params';
import { capture, restore, type BodyState } from '../engine/state';
import { loadModel, defaultSettings, stableDt } from '../engine/models';
import { History, travel } from '../history';
import { parse, serialize } from '../project';
import { MODELS, placeOnGround, type ModelName } from '../models';
import { importModel } from '../io/import';
import type { MessageKind, SceneInfo, Settings, Stats, Topology, UiState, Vec3 } from '../protocol';
import { makeStroke, type Stroke, type StrokeStart } from './strokes';

type Entry =
  | { kind: 'body'; state: BodyState; settings: Settings }
  | { kind: 'params'; params: Partial<Record<ParamName, number>> }
  // Undo of opening a scene: back to the body before it; its inverse opens the scene again.
  | { kind: 'before-scene'; state: BodyState; settings: Settings }
  | { kind: 'reopen-scene'; source: SceneSource };

/** What the document tells its owner (worker/service.ts turns these into replies). */
export interface DocumentHooks {
  message(text: string, kind?: MessageKind): void;
  /** A long operation is under way (fraction done if known), or ended (null). */
  progress(label: string | null, fraction?: number): void;
  /** The model changed by an operation (the owner autosaves). */
  changed(): void;
  /** An opened project brought the page's state. */
  ui(ui: Partial<UiState>): void;
}

/** Load the engine (the wasm module's bytes, or its URL). */
export async function loadEngine(source: BufferSource | string): Promise<void> {
  await initEngine(source);
}

export const ALL_PARAMS = Object.keys(Param) as ParamName[];

export class Document {
  private current: SoftBody | null = null;
  /** The open scene (its first body is the active body), if any. */
  private session: SceneSession | null = null;
  readonly history = new History<Entry>(50);
  readonly settings: Settings = { dt: 1e-3, substeps: 16, realTime: true, playing: true, model: 'mushroom' };
  ui: UiState = { brush: { radius: 0.35 }, tool: 'grab', strengths: {} };
  private stroke: Stroke | null = null;
  private pending: { label: string; state: BodyState } | null = null;
  /** Bumped when the meshes change shape (body replaced, subdivided, scene opened or closed). */
  topologyVersion = 0;
  /** Bumped when masses or pins may have changed. */
  bodyVersion = 0;

  constructor(private readonly hooks: DocumentHooks) {}

  get loaded(): boolean { return this.current !== null; }
  private get body(): SoftBody {
    if (!this.current) throw new Error('no model is loaded yet');
    return this.current;
  }

  // ----- what the page draws and reads ----------------------------------------------------------

  get vertexCount(): number { return this.body.vertexCount; }
  /** Floats the frame buffer holds: xyz of the active body, then of each other body. */
  get renderLength(): number {
    return 3 * (this.body.vertexCount + (this.session?.others ?? []).reduce((n, b) => n + b.vertexCount, 0));
  }
  /** Write every body's positions (f32) into `out` (renderLength floats). */
  renderInto(out: Float32Array): void {
    out.set(this.body.syncRender(), 0);
    let at = 3 * this.body.vertexCount;
    for (const b of this.session?.others ?? []) { out.set(b.syncRender(), at); at += 3 * b.vertexCount; }
  }
  stats(): Stats { return this.body.stats(); }
  get sceneInfo(): SceneInfo | null { return this.session?.info ?? null; }
  topology(): Topology {
    const b = this.body;
    return {
      vertexCount: b.vertexCount,
      triangles: b.triangles().slice(),
      springs: b.springs().slice(),
      others: (this.session?.others ?? []).map((o) => ({ vertexCount: o.vertexCount, triangles: o.triangles().slice() })),
      obstacles: this.session?.scene.obstacles() ?? [],
    };
  }
  bodyData(): { masses: Float64Array; pinned: Uint8Array } {
    return { masses: this.body.masses().slice(), pinned: this.body.pinned().slice() };
  }
  params(): Record<ParamName, number> {
    const b = this.body;
    return Object.fromEntries(ALL_PARAMS.map((p) => [p, b.get(p)])) as Record<ParamName, number>;
  }

  // ----- bodies ---------------------------------------------------------------------------------

  private setBody(body: SoftBody): void {
    const old = this.current;
    this.current = body;
    if (this.session && this.session.active !== body) {
      const note = this.session.adopt(body);
      if (note) this.hooks.message(note, 'warn');
    }
    if (old && old !== body) old.free();
    this.topologyVersion++;
    this.bodyVersion++;
  }

  /** Open on the autosaved project text if there is one (and it reads), else the default model. */
  open(autosave: string | null): void {
    if (autosave) {
      try {
        this.openProjectText(autosave, false);
        this.hooks.message('restored your last session (autosaved)');
        return;
      } catch (e) {
        this.hooks.message(`could not read the autosaved project: ${errorText(e)}`, 'warn');
      }
    }
    this.loadBuiltin('mushroom', false);
  }

  private useDefaults(body: SoftBody, model: string): void {
    const { dt } = defaultSettings(body);
    this.settings.dt = dt;
    this.settings.substeps = Math.max(1, Math.round(1 / 60 / dt));
    this.settings.model = model;
  }

  /** A built-in model with the default world, settled at rest on the ground. */
  loadBuiltin(name: string, undoable = true): void {
    if (!(MODELS as readonly string[]).includes(name)) { this.hooks.message(`there is no built-in model '${name}'`, 'error'); return; }
    this.edit(`load ${name}`, undoable, () => {
      const label = `loading ${name}`;
      this.hooks.progress(label, 0);
      const body = loadModel(name as ModelName);
      try {
        this.useDefaults(body, name);
        // Let it settle on the ground (a few simulated seconds) so it opens at rest.
        const dt = this.settings.dt;
        for (let t = 0; t < 6; t += dt * 100) {
          body.step(dt, 100);
          this.hooks.progress(label, t / 6);
        }
      } catch (e) {
        body.free();
        throw e;
      }
      this.closeScene();
      this.setBody(body);
    });
  }

  async importFile(name: string, data: ArrayBuffer): Promise<void> {
    this.hooks.progress(`importing ${name}`);
    let body: SoftBody | null = null;
    try {
      const imported = await importModel(name, data);
      const read = imported.kind === 'obj' ? SoftBody.fromObj(imported.bytes) : SoftBody.fromMesh(imported.positions, imported.indices);
      const warnings = read.warnings;
      const placed = placeOnGround(read.positions().slice(), 2.5);
      try {
        body = SoftBody.fromMesh(placed.positions, read.triangles().slice(), 1, false);
      } finally {
        read.free();
      }
      const b = body;
      const ok = this.edit(`import ${name}`, true, () => {
        this.closeScene();
        this.useDefaults(b, name);
        this.setBody(b);
      });
      if (!ok) return;
      this.hooks.message(`imported ${name}: ${b.vertexCount} vertices, ${b.faceCount} faces (scaled ×${placed.scale.toPrecision(3)} to fit)`);
      if (warnings) this.hooks.message(warnings, 'warn');
    } catch (e) {
      if (body && body !== this.current) body.free();
      this.hooks.message(`could not import ${name}: ${errorText(e).replace(/^(OBJ|mesh): /, '')} — the current model is unchanged`, 'error');
    } finally {
      this.hooks.progress(null);
    }
  }

  // ----- editing and undo -----------------------------------------------------------------------

  /**
   * Run a modeling operation as one undoable step. If it fails, it is reported and the model
   * goes back to how it was before. Returns whether it succeeded.
   */
  edit(label: string, undoable: boolean, op: () => void): boolean {
    const before = this.current && undoable ? capture(this.current) : null;
    const settings = { ...this.settings };
    const body = this.current;
    try {
      op();
    } catch (e) {
      // The engine refuses an operation without changing the body; if the body had been
      // replaced already (and the old one freed), the captured state comes back.
      Object.assign(this.settings, settings);
      if (before && this.current !== body) {
        try { this.setBody(restore(before)); } catch { /* keep what there is */ }
      }
      this.hooks.message(`${label}: ${errorText(e)}${body ? ' — the model is as it was before' : ''}`, 'error');
      return false;
    } finally {
      this.hooks.progress(null);
    }
    if (before) this.history.push(label, { kind: 'body', state: before, settings });
    this.hooks.changed();
    return true;
  }

  /** Change a parameter (undoable); a refused value is reported and leaves the old one. */
  setParam(name: ParamName, value: number): boolean {
    const body = this.body;
    const before = { [name]: body.get(name) };
    try {
      body.set(name, value);
    } catch (e) {
      this.hooks.message(errorText(e), 'error');
      return false;
    }
    this.history.push(`set ${name}`, { kind: 'params', params: before });
    this.shareWorld([name]);
    this.hooks.changed();
    return true;
  }

  setMass(total: number): void {
    this.edit('set mass', true, () => this.body.set('totalMass', total));
    this.bodyVersion++;
  }

  /** Wind along `direction` at `strength` m/s (0: calm); undoable. */
  wind(direction: Vec3, strength: number): void {
    this.edit('wind', true, () => {
      this.body.set('windX', direction[0] * strength);
      this.body.set('windY', direction[1] * strength);
      this.body.set('windZ', direction[2] * strength);
      this.shareWorld(['windX', 'windY', 'windZ']);
    });
  }

  private apply(entry: Entry): Entry {
    if (entry.kind === 'params') {
      const now: Partial<Record<ParamName, number>> = {};
      for (const [k, v] of Object.entries(entry.params) as [ParamName, number][]) {
        now[k] = this.body.get(k);
        this.body.set(k, v);
      }
      this.shareWorld(Object.keys(entry.params) as ParamName[]);
      return { kind: 'params', params: now };
    }
    if (entry.kind === 'before-scene') {
      const source = this.session?.source;
      this.closeScene();
      Object.assign(this.settings, entry.settings);
      this.setBody(restore(entry.state));
      return { kind: 'reopen-scene', source: source! };
    }
    if (entry.kind === 'reopen-scene') {
      const now: Entry = { kind: 'before-scene', state: capture(this.body), settings: { ...this.settings } };
      this.enterScene(SceneSession.open(entry.source));
      return now;
    }
    const now: Entry = { kind: 'body', state: capture(this.body), settings: { ...this.settings } };
    Object.assign(this.settings, entry.settings);
    this.setBody(restore(entry.state));
    return now;
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

  /** Freeze: under gravity the body keeps carrying its weight (no sag), otherwise a plain freeze. */
  freeze(): void {
    if (this.edit('freeze', true, () => (this.body.get('gravity') !== 0 ? this.body.freezeUnderLoad() : this.body.freeze()))) {
      this.hooks.message('frozen: this shape is the new rest shape');
    }
  }
  reset(): void { this.edit('reset', true, () => this.body.reset()); }
  subdivide(): void {
    if (this.body.vertexCount > 200_000) { this.hooks.message('the mesh is already very fine; not subdividing', 'warn'); return; }
    this.edit('subdivide', true, () => {
      this.hooks.progress('subdividing');
      const body = this.body;
      body.subdivide();
      const note = this.session?.adopt(body);
      if (note) this.hooks.message(note, 'warn');
      this.settings.dt = Math.min(this.settings.dt, stableDt(body));
      this.settings.substeps = Math.max(1, Math.round(1 / 60 / this.settings.dt));
      this.setBody(body);
    });
  }

  // ----- strokes (the tools' drags) ---------------------------------------------------------------

  strokeStart(s: StrokeStart): void {
    if (this.stroke) this.strokeEnd();
    this.pending = { label: s.tool, state: capture(this.body) };
    this.stroke = makeStroke(s);
    this.stroke.start(this.body);
    if (this.stroke.paintsBodyData) this.bodyVersion++;
  }
  strokeMove(point: Vec3 | null, inverted: boolean): void { this.stroke?.move(point, inverted, this.body); }
  strokeEnd(): void {
    if (!this.stroke) return;
    this.stroke.end(this.body);
    this.stroke = null;
    if (this.pending) this.history.push(this.pending.label, { kind: 'body', state: this.pending.state, settings: { ...this.settings } });
    this.pending = null;
    this.hooks.changed();
  }
  get stroking(): boolean { return this.stroke !== null; }

  // ----- stepping -------------------------------------------------------------------------------

  /** The stroke acts for `dt` simulated seconds (before the steps of a tick). */
  updateStroke(dt: number): void {
    if (!this.stroke) return;
    this.stroke.update(this.body, dt);
    if (this.stroke.paintsBodyData) this.bodyVersion++;
  }

  /**
   * `n` steps of `dt`: the whole scene (contacts, events) if one is open, else the body. On a
   * blow-up the engine rolls the step back; the simulation pauses and says so. False then.
   */
  advance(dt: number, n: number): boolean {
    try {
      if (this.session) this.session.scene.step(dt, n);
      else this.body.step(dt, n);
      return true;
    } catch (e) {
      this.settings.playing = false;
      this.hooks.message(`${errorText(e)}. Paused. Try a smaller dt (now ${this.settings.dt} s) or another integrator.`, 'error');
      return false;
    }
  }

  // ----- scenes ---------------------------------------------------------------------------------

  /** Open a scene file (with the mesh files it names); undoable. False if it could not be read. */
  openScene(name: string, text: string, files: Map<string, Uint8Array> = new Map()): boolean {
    let session: SceneSession;
    this.hooks.progress(`opening ${name}`);
    try {
      session = SceneSession.open({ name, text, files });
    } catch (e) {
      this.hooks.progress(null);
      this.hooks.message(`could not open ${name}: ${errorText(e).replace(/^scene: /, '')} — the current model is unchanged`, 'error');
      return false;
    }
    const before: Entry = { kind: 'before-scene', state: capture(this.body), settings: { ...this.settings } };
    this.enterScene(session);
    this.hooks.progress(null);
    this.history.push(`open ${name}`, before);
    const n = session.scene.bodies.length;
    this.hooks.message(`opened scene ${name}: ${n} ${n === 1 ? 'body' : 'bodies'}, ${session.scene.duration} s of events — play to run it`);
    this.hooks.changed();
    return true;
  }

  private enterScene(session: SceneSession): void {
    this.closeScene();
    this.settings.dt = session.scene.dt;
    this.settings.substeps = Math.max(1, Math.round(1 / 60 / session.scene.dt));
    this.settings.model = session.source.name;
    this.session = session;
    this.setBody(session.active);
  }

  /** Play the open scene again from its start (undoable like opening it). */
  restartScene(): void {
    if (!this.session) { this.hooks.message('no scene is open (Files › Open scene…)', 'warn'); return; }
    const s = this.session.source;
    this.openScene(s.name, s.text, s.files);
  }

  /** The open scene (or the body alone) as scene file text, the shapes as they are now. */
  sceneText(): string {
    const scene = this.session?.scene ?? null;
    return Scene.save(scene ? scene.bodies : [this.body], this.settings.dt, scene?.duration ?? 10, scene);
  }

  /** Leave the scene: its other bodies go; the active body stays (until replaced). */
  private closeScene(): void {
    if (!this.session) return;
    this.session.close();
    this.session = null;
    this.topologyVersion++;
  }

  private shareWorld(names: ParamName[]): void { if (this.session) this.session.shareWorld(this.body, names); }

  // ----- project files --------------------------------------------------------------------------

  projectText(): string {
    return serialize({ name: this.settings.model, state: capture(this.body), ui: { ...this.settings, ...this.ui } });
  }

  openProjectText(text: string, undoable = true, label?: string): void {
    const p = parse(text);
    const body = restore(p.state);
    const ok = this.edit(`open ${label ?? p.name}`, undoable, () => {
      const ui = p.ui as Partial<Settings & UiState>;
      if (typeof ui.dt === 'number' && ui.dt > 0) this.settings.dt = ui.dt;
      if (typeof ui.substeps === 'number' && ui.substeps >= 1) this.settings.substeps = ui.substeps;
      if (typeof ui.playing === 'boolean') this.settings.playing = ui.playing;
      if (typeof ui.realTime === 'boolean') this.settings.realTime = ui.realTime;
      this.settings.model = p.name;
      const page: Partial<UiState> = {};
      if (ui.brush && typeof ui.brush.radius === 'number') page.brush = { radius: ui.brush.radius };
      if (typeof ui.tool === 'string') page.tool = ui.tool;
      if (ui.strengths && typeof ui.strengths === 'object') page.strengths = ui.strengths;
      this.ui = { ...this.ui, ...page };
      this.hooks.ui(page);
      this.closeScene();
      this.setBody(body);
    });
    if (!ok) body.free();
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

export function errorText(e: unknown): string {
  return e instanceof Error ? e.message : String(e);
}
