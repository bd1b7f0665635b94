// World: one small class over one engine world (a handle of crates/softsculpt-wasm). The world
// owns its bodies, settings, clock and an open scene's events; bodies are indices 0, 1, ….
// `body(i)` gives a BodyView whose getters are typed arrays over wasm memory.
//
// Views: a typed array from a BodyView is valid until the next call on any World (a call may grow
// wasm memory, which detaches every view, or replace bodies: add, clear, subdivide, restore,
// openScene, applyDelta, openProjectV1). Get it again after a call — the getters re-make
// the arrays when needed and are cheap otherwise — and never keep one across calls.

import { LAYOUT_LEN, SCOPE, SLOT, STATS_LEN, readStats, type Advance, type DeltaScope, type FileReport, type FreezeReport, type RemeshReport, type Stats } from './abi';
import { errorJson, raw, resultBytes, resultText, view, withArrays, withBytes } from './wasm';

// The JSON reports' types are written from the binding's `reports!` blocks (abi.ts).
export type { Advance, DeltaScope, FileReport, FreezeReport, RemeshReport, Stats };

/** What the engine refused, and why: `kind` is one of the binding's error kinds. */
export class EngineError extends Error {
  readonly kind: 'mesh' | 'parameter' | 'step' | 'snapshot' | 'scene' | 'delta' | 'project' | 'usage';
  /** Every field of the engine's error JSON (time, step, line, parameter, unit, key, …). */
  readonly fields: Record<string, unknown>;
  readonly parameter?: string;
  readonly unit?: string;
  /** Simulated time (s) of the failing step. */
  readonly time?: number;
  readonly step?: number;
  /** Time (s) the world was rolled back to. */
  readonly rolledBackTo?: number;
  /** Scene-file line (a scene error, or the event at fault in a step). */
  readonly line?: number;
  readonly key?: string;

  constructor(fields: Record<string, unknown>) {
    super(String(fields.message ?? 'engine error'));
    this.name = 'EngineError';
    this.fields = fields;
    this.kind = (fields.kind ?? 'usage') as EngineError['kind'];
    const s = (k: string) => (typeof fields[k] === 'string' ? (fields[k] as string) : undefined);
    const n = (k: string) => (typeof fields[k] === 'number' ? (fields[k] as number) : undefined);
    this.parameter = s('parameter');
    this.unit = s('unit');
    this.time = n('time');
    this.step = n('step');
    this.rolledBackTo = n('rolled_back_to');
    this.line = n('line');
    this.key = s('key');
  }
}

/** −1 is failure (the error slot says why); anything else is returned. */
function check(r: number): number {
  if (r < 0) throw new EngineError(errorJson());
  return r;
}

const encode = (s: string) => new TextEncoder().encode(s);

export type ParamValue = number | boolean | string | [number, number, number];

/** A body's triangle quality (`World.quality`, the core's `mesh::quality::Quality`). */
export interface Quality { min_angle_deg: number; small_angle_share: number; edge_min: number; edge_mean: number; edge_spread: number; poor: boolean }

/** One row of the engine's parameter table (softsculpt::params). */
export interface ParamInfo {
  id: import('./params').ParamId;
  scope: 'body' | 'world' | 'scene' | 'obstacle';
  unit: string;
  default: ParamValue;
  min: number | null;
  max: number | null;
  min_open: boolean;
  choices: string[];
  help: string;
}

/** A rigid obstacle as the engine describes it (m). */
export type Obstacle =
  | { kind: 'sphere'; friction: number; center: number[]; radius: number }
  | { kind: 'box'; friction: number; center: number[]; half: number[]; axes: number[][] }
  | { kind: 'capsule'; friction: number; a: number[]; b: number[]; radius: number }
  | { kind: 'mesh'; friction: number; positions: Float64Array; indices: Uint32Array };

/**
 * A recording as a GLB of morph targets (the core's animation writer, the format of `softsculpt
 * run --frames`): `times` (s); per track its triangles and its frames (xyz, f32, one per time).
 */
export function animationGlb(times: Float64Array, tracks: { triangles: Uint32Array; frames: Float32Array[] }[]): Uint8Array {
  const counts = new Uint32Array(tracks.flatMap((t) => [t.frames[0].length / 3, t.triangles.length / 3]));
  const tris = new Uint32Array(tracks.reduce((n, t) => n + t.triangles.length, 0));
  const frames = new Float32Array(tracks.reduce((n, t) => n + t.frames.length * t.frames[0].length, 0));
  let at = 0, af = 0;
  for (const t of tracks) {
    tris.set(t.triangles, at); at += t.triangles.length;
    for (const f of t.frames) { frames.set(f, af); af += f.length; }
  }
  check(withArrays([times, counts, tris, frames], (tp, cp, ip, fp) => raw().ss_animation_glb(tp, times.length, cp, tracks.length, ip, fp)));
  return resultBytes();
}

/** Body `index` of a world: counts and typed-array views (see the file comment). */
export class BodyView {
  private layoutCopy = new Uint32Array(LAYOUT_LEN);
  private epoch = -1;
  private buffer: ArrayBuffer | SharedArrayBuffer | null = null;
  private cache = new Map<string, ArrayBufferView>();

  constructor(private readonly world: World, readonly index: number) {}

  /** The layout table, read again after a call on the world or a memory growth. */
  private layout(): Uint32Array {
    const buffer = raw().memory.buffer;
    if (this.epoch !== this.world.epoch || this.buffer !== buffer) {
      const p = raw().ss_body_views(this.world.handle, this.index);
      if (p === 0) throw new EngineError(errorJson());
      this.layoutCopy.set(view.u32(p, LAYOUT_LEN));
      this.epoch = this.world.epoch;
      this.buffer = raw().memory.buffer;
      this.cache.clear();
    }
    return this.layoutCopy;
  }

  private get<T extends ArrayBufferView>(slot: keyof typeof SLOT, make: (ptr: number, len: number) => T, len: number): T {
    const l = this.layout();
    let a = this.cache.get(slot) as T | undefined;
    if (!a) {
      a = make(l[SLOT[slot]], len);
      this.cache.set(slot, a);
    }
    return a;
  }

  get vertexCount(): number { return this.layout()[SLOT.n]; }
  get faceCount(): number { return this.layout()[SLOT.f]; }
  get springCount(): number { return this.layout()[SLOT.s]; }
  get bendingCount(): number { return this.layout()[SLOT.k]; }

  /** The engine's positions (m, xyz per vertex): read only. */
  get positions(): Float64Array { return this.get('positions', view.f64, 3 * this.vertexCount); }
  get velocities(): Float64Array { return this.get('velocities', view.f64, 3 * this.vertexCount); }
  /** f32 positions for drawing, as of the last `sync()`. */
  get render(): Float32Array { return this.get('render', view.f32, 3 * this.vertexCount); }
  get triangles(): Uint32Array { return this.get('triangles', view.u32, 3 * this.faceCount); }
  get springs(): Uint32Array { return this.get('springs', view.u32, 2 * this.springCount); }
  get masses(): Float64Array { return this.get('masses', view.f64, this.vertexCount); }
  /** 1 pinned, 0 free, as of the last `sync()`; write it, then `World.setPins`. */
  get pinned(): Uint8Array { return this.get('pinned', view.u8, this.vertexCount); }
  get rest(): Float64Array { return this.get('rest', view.f64, this.springCount); }
  get bendingRest(): Float64Array { return this.get('bendingRest', view.f64, this.bendingCount); }
  /** Staging (N, xyz per vertex): write, then `World.applyLoads`. */
  get userForces(): Float64Array { return this.get('userForces', view.f64, 3 * this.vertexCount); }
  /** Staging (Pa, per face, inward): write, then `World.applyLoads`. */
  get facePressures(): Float64Array { return this.get('facePressures', view.f64, this.faceCount); }
  /** Staging (per vertex): factors for `scaleRest`, masses for `setMasses`. */
  get scratch(): Float64Array { return this.get('scratch', view.f64, this.vertexCount); }

  /** Statistics as of the last `sync()`. */
  get stats(): Stats {
    return readStats(this.get('stats', view.f64, STATS_LEN));
  }
}

export class World {
  private h: number;
  /** Counts calls that may replace bodies or arrays; BodyViews re-read their layout when it moves. */
  epoch = 0;
  /** Warnings of the last `add*` (welded seams, dropped faces…). */
  warnings: string[] = [];

  private constructor(handle: number) { this.h = handle; }

  /** An empty world with the parameter table's defaults. */
  static create(): World { return new World(check(raw().ss_world_new())); }
  /** The standard benchmark workload (softsculpt::workload) at an icosphere level. */
  static workload(level: number): World { return new World(check(raw().ss_workload(level))); }

  get handle(): number {
    if (this.h === 0) throw new EngineError({ kind: 'usage', message: 'the world was freed' });
    return this.h;
  }
  get alive(): boolean { return this.h !== 0; }

  /** Every call goes through here: the views are re-made after it. */
  private call(f: (w: number) => number): number {
    const w = this.handle;
    this.epoch++;
    return check(f(w));
  }

  free(): void {
    if (this.h !== 0) raw().ss_world_free(this.h);
    this.h = 0;
  }

  private added(b: number): number {
    this.warnings = JSON.parse(resultText()) as string[];
    return b;
  }
  /** A built-in model (`sphere`, `mushroom`, `octopus`, …) of `mass` kg; its body index. */
  addBuiltin(name: string, mass = 1): number {
    return this.added(this.call((w) => withBytes(encode(name), (p, n) => raw().ss_add_builtin(w, p, n, mass))));
  }
  /** An OBJ file (welded, checked, oriented); warnings in `warnings`. */
  addObj(bytes: Uint8Array, mass = 1): number {
    return this.added(this.call((w) => withBytes(bytes, (p, n) => raw().ss_add_obj(w, p, n, mass))));
  }
  /** An indexed triangle mesh; `prepare` makes it ready like a file (weld, orient, reorder). */
  addMesh(positions: Float64Array, indices: Uint32Array, mass = 1, prepare = true): number {
    return this.added(this.call((w) => withArrays([positions, indices], (p, i) =>
      raw().ss_add_mesh(w, p, positions.length / 3, i, indices.length, mass, prepare ? 1 : 0))));
  }
  /**
   * A mesh file of any format, read as the command line reads it (weld, checks, orientation):
   * one body, or one per piece (`split`, largest area first), each of `mass` kg; not rotated.
   * Returns the first body's index and what the file held.
   */
  addFile(name: string, bytes: Uint8Array, split: boolean, mass = 1): { first: number; report: FileReport } {
    const first = this.call((w) => withBytes(encode(name), (np, nl) => withBytes(bytes, (p, n) => raw().ss_add_file(w, np, nl, p, n, split ? 1 : 0, mass))));
    const report = JSON.parse(resultText()) as FileReport;
    this.warnings = report.warnings;
    return { first, report };
  }
  /**
   * Preset `name` for a model `size` times as large as the one it was tuned for (the core's
   * similarity rules, params/similarity.rs); returns the gas parameters skipped because body
   * `b` is open.
   */
  applyPresetScaled(b: number, name: string, size: number): string[] {
    this.call((w) => withBytes(encode(name), (p, n) => raw().ss_apply_preset_scaled(w, b, p, n, size)));
    return JSON.parse(resultText()) as string[];
  }

  /** A balloon sketched from a closed outline (x y pairs, m), inflated to rest; `edge` ≤ 0: the default. */
  addSketch(xy: Float64Array, edge = 0, mass = 1): number {
    return this.added(this.call((w) => withArrays([xy], (p) => raw().ss_add_sketch(w, p, xy.length / 2, edge, mass))));
  }
  /** Drop bodies, events and loads; keep the settings. */
  clear(): void { this.call((w) => raw().ss_clear(w)); }

  get bodyCount(): number { return check(raw().ss_body_count(this.handle)); }
  body(i: number): BodyView { return new BodyView(this, i); }
  /** Newton iterations of body `b`'s last step (0 after an explicit one). */
  newtonIterations(b: number): number { return check(raw().ss_body_newton_iterations(this.handle, b)); }
  /** What of the hinges body `b`'s last step let go of to finish: 0 nothing, 1 the crushed faces', 2 all. */
  relaxed(b: number): number { return check(raw().ss_body_relaxed(this.handle, b)); }

  /** `n` steps or none: on a blow-up the whole world is rolled back and this throws (kind 'step'). */
  step(n = 1): void { this.call((w) => raw().ss_step(w, n)); }
  /** The largest stable step (s) of an explicit integrator for every body (the core's `World::stable_dt`); 0 for implicit. */
  stableDt(integrator: string): number {
    const dt = withBytes(encode(integrator), (p, n) => raw().ss_stable_dt(this.handle, p, n));
    if (dt < 0) throw new EngineError(errorJson());
    return dt;
  }
  /** The relative residual body `b`'s last implicit step was accepted at when its deadline stopped it (0: it converged, or explicit). */
  accuracy(b: number): number {
    const r = raw().ss_body_accuracy(this.handle, b);
    if (r < 0) throw new EngineError(errorJson());
    return r;
  }
  /**
   * `frameDt` simulated seconds (`World::advance`): under a real-time budget of `seconds`
   * (0: converge every step), refused implicit steps halved up to `splits` times, `relax`: the
   * relaxed retry, `rewind`: a failed frame goes back to the last sound state (the core's
   * `world/rewind.rs`; the error's field `rewound_to`, s). Throws like `step` (the world as
   * after the last step taken, or rewound); under a real-time budget a waiting command
   * abandons the step in progress (cause `interrupted`).
   */
  advance(frameDt: number, seconds = 0, minAccuracy = 0, splits = 0, relax = false, rewind = false): Advance {
    this.call((w) => raw().ss_advance(w, frameDt, seconds, minAccuracy, splits, relax ? 1 : 0, rewind ? 1 : 0));
    return JSON.parse(resultText()) as Advance;
  }
  /** The model changed: the rewind points before now are not its past (`World::forget_rewind`). */
  forgetRewind(): void { this.call((w) => raw().ss_forget_rewind(w)); }
  /** Refresh every body's render positions, pins and stats. */
  sync(): void { this.call((w) => raw().ss_sync(w)); }

  /** The material presets the core defines (name, help): the modeler's Material list. */
  materialPresets(): { name: string; help: string }[] {
    check(raw().ss_material_presets());
    return JSON.parse(resultText()) as { name: string; help: string }[];
  }
  paramTable(): ParamInfo[] {
    check(raw().ss_param_table());
    return JSON.parse(resultText()) as ParamInfo[];
  }
  /** Every body and world parameter of body `b` (null: not set, e.g. the ground's without ground). */
  params(b = 0): Record<string, ParamValue | null> {
    this.call((w) => raw().ss_params(w, b));
    return JSON.parse(resultText()) as Record<string, ParamValue | null>;
  }
  /** Set a parameter by its table id (body parameters on body `b`); throws kind 'parameter'. */
  setParam(b: number, id: import('./params').ParamId, value: ParamValue): void {
    const json = JSON.stringify(value) ?? 'null';
    this.call((w) => withBytes(encode(id), (ip, il) => withBytes(encode(json), (jp, jl) => raw().ss_set_param(w, b, ip, il, jp, jl))));
  }

  /** Apply a preset of the core's (`modeler`…): its values on body `b` and the world, all or nothing. */
  applyPreset(b: number, name: string): void {
    this.call((w) => withBytes(encode(name), (p, n) => raw().ss_apply_preset(w, b, p, n)));
  }

  /** Rest shape := current shape (`World::freeze`); the tension-keeping one reports its residual (N). */
  freeze(b: number, underLoad = false, keepTension = false): FreezeReport {
    this.call((w) => raw().ss_freeze(w, b, underLoad ? 1 : 0, keepTension ? 1 : 0));
    return JSON.parse(resultText()) as FreezeReport;
  }
  reset(b: number): void { this.call((w) => raw().ss_reset(w, b)); }
  /** The ground to `height` m, carrying every body standing on it (`World::move_ground`); returns how many moved. */
  moveGround(height: number): number {
    this.call((w) => raw().ss_move_ground(w, height));
    return (JSON.parse(resultText()) as { moved: number }).moved;
  }
  /** Contacts off between the bodies that overlap or touch now, until they part (an import's pieces); returns those pairs. */
  letOverlappingBe(): [number, number][] {
    this.call((w) => raw().ss_let_overlapping_be(w));
    return (JSON.parse(resultText()) as { pairs: [number, number][] }).pairs;
  }
  /** Replace body `b` by its isotropic remeshing to `edge` m (frozen, under load if asked); returns the dropped pending events. */
  remesh(b: number, edge: number, underLoad: boolean): number {
    return this.remeshReporting(b, edge, underLoad).dropped_events;
  }
  /**
   * `remesh` and how the core kept the shape: the edge length used (shorter than `edge` when the
   * mesh was too coarse for it), creases kept, tries, how far the surface moved. A remesh that
   * would change the shape throws (an `EngineError`) and changes nothing.
   */
  remeshReporting(b: number, edge: number, underLoad: boolean): RemeshReport {
    this.call((w) => raw().ss_remesh(w, b, edge, underLoad ? 1 : 0));
    return JSON.parse(resultText()) as RemeshReport;
  }
  /** Body `b`'s triangle quality: smallest angle (°), share of angles below 25°, shortest and mean edge (m), spread (σ/mean), poor. */
  quality(b: number): Quality {
    this.call((w) => raw().ss_quality(w, b));
    return JSON.parse(resultText());
  }
  /** Loop subdivision of body `b`; returns how many of its pending scene events were dropped. */
  subdivide(b: number): number {
    this.call((w) => raw().ss_subdivide(w, b));
    return (JSON.parse(resultText()) as { dropped_events: number }).dropped_events;
  }
  /** Rest lengths × per-vertex factors (given, or already in the body's scratch). */
  scaleRest(b: number, factors?: ArrayLike<number>): void {
    if (factors) this.body(b).scratch.set(factors);
    this.call((w) => raw().ss_scale_rest(w, b));
  }
  /** Vertex masses (kg), given or already in the body's scratch. */
  setMasses(b: number, masses?: ArrayLike<number>): void {
    if (masses) this.body(b).scratch.set(masses);
    this.call((w) => raw().ss_set_masses(w, b));
  }
  /** Pins (1/0 per vertex), given or already written into the body's `pinned` view. */
  setPins(b: number, pinned?: ArrayLike<number>): void {
    if (pinned) this.body(b).pinned.set(pinned);
    this.call((w) => raw().ss_set_pins(w, b));
  }
  /** User forces and face pressures from the body's staging views. */
  applyLoads(b: number): void { this.call((w) => raw().ss_apply_loads(w, b)); }
  /**
   * Target springs of body `b`, replacing its others: records of 6 numbers (vertex, anchor xyz
   * (m), stiffness (N/m), damping (N·s/m)); empty clears them. Exact in the implicit system.
   */
  setTargets(b: number, records: Float64Array): void {
    if (records.length % 6 !== 0) throw new EngineError({ kind: 'usage', message: 'targets are records of 6 numbers' });
    if (records.length === 0) { this.call((w) => raw().ss_set_targets(w, b, 0, 0)); return; }
    this.call((w) => withArrays([records], (p) => raw().ss_set_targets(w, b, p, records.length / 6)));
  }

  /** The whole world as snapshot bytes (docs/snapshot.md). */
  snapshot(): Uint8Array {
    this.call((w) => raw().ss_snapshot(w));
    return resultBytes();
  }
  /** The world from snapshot bytes; throws kind 'snapshot' and leaves the world as it was. */
  restore(bytes: Uint8Array): void { this.call((w) => withBytes(bytes, (p, n) => raw().ss_restore(w, p, n))); }

  /** The world becomes a scene file's; `files` holds the mesh files it names (by file name). */
  openScene(text: string, files: Map<string, Uint8Array> = new Map()): { names: string[]; dt: number; duration: number } {
    for (const [name, bytes] of files) {
      check(withBytes(encode(name), (np, nl) => withBytes(bytes, (p, l) => raw().ss_scene_file(np, nl, p, l))));
    }
    this.call((w) => withBytes(encode(text), (p, n) => raw().ss_open_scene(w, p, n)));
    return JSON.parse(resultText()) as { names: string[]; dt: number; duration: number };
  }
  /** The world as scene text (TOML), with the open scene's obstacles and events. */
  saveScene(): string {
    this.call((w) => raw().ss_save_scene(w));
    return resultText();
  }
  obstacles(): Obstacle[] {
    this.call((w) => raw().ss_obstacles(w));
    const list = JSON.parse(resultText()) as (Obstacle & { positions?: number[]; indices?: number[] })[];
    return list.map((o) => (o.kind === 'mesh'
      ? { ...o, positions: Float64Array.from(o.positions as ArrayLike<number>), indices: Uint32Array.from(o.indices as ArrayLike<number>) }
      : o));
  }

  /** Remember the world as it is now, for `delta`. */
  mark(): void { this.call((w) => raw().ss_mark(w)); }
  /** Bytes of a delta that takes the world back to the mark. */
  delta(scope: DeltaScope): Uint8Array {
    this.call((w) => raw().ss_delta(w, SCOPE[scope]));
    return resultBytes();
  }
  /** Apply a delta; returns its inverse (to redo what it undid). Throws kind 'delta' (world untouched). */
  applyDelta(bytes: Uint8Array): Uint8Array {
    this.call((w) => withBytes(bytes, (p, n) => raw().ss_apply_delta(w, p, n)));
    return resultBytes();
  }
  /** A version-1 project file of the modeler becomes the world; its name and ui settings. */
  openProjectV1(text: string): { name: string; ui: Record<string, unknown> } {
    this.call((w) => withBytes(encode(text), (p, n) => raw().ss_open_project_v1(w, p, n)));
    return JSON.parse(resultText()) as { name: string; ui: Record<string, unknown> };
  }
}
