// The page's mirror of the simulation: the latest frame drawn and the state that came with it
// (topology, masses and pins, parameters, settings, history sizes). The viewport, the tools'
// picking and overlays, the panel, the HUD and `window.softsculpt` all read it; it is only ever
// written by `apply`, one frame at a time, so what it holds is always one consistent frame.

import type { Frame, Obstacle, ParamInfo, Params, Recording, SceneInfo, Settings, Stats, Topology } from './protocol';
import type { Shape } from './io/export';
import type { BodyView } from './tools/tool';

const NO_STATS: Stats = {
  step: 0, time: 0, volume: 0, pressure: 0, kinetic: 0, elastic: 0, gas: 0, gravity: 0, total: 0,
  momentum: [0, 0, 0], centerOfMass: [0, 0, 0], maxSpeed: 0,
};

const NO_STRAIN = new Float32Array(0);

/** How long the HUD keeps showing a time-limited step's accuracy after the last such frame (ms). */
export const ACCURACY_HOLD_MS = 1000;

export class Mirror implements BodyView {
  /** The first frame of a model has been drawn. */
  ready = false;
  /** The frame buffer being drawn: the active body's xyz, then the other bodies'. */
  all: Float32Array = new Float32Array(0);
  /** The active body's positions (a view into `all`). */
  positions: Float32Array = new Float32Array(0);
  triangles: Uint32Array = new Uint32Array(0);
  springs: Uint32Array = new Uint32Array(0);
  others: Topology['others'] = [];
  obstacles: Obstacle[] = [];
  masses: Float64Array = new Float64Array(0);
  pinned: Uint8Array = new Uint8Array(0);
  stats: Stats = NO_STATS;
  simMs = 0;
  slowMotion = false;
  realTimeFraction = 1;
  /**
   * The accuracy the last time-limited steps reached (relative residual, `Frame.accuracy`),
   * held for ACCURACY_HOLD_MS after the last frame that reported one (so the HUD does not
   * flicker between frames that converged and frames that did not); 0: converged.
   */
  accuracy = 0;
  private accuracyAt = -Infinity;
  scene: SceneInfo | null = null;
  /** Every parameter of the active body and the world by table id (an object the panel may bind to: updated in place). */
  readonly params: Params = {};
  /** The engine's parameter table: ids, units, ranges, help (empty until the first frame). */
  table: ParamInfo[] = [];
  /** The core's material presets (name, help). */
  presets: { name: string; help: string }[] = [];
  /** Threads the engine steps on. */
  threads = 1;
  /** The simulation's settings (updated in place; the panel binds to it). */
  readonly settings: Settings = { dt: 1e-3, substeps: 16, realTime: true, playing: true, keepTension: false, model: 'mushroom' };
  history: [number, number] = [0, 0];
  /** The active body's surface is closed (open: cloth-like, no gas). */
  closed = true;
  /** A recording under way, or null. */
  recording: Recording | null = null;
  /** Each vertex's strain l / L − 1 (when the strain view is on), else empty. */
  strain: Float32Array = NO_STRAIN;

  get vertexCount(): number { return this.positions.length / 3; }
  get faceCount(): number { return this.triangles.length / 3; }
  get springCount(): number { return this.springs.length / 2; }
  get totalMass(): number { return this.masses.reduce((a, b) => a + b, 0); }

  /** Take a frame; returns the buffer it replaces (drawn already: hand it back to the worker). */
  apply(f: Frame): Float32Array | null {
    const old = this.all.byteLength > 0 ? this.all : null;
    if (f.topology) {
      this.triangles = f.topology.triangles;
      this.springs = f.topology.springs;
      this.others = f.topology.others;
      this.obstacles = f.topology.obstacles;
      this.positions = f.positions.subarray(0, 3 * f.topology.vertexCount);
      this.closed = f.topology.closed ?? true;
    } else {
      this.positions = f.positions.subarray(0, this.positions.length);
    }
    this.all = f.positions;
    if (f.body) { this.masses = f.body.masses; this.pinned = f.body.pinned; }
    if (f.params) Object.assign(this.params, f.params);
    if (f.table) this.table = f.table;
    if (f.presets) this.presets = f.presets;
    if (f.threads) this.threads = f.threads;
    if (f.settings) Object.assign(this.settings, f.settings);
    if (f.history) this.history = f.history;
    this.strain = f.strain ?? NO_STRAIN;
    this.stats = f.stats;
    this.simMs = f.simMs;
    this.slowMotion = f.slowMotion;
    this.realTimeFraction = f.realTimeFraction;
    const now = performance.now();
    if (f.accuracy > 0) { this.accuracy = f.accuracy; this.accuracyAt = now; } else if (now - this.accuracyAt > ACCURACY_HOLD_MS) this.accuracy = 0;
    this.scene = f.scene;
    this.recording = f.recording ?? null;
    return old;
  }

  /** Every body's shape as drawn: the active body, then the others. */
  shapes(): Shape[] {
    const out: Shape[] = [{ positions: this.positions, triangles: this.triangles }];
    let at = this.positions.length;
    for (const o of this.others) { out.push({ positions: this.all.subarray(at, at + 3 * o.vertexCount), triangles: o.triangles }); at += 3 * o.vertexCount; }
    return out;
  }
}
