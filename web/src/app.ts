// The modeler's page: the object the panel, the keys, the tools and the inspector talk to. It
// holds the view, the tools and their shared state (brush, symmetry, strengths: the ToolContext),
// keeps the page's tool state in step with the worker's (UiState), and takes the worker's
// replies. The simulation and the document run in a worker (src/worker/); the page sends it
// commands (commands.ts, src/protocol.ts) and draws the frames it sends back (frames.ts), so
// drawing, the camera and the panel never wait for the engine.

import type { Command, MessageKind, Reply, UiState } from './protocol';
import { SimulationClient } from './client';
import { Mirror } from './mirror';
import { Viewport } from './view/viewport';
import { Plots } from './view/plots';
import { Hud } from './view/hud';
import { ToolManager } from './tools/manager';
import type { Tool, ToolContext } from './tools/tool';
import { GrabTool } from './tools/grab';
import { PressTool } from './tools/press';
import { InflateTool, MassTool, PinTool } from './tools/paint';
import { SketchTool } from './tools/sketch';
import { download } from './io/export';
import { askImport } from './io/dialog';
import { rememberUp } from './io/upaxis';
import { sig3 } from './format';
import { boxCentre, type Axes, type Symmetry } from './tools/symmetry';
import { BrushCursor, clampRadius, clampStrength } from './tools/cursor';
import { brushUnit } from './tools/scale';
import { saveCamera } from './view/camerastore';
import { Commands } from './commands';
import { Frames } from './frames';

export { windLine } from './view/readout';
export { STRAIN_FULL, strainColors } from './frames';

/** Tools that act through the simulation's steps (nothing happens while paused). */
const ACTS_WHILE_PLAYING = new Set(['grab', 'press', 'inflate', 'mass']);

export class App extends Commands implements ToolContext {
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
  /** The material's name the panel shows ('' before it knows); kept in projects (UiState.material). */
  materialName = '';
  /** A material name from an opened project or session, for the panel to give the model that arrives with it. */
  materialFromUi: string | null = null;
  private adjustText: string | null = null;
  private readonly client: SimulationClient;
  private readonly frames: Frames;
  private busyLabel: string | null = null;
  private listeners: (() => void)[] = [];
  private lastMessage = '';
  private onReady: (() => void) | null = null;

  constructor(canvas: HTMLCanvasElement, plotCanvas: HTMLCanvasElement, hudRoot: HTMLElement, helpText: string, wasmUrl: string) {
    super();
    this.viewport = new Viewport(canvas);
    this.plots = new Plots(plotCanvas);
    this.hud = new Hud(hudRoot, helpText);
    this.frames = new Frames(this, { changed: () => this.changed(), ready: () => this.onReady?.(), adjusting: () => this.adjustText });
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

  send(cmd: Command, transfer: Transferable[] = []): void { this.client.send(cmd, transfer); }

  /** Called whenever the mirrored state changed (the panel refreshes itself). */
  onChange(f: () => void): void { this.listeners.push(f); }
  private changed(): void { for (const f of this.listeners) f(); }

  /** The long operation under way in the worker ("subdividing"…), or null. */
  get busy(): string | null { return this.busyLabel; }

  // ----- the tools' context: the body, the brush, symmetry --------------------------------------

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

  /**
   * Whether `tool` can act now: the grab, press and the growing brushes act through the
   * simulation's steps, so while paused they would do nothing (and leave an empty undo step).
   */
  private mayAct(tool: Tool): boolean {
    if (this.mirror.settings.playing || !ACTS_WHILE_PLAYING.has(tool.name)) return true;
    this.message(`paused: the ${tool.label.toLowerCase()} acts while the simulation plays — press Space to play`, 'warn');
    return false;
  }

  // ----- the page's tool state, in step with the worker's ---------------------------------------

  ui(): UiState {
    const ui: UiState = { brush: { ...this.brush }, tool: this.tools.tool.name, strengths: Object.fromEntries(this.tools.tools.map((t) => [t.name, t.strength])), symmetry: [...this.symmetryAxes] as Axes };
    if (this.materialName) ui.material = this.materialName;
    return ui;
  }
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
      this.frames.symmetryFromUi();
    }
    this.changed();
  }

  // ----- replies --------------------------------------------------------------------------------

  private onReply(r: Reply): void {
    switch (r.type) {
      case 'frame': this.frames.receive(r.frame); return;
      case 'message': return this.message(r.text, r.kind);
      case 'progress': return this.setBusy(r.label, r.fraction);
      case 'download': return download(new Blob([r.bytes ? (r.bytes as Uint8Array<ArrayBuffer>) : r.text], { type: r.mime }), r.filename);
      case 'importQuestion': void askImport(r.question).then((answer) => {
        // The user's up axis for this file settles its guess when it comes again (io/upaxis.ts).
        if (answer && r.question.declaredUp === null && !r.question.upSure) rememberUp(r.question.name, r.question.format, answer.up);
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

  // ----- the frame (frames.ts) ------------------------------------------------------------------

  /** The colours over the model: the strain view, else the tool's overlay. */
  refreshOverlay(): void { this.frames.refreshOverlay(); }
  /** The ground, the wind arrow and the springs as the parameters and the display say. */
  syncScene(): void { this.frames.syncScene(); }
  /** Every animation frame: draw the newest frame from the worker, then hand the previous buffer back. */
  frame(): void { this.frames.frame(); }
  /** Keep the camera where it is now (view/camerastore.ts; restored with the page's first model). */
  saveCamera(): void { saveCamera(this.viewport.rig); }

  /** Show a message (`sticky`: it stays until clicked; others go by themselves, view/hud.ts). */
  message(text: string, kind: MessageKind = 'info', sticky = false): void {
    this.lastMessage = text;
    this.hud.message(text, kind, sticky);
  }
  get lastMessageText(): string { return this.lastMessage; }
}
