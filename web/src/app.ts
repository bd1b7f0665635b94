// The modeler's page: the view, the tools, the panel's operations, the HUD and plots. The
// simulation and the document run in a worker (src/worker/); the page sends it commands
// (src/protocol.ts) and draws the frames it sends back, so drawing, the camera and the panel
// never wait for the engine.
//
// A frame: the worker's latest positions (a transferred buffer) replace the drawn ones, the view
// renders them, and the buffer drawn before goes back to the worker.

import { Box3, Sphere, Vector3, type Camera } from 'three';
import type { Command, Frame, MessageKind, ParamValue, Reply, Settings, UiState } from './protocol';
import { SimulationClient } from './client';
import { paceText, viewText } from './view/pace';
import { Mirror } from './mirror';
import { Viewport } from './view/viewport';
import { Plots } from './view/plots';
import { Hud, sceneLine } from './view/hud';
import { ToolManager } from './tools/manager';
import type { Tool, ToolContext } from './tools/tool';
import { GrabTool } from './tools/grab';
import { PressTool } from './tools/press';
import { InflateTool, MassTool, PinTool } from './tools/paint';
import { SketchTool } from './tools/sketch';
import { download, exportShape, type ExportFormat } from './io/export';
import { askImport } from './io/dialog';
import { rememberedUp, rememberUp } from './io/upaxis';
import { baseName } from './project';
import { sig3, volumeText } from './format';
import { boxCentre, isSymmetric, meanEdge, type Axes, type Symmetry } from './tools/symmetry';
import { divergingColor } from './tools/brush';
import { BrushCursor, clampRadius, clampStrength } from './tools/cursor';
import { supersede } from './supersede';
import { brushUnit, rescaleBrush } from './tools/scale';

const CAMERA_KEY = 'softsculpt.camera';
/** A model is symmetric if its mirror image matches it to this fraction of its mean edge length. */
const SYMMETRY_TOLERANCE = 0.75;
/** Tools that act through the simulation's steps (nothing happens while paused). */
const ACTS_WHILE_PLAYING = new Set(['grab', 'press', 'inflate', 'mass']);

export class App implements ToolContext {
  readonly viewport: Viewport;
  readonly brush = { radius: 0.35 };
  readonly mirror = new Mirror();
  readonly tools: ToolManager;
  readonly plots: Plots;
  readonly hud: Hud;
  wireframe = false;
  /** Mirror symmetry axes (X, Y, Z) for every tool; X turns on for a model symmetric across x. */
  readonly symmetryAxes: Axes = [false, false, false];
  /** The strain view: springs' stretch as colours (blue compressed, red stretched). */
  strainView = false;
  /** The brush ring under the cursor and the radius/strength adjusting (B, Shift+B). */
  readonly cursor: BrushCursor;
  private adjustText: string | null = null;
  private readonly client: SimulationClient;
  /** A frame received and not drawn yet. */
  private pending: Frame | null = null;
  /** When the last frame arrived (performance.now(), ms): the HUD says when steps stall (view/pace.ts). */
  private frameArrived = performance.now();
  /** The buffer drawn before the current one, to hand back after rendering. */
  private drawn: Float32Array | null = null;
  private busyLabel: string | null = null;
  private listeners: (() => void)[] = [];
  private lastMessage = '';
  private onReady: (() => void) | null = null;
  /** The model the view was last framed on, with its load's serial (null: none yet). */
  private framedModel: string | null = null;
  /** Where the symmetry axes came from: a restored session's page state, or the model. */
  private symmetryFrom: 'ui' | 'model' = 'model';

  constructor(canvas: HTMLCanvasElement, plotCanvas: HTMLCanvasElement, hudRoot: HTMLElement, helpText: string, wasmUrl: string) {
    this.viewport = new Viewport(canvas);
    this.plots = new Plots(plotCanvas);
    this.hud = new Hud(hudRoot, helpText);
    this.viewport.rig.onSettled(() => this.saveCamera());
    const tools: Tool[] = [new GrabTool(), new PressTool(), new InflateTool(), new MassTool(), new PinTool(), new SketchTool()];
    this.tools = new ToolManager(this, tools, () => { this.refreshOverlay(); this.sendUi(); this.changed(); },
      () => this.busyLabel === null && this.mirror.ready, (t) => this.mayAct(t));
    this.cursor = new BrushCursor(this, (text) => { this.adjustText = text; if (text === null) this.sendUi(); });
    this.client = new SimulationClient(wasmUrl, {
      reply: (r) => this.onReply(r),
      // A worker that cannot be restarted: the message stays (the page needs a reload).
      failed: (text, final) => { this.setBusy(null); this.message(text, 'error', final); },
    });
  }

  /** Start the simulation worker (opening the autosave, else the mushroom); `ready` runs at the first frame drawn. */
  start(ready: () => void): void {
    this.onReady = ready;
    this.client.start(true);
  }

  body(): Mirror { return this.mirror; }
  /** Body `k`'s positions as drawn (0: the first; an import's pieces, a scene's bodies follow). */
  positionsOf(k: number): ArrayLike<number> { return k === 0 ? this.mirror.positions : this.mirror.shapes()[k]?.positions ?? this.mirror.positions; }
  /** Symmetry for a stroke starting now on body `k`: the chosen axes through that body's box centre (each piece mirrors about itself, as Blender's objects about their own origin). */
  symmetry(k = 0): Symmetry | undefined {
    if (!this.symmetryAxes.some(Boolean)) return undefined;
    return { axes: [...this.symmetryAxes] as Axes, centre: boxCentre(this.positionsOf(k)) };
  }
  setSymmetry(axis: 0 | 1 | 2, on: boolean): void {
    this.symmetryAxes[axis] = on;
    this.cursor.poke();
    this.sendUi();
    this.changed();
  }
  /** Brush radius × `f` (keys [ and ]), within its range. */
  scaleRadius(f: number): void {
    this.brush.radius = clampRadius(this.brush.radius * f);
    this.cursor.poke();
    this.sendUi();
  }
  /** The active tool's strength × `f` (keys { and }), within its range. */
  scaleStrength(f: number): void {
    const t = this.tools.tool;
    if (!t.strengthInfo) { this.message(`the ${t.label.toLowerCase()} has no strength`); return; }
    t.strength = clampStrength(t, t.strength * f);
    this.cursor.poke();
    this.sendUi();
    this.message(`${t.label.toLowerCase()} ${t.strengthInfo.label}: ${sig3(t.strength)}`);
  }
  setStrainView(on: boolean): void {
    this.strainView = on;
    this.setSettings({ strain: on });
    this.refreshOverlay();
  }
  send(cmd: Command, transfer: Transferable[] = []): void { this.client.send(cmd, transfer); }

  /** Called whenever the mirrored state changed (the panel refreshes itself). */
  onChange(f: () => void): void { this.listeners.push(f); }
  private changed(): void { for (const f of this.listeners) f(); }

  /** The long operation under way in the worker ("subdividing"…), or null. */
  get busy(): string | null { return this.busyLabel; }

  /**
   * Whether `tool` can act now: the grab, press and the growing brushes act through the
   * simulation's steps, so while paused they would do nothing (and leave an empty undo step).
   */
  private mayAct(tool: Tool): boolean {
    if (this.mirror.settings.playing || !ACTS_WHILE_PLAYING.has(tool.name)) return true;
    this.message(`paused: the ${tool.label.toLowerCase()} acts while the simulation plays — press Space to play`, 'warn');
    return false;
  }

  /** Send a modeling operation, unless a long one is still running (then say so). */
  private operate(cmd: Command, transfer: Transferable[] = []): void {
    if (this.busyLabel) { this.message(`still ${this.busyLabel}… try again when it is done`, 'warn'); return; }
    this.send(cmd, transfer);
  }

  // ----- operations (each is a command to the worker) -------------------------------------------

  loadBuiltin(name: string): void { this.operate({ type: 'loadBuiltin', name }); }
  importFile(name: string, data: ArrayBuffer): void { this.operate({ type: 'import', name, data, upAnswers: rememberedUp() }, [data]); }
  /** Turn the imported model to another up axis (a wrong guess fixed), remembered for its file. */
  setUpAxis(up: 'y' | 'z'): void {
    const frame = this.mirror.settings.frame;
    rememberUp(frame?.file, frame?.format, up);
    this.operate({ type: 'setUp', up });
  }
  openProjectFile(name: string, text: string): void { this.operate({ type: 'openProject', name, text }); }
  openScene(name: string, text: string, files: Map<string, Uint8Array>): void { this.operate({ type: 'openScene', name, text, files }); }
  restartScene(): void { this.operate({ type: 'restartScene' }); }
  saveScene(): void { this.send({ type: 'saveScene' }); }
  saveProject(): void { this.send({ type: 'saveProject', ui: this.ui() }); }
  freeze(): void { this.operate({ type: 'freeze' }); }
  reset(): void { this.operate({ type: 'reset' }); }
  subdivide(): void { this.operate({ type: 'subdivide' }); }
  remesh(): void { this.operate({ type: 'remesh' }); }
  undo(): void { if (!this.tools.isDragging) this.operate({ type: 'undo' }); }
  redo(): void { if (!this.tools.isDragging) this.operate({ type: 'redo' }); }
  step(): void { this.send({ type: 'step' }); }
  /** Set a parameter by its table id (see `mirror.table`). */
  setParam(name: import('./engine/params').ParamId, value: ParamValue): void { this.send({ type: 'setParam', name, value }); }
  setMass(total: number): void { this.send({ type: 'setMass', total }); }
  /** Change settings (play, dt, real time, steps per frame); the mirror follows at once. */
  setSettings(patch: Partial<Settings>): void {
    Object.assign(this.mirror.settings, patch);
    this.send({ type: 'settings', patch });
  }
  togglePlaying(): void {
    this.setSettings({ playing: !this.mirror.settings.playing });
    this.message(this.mirror.settings.playing ? 'playing' : 'paused');
  }

  /** Wind blowing along the current view direction at `strength` m/s (0: calm); undoable. */
  windFromView(strength: number): void {
    const d = this.viewport.camera.getWorldDirection(new Vector3());
    this.send({ type: 'wind', direction: [d.x, d.y, d.z], strength });
  }
  get windStrength(): number {
    return Math.hypot(...this.wind);
  }
  /** The wind velocity (m/s). */
  get wind(): [number, number, number] {
    const w = this.mirror.params.wind;
    return Array.isArray(w) ? w : [0, 0, 0];
  }

  /** Download the shapes as drawn (every body), in the imported file's units and frame. */
  async export(format: ExportFormat): Promise<void> {
    const shapes = this.mirror.shapes();
    const blob = await exportShape(format, shapes, undefined, this.mirror.settings.frame);
    const name = `${baseName(this.mirror.settings.model)}.${format}`;
    download(blob, name);
    // What the file holds: every body (a new-user trial saw one body's counts for a file of two).
    const vertices = shapes.reduce((n, s) => n + s.positions.length / 3, 0);
    const faces = shapes.reduce((n, s) => n + s.triangles.length / 3, 0);
    const bodies = shapes.length > 1 ? ` in ${shapes.length} bodies` : '';
    this.message(`exported ${name}: ${vertices} vertices, ${faces} faces${bodies} (${sig3(blob.size / 1024)} KB, in your downloads)`);
  }
  /** Start or stop recording (io: worker/recorder.ts); export the recording as GLB morph targets. */
  record(on = !this.mirror.recording): void { this.send({ type: 'record', on }); }
  exportRecording(): void { this.send({ type: 'exportRecording' }); }

  ui(): UiState {
    const ui: UiState = { brush: { ...this.brush }, tool: this.tools.tool.name, strengths: Object.fromEntries(this.tools.tools.map((t) => [t.name, t.strength])), symmetry: [...this.symmetryAxes] as Axes };
    if (this.materialName) ui.material = this.materialName;
    return ui;
  }
  /** The material's name the panel shows ('' before it knows); kept in projects (UiState.material). */
  materialName = '';
  /** A material name from an opened project or session, for the panel to give the model that arrives with it. */
  materialFromUi: string | null = null;
  /** Tell the worker the tool state (kept in project files and the autosave). */
  sendUi(): void { this.send({ type: 'ui', ui: this.ui() }); }

  private applyUi(ui: Partial<UiState>): void {
    brushUnit.tookUi({ radius: !!ui.brush, strengths: !!ui.strengths }); // page leftovers (#10): saved lengths are in the next model's units
    if (ui.brush) this.brush.radius = ui.brush.radius;
    // Clamped to the slider's range: an older project's strength may be in another unit (the
    // press was a pressure in Pa before it was a depth in m).
    for (const t of this.tools.tools) {
      const v = ui.strengths?.[t.name];
      // (A length is in the units of the model that follows, whose range is not known yet.)
      if (typeof v === 'number' && t.strengthInfo) t.strength = t.isLength ? v : Math.min(Math.max(v, t.strengthInfo.min), t.strengthInfo.max);
    }
    if (ui.tool) this.tools.select(ui.tool);
    if (typeof ui.material === 'string') this.materialFromUi = ui.material;
    if (Array.isArray(ui.symmetry) && ui.symmetry.length === 3) {
      ui.symmetry.forEach((v, d) => (this.symmetryAxes[d] = v === true));
      this.symmetryFrom = 'ui';
    }
    this.changed();
  }

  // ----- replies --------------------------------------------------------------------------------

  private onReply(r: Reply): void {
    switch (r.type) {
      case 'frame':
        this.frameArrived = performance.now();
        if (this.pending) {
          // Not drawn yet and already superseded: what it brought that the new one lacks carries
          // over, and its buffer goes straight back to the worker.
          r.frame = supersede(this.pending, r.frame);
          this.giveBack(this.pending.positions);
        }
        this.pending = r.frame;
        return;
      case 'message': return this.message(r.text, r.kind);
      case 'progress': return this.setBusy(r.label, r.fraction);
      case 'download': return download(new Blob([r.bytes ? (r.bytes as Uint8Array<ArrayBuffer>) : r.text], { type: r.mime }), r.filename);
      case 'importQuestion': void askImport(r.question).then((answer) => {
        // The user's up axis for this file settles its guess when it comes again (io/upaxis.ts).
        if (answer && r.question.declaredUp === null) rememberUp(r.question.name, r.question.format, answer.up);
        this.send({ type: 'importAnswer', answer });
      }); return;
      case 'ui': return this.applyUi(r.ui);
      case 'fatal': this.message(r.text, 'error', true); return;
    }
  }

  private setBusy(label: string | null, fraction?: number): void {
    this.busyLabel = label;
    this.hud.progress(label, fraction);
  }

  private giveBack(buffer: Float32Array): void {
    if (buffer.buffer.byteLength > 0) this.send({ type: 'returnBuffer', buffer: buffer.buffer as ArrayBuffer }, [buffer.buffer as ArrayBuffer]);
  }

  private applyFrame(f: Frame): void {
    const m = this.mirror;
    const wasRecording = m.recording !== null;
    const old = m.apply(f);
    if (f.topology) {
      this.viewport.attach(m.triangles, m.springs, m.positions);
      this.viewport.measureModel();
      // (pieces) Every body is the model: the view frames an import's pieces (a scene's bodies) together.
      if (m.others.length > 0) {
        const sphere = new Box3().setFromArray(m.all).getBoundingSphere(new Sphere());
        if (Number.isFinite(sphere.radius) && sphere.radius > 0) this.viewport.rig.setModel(sphere.center, sphere.radius);
      }
      // page leftovers (#10): the brush's lengths follow the model's size (tools/scale.ts).
      rescaleBrush(this.brush, this.tools.tools, brushUnit.model(this.viewport.modelRadius));
      // Another model (loaded, imported, opened): framed in the view. The same model changed
      // (subdivided, undone) keeps the user's view.
      // A load (even of a file of the old one's name) has its own serial (settings.opened).
      const model = `${m.settings.model}#${m.settings.opened ?? ''}`;
      if (model !== this.framedModel) {
        if (this.framedModel !== null) this.hud.clearMessages();
        // A new model: X symmetry on if it is symmetric across x (the first model keeps a
        // restored session's choice).
        if (this.framedModel !== null || this.symmetryFrom !== 'ui') this.symmetryAxes.splice(0, 3, isSymmetric(m.positions, 0, SYMMETRY_TOLERANCE * meanEdge(m.positions, m.springs)), false, false);
        if (this.framedModel !== null || !this.restoreCamera()) this.viewport.resetView();
        this.framedModel = model;
      }
      this.viewport.extras.setBodies(m.others);
      this.viewport.extras.setObstacles(m.obstacles);
      this.plots.clear();
    } else {
      this.viewport.update(m.positions);
    }
    this.viewport.extras.update(m.all, m.positions.length);
    if (f.topology || f.body || (this.strainView && f.strain)) this.refreshOverlay();
    if (f.params) this.syncScene();
    this.plots.push(m.stats.time, [m.stats.volume, m.stats.pressure, m.stats.kinetic, m.stats.elastic, m.stats.gas]);
    if (f.topology || f.body || f.params || f.table || f.settings || f.history || (m.recording !== null) !== wasRecording) this.changed();
    if (old) this.drawn = old;
    if (!m.ready) {
      m.ready = true;
      this.onReady?.();
    }
  }

  // ----- the frame ------------------------------------------------------------------------------

  refreshOverlay(): void {
    const t = this.tools.tool;
    const m = this.mirror;
    if (this.strainView && m.strain.length === m.vertexCount) { this.viewport.setColors((c) => strainColors(c, m.strain)); return; }
    this.viewport.setColors(t.overlay && m.masses.length === m.vertexCount ? (c) => t.overlay!(c, m) : null);
  }

  syncScene(): void {
    const p = this.mirror.params;
    this.viewport.setGround(p.ground === true, typeof p['ground.height'] === 'number' ? p['ground.height'] : 0);
    this.viewport.setWind(this.wind);
    this.viewport.springs.visible = this.wireframe;
  }

  /** Every animation frame: draw the newest frame from the worker, then hand the previous buffer back. */
  frame(): void {
    const f = this.pending;
    this.pending = null;
    if (f) this.applyFrame(f);
    const m = this.mirror, s = m.stats;
    this.hud.tick(f !== null);
    if (m.ready) {
      // How fast the simulation goes comes first (the drawing's fps can be high while it crawls).
      const pace = paceText({ playing: m.settings.playing, busy: this.busyLabel !== null, slowMotion: m.slowMotion, realTimeFraction: m.realTimeFraction, accuracy: m.accuracy, sinceFrameMs: performance.now() - this.frameArrived });
      this.hud.show([
        `simulation: ${pace}   ${m.simMs.toFixed(1)} ms of steps/frame${m.threads > 1 ? ` on ${m.threads} threads` : ''}   ${viewText(this.hud.fps, this.hud.shapesPerSecond, m.slowMotion)}` +
          (m.recording ? `   ● REC ${m.recording.frames} frames, ${m.recording.seconds.toFixed(1)} s` : ''),
        `${m.vertexCount} vertices   ${m.springCount} springs   ${m.faceCount} faces   tool: ${this.tools.tool.label}`,
        `t ${s.time.toFixed(2)} s   ${volumeText(s.volume, m.closed)}   P ${sig3(s.pressure)} Pa   max speed ${sig3(s.maxSpeed)} m/s`,
        ...(this.windStrength > 0 ? [windLine(this.wind, this.viewport.camera)] : []),
        ...(m.scene ? [sceneLine(m.scene)] : []),
      ]);
      this.hud.setState(this.adjustText ?? (!m.settings.playing ? 'Paused — Space to play' : null));
      if (f) this.plots.draw();
    }
    this.cursor.update(f !== null);
    this.viewport.render();
    if (this.drawn) { this.giveBack(this.drawn); this.drawn = null; }
  }

  /** The camera as the user left it (kept across reloads, like the model). */
  private restoreCamera(): boolean {
    try {
      const s = JSON.parse(localStorage.getItem(CAMERA_KEY) ?? 'null');
      if (!s || !Array.isArray(s.position) || !Array.isArray(s.target)) return false;
      this.viewport.rig.restore(s);
      return true;
    } catch { return false; }
  }
  saveCamera(): void {
    try { localStorage.setItem(CAMERA_KEY, JSON.stringify(this.viewport.rig.state())); } catch { /* private mode: not kept */ }
  }

  /** Show a message (`sticky`: it stays until clicked; others go by themselves, view/hud.ts). */
  message(text: string, kind: MessageKind = 'info', sticky = false): void {
    this.lastMessage = text;
    this.hud.message(text, kind, sticky);
  }
  get lastMessageText(): string { return this.lastMessage; }
}

/**
 * The wind as seen from the camera (its 3D arrow is end-on when it blows along the view, as W
 * makes it): speed, an arrow for its direction across the screen, and whether it blows away from
 * or towards the viewer.
 */
export function windLine(w: [number, number, number], camera: Camera): string {
  const v = new Vector3(...w);
  const speed = v.length();
  v.transformDirection(camera.matrixWorldInverse);
  const across = Math.hypot(v.x, v.y);
  const arrows = ['→', '↗', '↑', '↖', '←', '↙', '↓', '↘'];
  const arrow = across > 0.2 ? arrows[(Math.round(Math.atan2(v.y, v.x) / (Math.PI / 4)) + 8) % 8] : '';
  const depth = v.z < -0.5 ? ' away from you' : v.z > 0.5 ? ' towards you' : '';
  return `wind ${sig3(speed)} m/s ${arrow}${arrow && depth ? ' and' : ''}${depth}`;
}

/** Strain → colour: 0 white, ±STRAIN_FULL and beyond full red (stretched) or blue (compressed). */
export const STRAIN_FULL = 0.1;
export function strainColors(colors: Float32Array, strain: Float32Array): void {
  for (let i = 0; i < strain.length; i++) divergingColor(colors, i, strain[i] / STRAIN_FULL);
}

