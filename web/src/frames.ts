// The worker's frames on the page. A frame (worker/frames.ts) brings the latest positions in a
// transferred buffer: the newest is kept until the next animation frame (one superseded before
// it was drawn hands what it brought on, supersede.ts, and its buffer straight back); then it
// replaces the drawn positions in the mirror, the view renders them, and the buffer drawn before
// goes back to the worker. A new mesh is attached to the view, and another model framed (the
// camera where the user left it for the page's first, view/camerastore.ts), with X symmetry on
// if the model is symmetric across x.

import { Box3, Sphere } from 'three';
import type { Axes } from './tools/symmetry';
import { isSymmetric, meanEdge } from './tools/symmetry';
import type { Command, Frame } from './protocol';
import type { Mirror } from './mirror';
import type { Viewport } from './view/viewport';
import type { Hud } from './view/hud';
import type { Plots } from './view/plots';
import type { ToolManager } from './tools/manager';
import type { BrushCursor } from './tools/cursor';
import { divergingColor } from './tools/brush';
import { brushUnit, rescaleBrush } from './tools/scale';
import { supersede } from './supersede';
import { restoreCamera } from './view/camerastore';
import { readoutLines } from './view/readout';

/** A model is symmetric if its mirror image matches it to this fraction of its mean edge length. */
const SYMMETRY_TOLERANCE = 0.75;

/** What the frames draw into and read from: the page (app.ts `App`). */
export interface FrameHost {
  readonly mirror: Mirror;
  readonly viewport: Viewport;
  readonly hud: Hud;
  readonly plots: Plots;
  readonly brush: { radius: number };
  readonly tools: ToolManager;
  readonly cursor: BrushCursor;
  readonly symmetryAxes: Axes;
  readonly strainView: boolean;
  readonly wireframe: boolean;
  readonly wind: [number, number, number];
  readonly busy: string | null;
  send(cmd: Command, transfer?: Transferable[]): void;
}

/** What the frames tell the page. */
export interface FrameHooks {
  /** The mirrored state changed (the panel refreshes itself). */
  changed(): void;
  /** The first frame was drawn. */
  ready(): void;
  /** The brush radius or strength being adjusted (B, Shift+B), shown in place of the paused banner; null if none. */
  adjusting(): string | null;
}

export class Frames {
  /** A frame received and not drawn yet. */
  private pending: Frame | null = null;
  /** When the last frame arrived (performance.now(), ms): the HUD says when steps stall (view/pace.ts). */
  private arrived = performance.now();
  /** The buffer drawn before the current one, to hand back after rendering. */
  private drawn: Float32Array | null = null;
  /** The model the view was last framed on, with its load's serial (null: none yet). */
  private framedModel: string | null = null;
  /** Where the symmetry axes came from: a restored session's page state, or the model. */
  private symmetryFrom: 'ui' | 'model' = 'model';

  constructor(private readonly page: FrameHost, private readonly hooks: FrameHooks) {}

  /** The symmetry axes came with a restored session's page state: the first model keeps them. */
  symmetryFromUi(): void { this.symmetryFrom = 'ui'; }

  /** A frame from the worker, kept until the next animation frame. */
  receive(frame: Frame): void {
    this.arrived = performance.now();
    if (this.pending) {
      // Not drawn yet and already superseded: what it brought that the new one lacks carries
      // over, and its buffer goes straight back to the worker.
      frame = supersede(this.pending, frame);
      this.giveBack(this.pending.positions);
    }
    this.pending = frame;
  }

  /** Every animation frame: draw the newest frame from the worker, then hand the previous buffer back. */
  frame(): void {
    const page = this.page;
    const f = this.pending;
    this.pending = null;
    if (f) this.apply(f);
    const m = page.mirror;
    page.hud.tick(f !== null);
    if (m.ready) {
      page.hud.show(readoutLines(m, {
        busy: page.busy !== null, sinceFrameMs: performance.now() - this.arrived, fps: page.hud.fps, shapesPerSecond: page.hud.shapesPerSecond,
        toolLabel: page.tools.tool.label, wind: page.wind, camera: page.viewport.camera,
      }));
      page.hud.setState(this.hooks.adjusting() ?? (!m.settings.playing ? 'Paused — Space to play' : null));
      if (f) page.plots.draw();
    }
    page.cursor.update(f !== null);
    page.viewport.render();
    if (this.drawn) { this.giveBack(this.drawn); this.drawn = null; }
  }

  /** The colours over the model: the strain view, else the tool's overlay (masses, pins), else none. */
  refreshOverlay(): void {
    const { tools, mirror: m, viewport } = this.page;
    const t = tools.tool;
    if (this.page.strainView && m.strain.length === m.vertexCount) { viewport.setColors((c) => strainColors(c, m.strain)); return; }
    viewport.setColors(t.overlay && m.masses.length === m.vertexCount ? (c) => t.overlay!(c, m) : null);
  }

  /** The ground, the wind arrow and the springs as the parameters and the display say. */
  syncScene(): void {
    const { mirror, viewport } = this.page;
    const p = mirror.params;
    viewport.setGround(p.ground === true, typeof p['ground.height'] === 'number' ? p['ground.height'] : 0);
    viewport.setWind(this.page.wind);
    viewport.springs.visible = this.page.wireframe;
  }

  private giveBack(buffer: Float32Array): void {
    if (buffer.buffer.byteLength > 0) this.page.send({ type: 'returnBuffer', buffer: buffer.buffer as ArrayBuffer }, [buffer.buffer as ArrayBuffer]);
  }

  private apply(f: Frame): void {
    const { mirror: m, viewport, plots } = this.page;
    const wasRecording = m.recording !== null;
    const old = m.apply(f);
    if (f.topology) {
      this.newMesh();
    } else {
      viewport.update(m.positions);
    }
    viewport.extras.update(m.all, m.positions.length);
    if (f.topology || f.body || (this.page.strainView && f.strain)) this.refreshOverlay();
    if (f.params) this.syncScene();
    plots.push(m.stats.time, [m.stats.volume, m.stats.pressure, m.stats.kinetic, m.stats.elastic, m.stats.gas]);
    if (f.topology || f.body || f.params || f.table || f.settings || f.history || (m.recording !== null) !== wasRecording) this.hooks.changed();
    if (old) this.drawn = old;
    if (!m.ready) {
      m.ready = true;
      this.hooks.ready();
    }
  }

  /** A frame with another mesh: attached to the view, the brush fitted to it, another model framed. */
  private newMesh(): void {
    const { mirror: m, viewport, hud, plots, brush, tools, symmetryAxes } = this.page;
    viewport.attach(m.triangles, m.springs, m.positions);
    viewport.measureModel();
    // (pieces) Every body is the model: the view frames an import's pieces (a scene's bodies) together.
    if (m.others.length > 0) {
      const sphere = new Box3().setFromArray(m.all).getBoundingSphere(new Sphere());
      if (Number.isFinite(sphere.radius) && sphere.radius > 0) viewport.rig.setModel(sphere.center, sphere.radius);
    }
    // page leftovers (#10): the brush's lengths follow the model's size (tools/scale.ts).
    rescaleBrush(brush, tools.tools, brushUnit.model(viewport.modelRadius));
    // Another model (loaded, imported, opened): framed in the view. The same model changed
    // (subdivided, undone) keeps the user's view.
    // A load (even of a file of the old one's name) has its own serial (settings.opened).
    const model = `${m.settings.model}#${m.settings.opened ?? ''}`;
    if (model !== this.framedModel) {
      if (this.framedModel !== null) hud.clearMessages();
      // A new model: X symmetry on if it is symmetric across x (the first model keeps a
      // restored session's choice).
      if (this.framedModel !== null || this.symmetryFrom !== 'ui') symmetryAxes.splice(0, 3, isSymmetric(m.positions, 0, SYMMETRY_TOLERANCE * meanEdge(m.positions, m.springs)), false, false);
      if (this.framedModel !== null || !restoreCamera(viewport.rig)) viewport.resetView();
      this.framedModel = model;
    }
    viewport.extras.setBodies(m.others);
    viewport.extras.setObstacles(m.obstacles);
    plots.clear();
  }
}

/** Strain → colour: 0 white, ±STRAIN_FULL and beyond full red (stretched) or blue (compressed). */
export const STRAIN_FULL = 0.1;
export function strainColors(colors: Float32Array, strain: Float32Array): void {
  for (let i = 0; i < strain.length; i++) divergingColor(colors, i, strain[i] / STRAIN_FULL);
}
