// The modeler's page: the view, the tools, the panel's operations, the HUD and plots. The
// simulation and the document run in a worker (src/worker/); the page sends it commands
// (src/protocol.ts) and draws the frames it sends back, so drawing, the camera and the panel
// never wait for the engine.
//
// A frame: the worker's latest positions (a transferred buffer) replace the drawn ones, the view
// renders them, and the buffer drawn before goes back to the worker.

import { Vector3 } from 'three';
import type { Command, Frame, MessageKind, ParamValue, Reply, Settings, UiState } from './protocol';
import { SimulationClient } from './client';
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
import { baseName } from './project';

export class App implements ToolContext {
  readonly viewport: Viewport;
  readonly brush = { radius: 0.35 };
  readonly mirror = new Mirror();
  readonly tools: ToolManager;
  readonly plots: Plots;
  readonly hud: Hud;
  wireframe = false;
  private readonly client: SimulationClient;
  /** A frame received and not drawn yet. */
  private pending: Frame | null = null;
  /** The buffer drawn before the current one, to hand back after rendering. */
  private drawn: Float32Array | null = null;
  private busyLabel: string | null = null;
  private listeners: (() => void)[] = [];
  private lastMessage = '';
  private onReady: (() => void) | null = null;

  constructor(canvas: HTMLCanvasElement, plotCanvas: HTMLCanvasElement, hudRoot: HTMLElement, helpText: string, wasmUrl: string) {
    this.viewport = new Viewport(canvas);
    this.plots = new Plots(plotCanvas);
    this.hud = new Hud(hudRoot, helpText);
    const tools: Tool[] = [new GrabTool(), new PressTool(), new InflateTool(), new MassTool(), new PinTool(), new SketchTool()];
    this.tools = new ToolManager(this, tools, () => { this.refreshOverlay(); this.sendUi(); this.changed(); }, () => this.busyLabel === null && this.mirror.ready);
    this.client = new SimulationClient(wasmUrl, {
      reply: (r) => this.onReply(r),
      failed: (text) => { this.setBusy(null); this.message(text, 'error'); },
    });
  }

  /** Start the simulation worker (opening the autosave, else the mushroom); `ready` runs at the first frame drawn. */
  start(ready: () => void): void {
    this.onReady = ready;
    this.client.start(true);
  }

  body(): Mirror { return this.mirror; }
  send(cmd: Command, transfer: Transferable[] = []): void { this.client.send(cmd, transfer); }

  /** Called whenever the mirrored state changed (the panel refreshes itself). */
  onChange(f: () => void): void { this.listeners.push(f); }
  private changed(): void { for (const f of this.listeners) f(); }

  /** The long operation under way in the worker ("subdividing"…), or null. */
  get busy(): string | null { return this.busyLabel; }

  /** Send a modeling operation, unless a long one is still running (then say so). */
  private operate(cmd: Command, transfer: Transferable[] = []): void {
    if (this.busyLabel) { this.message(`still ${this.busyLabel}… try again when it is done`, 'warn'); return; }
    this.send(cmd, transfer);
  }

  // ----- operations (each is a command to the worker) -------------------------------------------

  loadBuiltin(name: string): void { this.operate({ type: 'loadBuiltin', name }); }
  importFile(name: string, data: ArrayBuffer): void { this.operate({ type: 'import', name, data }, [data]); }
  openProjectFile(name: string, text: string): void { this.operate({ type: 'openProject', name, text }); }
  openScene(name: string, text: string, files: Map<string, Uint8Array>): void { this.operate({ type: 'openScene', name, text, files }); }
  restartScene(): void { this.operate({ type: 'restartScene' }); }
  saveScene(): void { this.send({ type: 'saveScene' }); }
  saveProject(): void { this.send({ type: 'saveProject', ui: this.ui() }); }
  freeze(): void { this.operate({ type: 'freeze' }); }
  reset(): void { this.operate({ type: 'reset' }); }
  subdivide(): void { this.operate({ type: 'subdivide' }); }
  undo(): void { if (!this.tools.isDragging) this.operate({ type: 'undo' }); }
  redo(): void { if (!this.tools.isDragging) this.operate({ type: 'redo' }); }
  step(): void { this.send({ type: 'step' }); }
  /** Set a parameter by its table id (see `mirror.table`). */
  setParam(name: string, value: ParamValue): void { this.send({ type: 'setParam', name, value }); }
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

  /** Download the shape as drawn (the latest frame's positions and triangles). */
  async export(format: ExportFormat): Promise<void> {
    const blob = await exportShape(format, this.mirror.positions, this.mirror.triangles);
    download(blob, `${baseName(this.mirror.settings.model)}.${format}`);
  }

  ui(): UiState {
    return { brush: { ...this.brush }, tool: this.tools.tool.name, strengths: Object.fromEntries(this.tools.tools.map((t) => [t.name, t.strength])) };
  }
  /** Tell the worker the tool state (kept in project files and the autosave). */
  sendUi(): void { this.send({ type: 'ui', ui: this.ui() }); }

  private applyUi(ui: Partial<UiState>): void {
    if (ui.brush) this.brush.radius = ui.brush.radius;
    // Clamped to the slider's range: an older project's strength may be in another unit (the
    // press was a pressure in Pa before it was a depth in m).
    for (const t of this.tools.tools) {
      const v = ui.strengths?.[t.name];
      if (typeof v === 'number' && t.strengthInfo) t.strength = Math.min(Math.max(v, t.strengthInfo.min), t.strengthInfo.max);
    }
    if (ui.tool) this.tools.select(ui.tool);
    this.changed();
  }

  // ----- replies --------------------------------------------------------------------------------

  private onReply(r: Reply): void {
    switch (r.type) {
      case 'frame':
        if (this.pending) {
          // Not drawn yet and already superseded: what it brought that the new one lacks carries
          // over, and its buffer goes straight back to the worker.
          const { topology, body, params, table, settings, history } = this.pending;
          r.frame = { topology, body, params, table, settings, history, ...stripUndefined(r.frame) };
          this.giveBack(this.pending.positions);
        }
        this.pending = r.frame;
        return;
      case 'message': return this.message(r.text, r.kind);
      case 'progress': return this.setBusy(r.label, r.fraction);
      case 'download': return download(new Blob([r.text], { type: r.mime }), r.filename);
      case 'ui': return this.applyUi(r.ui);
      case 'fatal': this.message(r.text, 'error'); return;
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
    const old = m.apply(f);
    if (f.topology) {
      this.viewport.attach(m.triangles, m.springs, m.positions);
      this.viewport.extras.setBodies(m.others);
      this.viewport.extras.setObstacles(m.obstacles);
      this.plots.clear();
    } else {
      this.viewport.update(m.positions);
    }
    this.viewport.extras.update(m.all, m.positions.length);
    if (f.topology || f.body) this.refreshOverlay();
    if (f.params) this.syncScene();
    this.plots.push(m.stats.time, [m.stats.volume, m.stats.pressure, m.stats.kinetic, m.stats.elastic, m.stats.gas]);
    if (f.topology || f.body || f.params || f.table || f.settings || f.history) this.changed();
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
    this.hud.tick();
    if (m.ready) {
      this.hud.show([
        `${this.hud.fps.toFixed(0)} fps   sim ${m.simMs.toFixed(1)} ms/frame${m.slowMotion ? `   SLOW MOTION (${(m.realTimeFraction * 100).toFixed(0)}% of real time)` : ''}${m.settings.playing ? '' : '   PAUSED'}`,
        `${m.vertexCount} vertices   ${m.springCount} springs   ${m.faceCount} faces   tool: ${this.tools.tool.label}`,
        `t ${s.time.toFixed(2)} s   V ${s.volume.toFixed(4)} m³   P ${s.pressure.toFixed(2)} Pa   max speed ${s.maxSpeed.toFixed(3)} m/s`,
        ...(m.scene ? [sceneLine(m.scene)] : []),
      ]);
      if (f) this.plots.draw();
    }
    this.viewport.render();
    if (this.drawn) { this.giveBack(this.drawn); this.drawn = null; }
  }

  message(text: string, kind: MessageKind = 'info'): void {
    this.lastMessage = text;
    this.hud.message(text, kind);
  }
  get lastMessageText(): string { return this.lastMessage; }
}

function stripUndefined<T extends object>(o: T): T {
  return Object.fromEntries(Object.entries(o).filter(([, v]) => v !== undefined)) as T;
}
