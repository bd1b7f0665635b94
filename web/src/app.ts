// The modeler: one body (or a scene's bodies, the first one active), the view, the tools, undo,
// autosave, and the frame loop.
//
// A frame: the active tool updates its forces, the simulation runs its steps within a time
// budget (if it cannot keep up it runs in slow motion and says so), then the view reads the
// engine's positions and renders.

import { Vector3 } from 'three';
import { SoftBody } from './engine/softbody';
import { Scene } from './engine/scene';
import { SceneSession, type SceneSource } from './scene-session';
import { EDITABLE, type ParamName } from './engine/params';
import { History, travel } from './history';
import { capture, parse, restore, serialize, type BodyState } from './project';
import { loadModel, defaultSettings, stableDt, placeOnGround, type ModelName } from './models';
import { Viewport } from './view/viewport';
import { Plots } from './view/plots';
import { Hud } from './view/hud';
import { ToolManager } from './tools/manager';
import type { Tool, ToolContext } from './tools/tool';
import { GrabTool } from './tools/grab';
import { PressTool } from './tools/press';
import { InflateTool, MassTool, PinTool } from './tools/paint';
import { importModel } from './io/import';
import { download, exportShape, type ExportFormat } from './io/export';
import { loadAutosave, saveAutosave } from './storage';

type Entry =
  | { kind: 'body'; state: BodyState; settings: Settings }
  | { kind: 'params'; params: Partial<Record<ParamName, number>> }
  // Undo of opening a scene: back to the body before it; its inverse opens the scene again.
  | { kind: 'before-scene'; state: BodyState; settings: Settings }
  | { kind: 'reopen-scene'; source: SceneSource };



export interface Settings {
  /** Time step (s). */
  dt: number;
  /** Steps per frame when not in real time; in real time, the steps that fill the frame's time. */
  substeps: number;
  /** Advance simulated time at the pace of the clock (steps per frame follow the frame rate). */
  realTime: boolean;
  playing: boolean;
  model: string;
}

/**
 * Simulation time allowed per frame (ms) before the modeler falls back to slow motion: half the
 * time between frames (so drawing and input keep the other half), within [8, 30] ms.
 */
function frameBudget(elapsedSeconds: number): number {
  return Math.min(30, Math.max(8, 500 * elapsedSeconds));
}

export class App implements ToolContext {
  private current!: SoftBody;
  readonly viewport: Viewport;
  readonly brush = { radius: 0.35 };
  readonly history = new History<Entry>(50);
  readonly settings: Settings = { dt: 1e-3, substeps: 16, realTime: true, playing: true, model: 'mushroom' };
  private lastFrame = 0;
  /** Measured cost of one step (ms), to size the chunks of steps between budget checks. */
  private stepCostMs = 0.05;
  readonly tools: ToolManager;
  readonly plots: Plots;
  readonly hud: Hud;
  wireframe = false;
  /** Simulated time per frame fell short of the requested steps (running in slow motion). */
  slowMotion = false;
  simMs = 0;
  private pending: { label: string; state: BodyState } | null = null;
  private saveTimer = 0;
  private listeners: (() => void)[] = [];
  private lastMessage = '';
  /** The open scene (its first body is the active body), if any. */
  private session: SceneSession | null = null;

  constructor(canvas: HTMLCanvasElement, plotCanvas: HTMLCanvasElement, hudRoot: HTMLElement, helpText: string) {
    this.viewport = new Viewport(canvas);
    this.plots = new Plots(plotCanvas);
    this.hud = new Hud(hudRoot, helpText);
    const tools: Tool[] = [new GrabTool(), new PressTool(), new InflateTool(), new MassTool(), new PinTool()];
    this.tools = new ToolManager(this, tools, () => { this.refreshOverlay(); this.changed(); });
  }

  body(): SoftBody { return this.current; }

  /** Called whenever the body or a parameter changed (the panel refreshes itself). */
  onChange(f: () => void): void { this.listeners.push(f); }
  private changed(): void { for (const f of this.listeners) f(); }

  // ----- bodies ---------------------------------------------------------------------------------

  private setBody(body: SoftBody): void {
    const old = this.current;
    this.current = body;
    if (this.session && this.session.active !== body) {
      const note = this.session.adopt(body);
      if (note) this.message(note, 'warn');
    }
    if (old && old !== body) old.free();
    this.viewport.attach(body);
    this.viewport.update(body);
    this.plots.clear();
    this.refreshOverlay();
    this.syncScene();
    this.changed();
  }

  /** Open on the autosaved project if there is one, else the default model. */
  async start(): Promise<void> {
    try {
      const text = await loadAutosave();
      if (text) {
        this.openProjectText(text, false);
        this.message('restored your last session (autosaved)');
        return;
      }
    } catch (e) {
      this.message(`could not read the autosaved project: ${errorText(e)}`, 'warn');
    }
    this.loadBuiltin('mushroom', false);
  }

  /** A built-in model with the default world, settled at rest on the ground. */
  loadBuiltin(name: ModelName, undoable = true): void {
    this.edit(`load ${name}`, undoable, () => {
      const body = loadModel(name);
      this.closeScene();
      const { dt } = defaultSettings(body);
      this.settings.dt = dt;
      this.settings.substeps = Math.max(1, Math.round(1 / 60 / dt));
      this.settings.model = name;
      // Let it settle on the ground (a few simulated seconds) so it opens at rest.
      for (let t = 0; t < 6; t += dt * 100) body.step(dt, 100);
      this.setBody(body);
    });
  }

  async importFile(name: string, data: ArrayBuffer): Promise<void> {
    try {
      const imported = await importModel(name, data);
      let body = imported.kind === 'obj' ? SoftBody.fromObj(imported.bytes) : SoftBody.fromMesh(imported.positions, imported.indices);
      const warnings = body.warnings;
      const placed = placeOnGround(body.positions().slice(), 2.5);
      const placedBody = SoftBody.fromMesh(placed.positions, body.triangles().slice(), 1, false);
      body.free();
      body = placedBody;
      this.edit(`import ${name}`, true, () => {
        this.closeScene();
        const { dt } = defaultSettings(body);
        this.settings.dt = dt;
        this.settings.substeps = Math.max(1, Math.round(1 / 60 / dt));
        this.settings.model = name;
        this.setBody(body);
      });
      this.message(`imported ${name}: ${body.vertexCount} vertices, ${body.faceCount} faces (scaled ×${placed.scale.toPrecision(3)} to fit)`);
      if (warnings) this.message(warnings, 'warn');
    } catch (e) {
      this.message(`could not import ${name}: ${errorText(e).replace(/^(OBJ|mesh): /, '')} — the current model is unchanged`, 'error');
    }
  }

  // ----- editing and undo ---------------------------------------------------------------------

  beginEdit(label: string): void {
    this.pending = { label, state: capture(this.current) };
  }

  endEdit(): void {
    if (!this.pending) return;
    this.history.push(this.pending.label, { kind: 'body', state: this.pending.state, settings: { ...this.settings } });
    this.pending = null;
    this.changed();
    this.autosave();
  }

  /** Run a modeling operation as one undoable step. */
  edit(label: string, undoable: boolean, op: () => void): void {
    const before = this.current && undoable ? capture(this.current) : null;
    const settings = { ...this.settings };
    try {
      op();
    } catch (e) {
      this.message(`${label}: ${errorText(e)}`, 'error');
      return;
    }
    if (before) this.history.push(label, { kind: 'body', state: before, settings });
    this.changed();
    this.autosave();
  }

  /** Change a parameter (undoable); refused values are reported and leave the old one. */
  setParam(name: ParamName, value: number): boolean {
    const before = { [name]: this.current.get(name) };
    try {
      this.current.set(name, value);
    } catch (e) {
      this.message(errorText(e), 'error');
      this.changed();
      return false;
    }
    this.history.push(`set ${name}`, { kind: 'params', params: before });
    this.shareWorld([name]);
    this.syncScene();
    this.changed();
    this.autosave();
    return true;
  }

  private apply(entry: Entry): Entry {
    if (entry.kind === 'params') {
      const now: Partial<Record<ParamName, number>> = {};
      for (const [k, v] of Object.entries(entry.params) as [ParamName, number][]) {
        now[k] = this.current.get(k);
        this.current.set(k, v);
      }
      this.shareWorld(Object.keys(entry.params) as ParamName[]);
      this.syncScene();
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
      const now: Entry = { kind: 'before-scene', state: capture(this.current), settings: { ...this.settings } };
      this.enterScene(SceneSession.open(entry.source));
      return now;
    }
    const now: Entry = { kind: 'body', state: capture(this.current), settings: { ...this.settings } };
    Object.assign(this.settings, entry.settings);
    this.setBody(restore(entry.state));
    return now;
  }

  undo(): void { this.travel('undo'); }
  redo(): void { this.travel('redo'); }

  private travel(dir: 'undo' | 'redo'): void {
    if (this.tools.isDragging) return;
    try {
      const item = travel(this.history, dir, (e) => this.apply(e));
      if (!item) { this.message(`nothing to ${dir}`); return; }
      this.message(`${dir === 'undo' ? 'undid' : 'redid'} ${item.label}`);
    } catch (e) {
      this.message(`${dir} failed: ${errorText(e)}`, 'error');
    }
    this.changed();
    this.autosave();
  }

  // ----- modeling operations ------------------------------------------------------------------

  /** Freeze: under gravity the body keeps carrying its weight (no sag), otherwise a plain freeze. */
  freeze(): void {
    this.edit('freeze', true, () => (this.current.get('gravity') !== 0 ? this.current.freezeUnderLoad() : this.current.freeze()));
    this.message('frozen: this shape is the new rest shape');
  }
  reset(): void { this.edit('reset', true, () => this.current.reset()); }
  subdivide(): void {
    if (this.current.vertexCount > 200_000) { this.message('the mesh is already very fine; not subdividing', 'warn'); return; }
    this.edit('subdivide', true, () => {
      this.current.subdivide();
      const note = this.session?.adopt(this.current);
      if (note) this.message(note, 'warn');
      this.settings.dt = Math.min(this.settings.dt, stableDt(this.current));
      this.settings.substeps = Math.max(1, Math.round(1 / 60 / this.settings.dt));
      this.setBody(this.current);
    });
  }

  /** Wind blowing along the current view direction at `strength` m/s (0: calm); undoable. */
  windFromView(strength: number): void {
    const d = this.viewport.camera.getWorldDirection(new Vector3());
    this.edit('wind', true, () => {
      this.current.set('windX', d.x * strength);
      this.current.set('windY', d.y * strength);
      this.current.set('windZ', d.z * strength);
      this.shareWorld(['windX', 'windY', 'windZ']);
    });
    this.syncScene();
  }

  step(): void {
    try {
      this.advance(this.settings.dt, this.settings.substeps);
      this.viewport.extras.update();
    } catch (e) {
      this.blowUp(e);
    }
  }

  /** `n` steps of `dt`: the whole scene (contacts, events) if one is open, else the body. */
  private advance(dt: number, n: number): void {
    if (this.session) this.session.scene.step(dt, n);
    else this.current.step(dt, n);
  }

  // ----- scenes ---------------------------------------------------------------------------------

  /** Open a scene file (with the mesh files it names); undoable. False if it could not be read. */
  openScene(name: string, text: string, files: Map<string, Uint8Array> = new Map()): boolean {
    let session: SceneSession;
    try {
      session = SceneSession.open({ name, text, files });
    } catch (e) {
      this.message(`could not open ${name}: ${errorText(e).replace(/^scene: /, '')} — the current model is unchanged`, 'error');
      return false;
    }
    const before: Entry = { kind: 'before-scene', state: capture(this.current), settings: { ...this.settings } };
    this.enterScene(session);
    this.history.push(`open ${name}`, before);
    const n = session.scene.bodies.length;
    this.message(`opened scene ${name}: ${n} ${n === 1 ? 'body' : 'bodies'}, ${session.scene.duration} s of events — play to run it`);
    this.changed();
    this.autosave();
    return true;
  }

  private enterScene(session: SceneSession): void {
    this.closeScene();
    this.settings.dt = session.scene.dt;
    this.settings.substeps = Math.max(1, Math.round(1 / 60 / session.scene.dt));
    this.settings.model = session.source.name;
    this.session = session;
    this.setBody(session.active);
    this.viewport.extras.setBodies(session.others);
    this.viewport.extras.setObstacles(session.scene.obstacles());
  }

  /** Play the open scene again from its start (undoable like opening it). */
  restartScene(): void {
    if (!this.session) { this.message('no scene is open (Files › Open scene…)', 'warn'); return; }
    const s = this.session.source;
    this.openScene(s.name, s.text, s.files);
  }

  /** Download the open scene (or the body alone) as a scene file, the shapes as they are now. */
  saveScene(): void {
    try {
      const scene = this.session?.scene ?? null;
      const text = Scene.save(scene ? scene.bodies : [this.current], this.settings.dt, scene?.duration ?? 10, scene);
      download(new Blob([text], { type: 'application/toml' }), `${baseName(this.settings.model)}.toml`);
      this.message('saved the scene: the shapes as they are now, opening at rest');
    } catch (e) {
      this.message(`could not save the scene: ${errorText(e)}`, 'error');
    }
  }

  get sceneInfo(): SceneSession['info'] | null { return this.session?.info ?? null; }

  /** Leave the scene: its other bodies go; the active body stays (until replaced). */
  private closeScene(): void {
    this.session?.close();
    this.session = null;
    this.viewport.extras.clear();
  }

  private shareWorld(names: ParamName[]): void { this.session?.shareWorld(this.current, names); }

  private blowUp(e: unknown): void {
    this.settings.playing = false;
    this.message(`${errorText(e)}. Paused. Try a smaller dt (now ${this.settings.dt} s) or another integrator.`, 'error');
    this.changed();
  }

  // ----- files ----------------------------------------------------------------------------------

  async export(format: ExportFormat): Promise<void> {
    const blob = await exportShape(format, this.current.positions(), this.current.triangles());
    download(blob, `${baseName(this.settings.model)}.${format}`);
  }

  projectText(): string {
    return serialize({ name: this.settings.model, state: capture(this.current), ui: { ...this.settings, brush: this.brush, tool: this.tools.tool.name, strengths: Object.fromEntries(this.tools.tools.map((t) => [t.name, t.strength])) } });
  }

  saveProject(): void {
    download(new Blob([this.projectText()], { type: 'application/json' }), `${baseName(this.settings.model)}.softsculpt.json`);
  }

  openProjectText(text: string, undoable = true): void {
    const p = parse(text);
    const body = restore(p.state);
    this.edit(`open ${p.name}`, undoable, () => {
      const ui = p.ui as Partial<Settings> & { brush?: { radius: number }; tool?: string; strengths?: Record<string, number> };
      if (typeof ui.dt === 'number' && ui.dt > 0) this.settings.dt = ui.dt;
      if (typeof ui.substeps === 'number' && ui.substeps >= 1) this.settings.substeps = ui.substeps;
      if (typeof ui.playing === 'boolean') this.settings.playing = ui.playing;
      if (typeof ui.realTime === 'boolean') this.settings.realTime = ui.realTime;
      this.settings.model = p.name;
      if (ui.brush && typeof ui.brush.radius === 'number') this.brush.radius = ui.brush.radius;
      for (const t of this.tools.tools) if (typeof ui.strengths?.[t.name] === 'number') t.strength = ui.strengths[t.name];
      this.closeScene();
      this.setBody(body);
      if (ui.tool) this.tools.select(ui.tool);
    });
  }

  async openProjectFile(name: string, text: string): Promise<void> {
    try {
      this.openProjectText(text);
      this.message(`opened ${name}`);
    } catch (e) {
      this.message(`could not open ${name}: ${errorText(e)} — the current model is unchanged`, 'error');
    }
  }

  autosave(): void {
    clearTimeout(this.saveTimer);
    this.saveTimer = window.setTimeout(() => {
      saveAutosave(this.projectText()).catch((e) => this.message(`autosave failed: ${errorText(e)}`, 'warn'));
    }, 250);
  }

  // ----- the frame ------------------------------------------------------------------------------

  refreshOverlay(): void {
    const t = this.tools.tool;
    this.viewport.setColors(t.overlay ? (c) => t.overlay!(c, this.current) : null);
  }

  syncScene(): void {
    const b = this.current;
    this.viewport.setGround(b.get('groundOn') !== 0, b.get('groundHeight'));
    this.viewport.setWind([b.get('windX'), b.get('windY'), b.get('windZ')]);
    this.viewport.springs.visible = this.wireframe;
  }

  frame(): void {
    const body = this.current;
    const now = performance.now();
    // Real time: as many steps as the time since the last frame holds (at most 0.1 s of it).
    const elapsed = this.lastFrame ? Math.min(0.1, (now - this.lastFrame) / 1000) : 1 / 60;
    this.lastFrame = now;
    const { dt } = this.settings;
    const substeps = this.settings.realTime ? Math.max(1, Math.round(elapsed / dt)) : this.settings.substeps;
    this.tools.update(this.settings.playing ? dt * substeps : 0);
    let done = 0;
    const t0 = performance.now();
    if (this.settings.playing) {
      try {
        // In chunks, so that a slow machine stops at the budget instead of freezing the page.
        while (done < substeps) {
          // Chunks of about 2 ms, so the budget is checked often enough on any mesh.
          const n = Math.min(substeps - done, Math.max(1, Math.floor(2 / this.stepCostMs)));
          const c0 = performance.now();
          this.advance(dt, n);
          this.stepCostMs = 0.8 * this.stepCostMs + 0.2 * Math.max(1e-4, (performance.now() - c0) / n);
          done += n;
          if (performance.now() - t0 > frameBudget(elapsed)) break;
        }
      } catch (e) {
        this.blowUp(e);
      }
    }
    this.simMs = performance.now() - t0;
    this.slowMotion = this.settings.playing && done < substeps;
    this.viewport.update(body);
    this.viewport.extras.update();
    if (this.tools.tool.overlay && this.tools.isDragging) this.refreshOverlay();
    const s = body.stats();
    this.plots.push(s.time, [s.volume, s.pressure, s.kinetic, s.elastic, s.gas]);
    this.plots.draw();
    this.hud.tick();
    this.hud.show([
      `${this.hud.fps.toFixed(0)} fps   sim ${this.simMs.toFixed(1)} ms/frame${this.slowMotion ? `   SLOW MOTION (${((done / substeps) * 100).toFixed(0)}% of real time)` : ''}${this.settings.playing ? '' : '   PAUSED'}`,
      `${body.vertexCount} vertices   ${body.springCount} springs   ${body.faceCount} faces   tool: ${this.tools.tool.label}`,
      `t ${s.time.toFixed(2)} s   V ${s.volume.toFixed(4)} m³   P ${s.pressure.toFixed(2)} Pa   max speed ${s.maxSpeed.toFixed(3)} m/s`,
      ...(this.session ? [this.session.hudLine()] : []),
    ]);
    this.viewport.render();
  }

  message(text: string, kind: 'info' | 'warn' | 'error' = 'info'): void {
    this.lastMessage = text;
    this.hud.message(text, kind);
  }
  get lastMessageText(): string { return this.lastMessage; }

  /** Parameters for the panel. */
  params(): Record<ParamName, number> {
    return Object.fromEntries(EDITABLE.map((p) => [p, this.current.get(p)])) as Record<ParamName, number>;
  }
}

function errorText(e: unknown): string {
  return e instanceof Error ? e.message : String(e);
}

function baseName(name: string): string {
  return name.replace(/\.[^.]*$/, '').replace(/\.softsculpt$/, '') || 'softsculpt';
}
