// What the document holds, every field in one place: the engine world (body 0 first: its
// parameters and statistics are the panel's; an import's other pieces and an open scene's other
// bodies follow), the empty world a new model starts from, the open scene, the settings and the
// page's tool state, the undo history, the stroke under way, the versions the page's mirror
// follows, and what the current model's run has met (the user's changes, stops, relaxed and
// split steps). The document's jobs work on it: reading.ts, stroking.ts, editing.ts,
// parameters.ts, meshops.ts, stepping.ts, opening.ts and projects.ts; worker/document.ts is the
// class the worker and the tests hold, which gathers them.

import { World, type Advance, type DeltaScope } from '../engine/world';
import { History } from '../history';
import type { MessageKind, Settings, Stats, UiState } from '../protocol';
import type { ImportQuestion } from '../io/import';
import type { Stroke } from './strokes';
import type { Change, Imported } from './explain';

export const HISTORY_STEPS = 200;
export const HISTORY_BYTES = 512 * 1024 * 1024;

/** What a scene was opened from, to restart it (and to bring it back on undo). */
export interface SceneSource { name: string; text: string; files: Map<string, Uint8Array>; duration: number }

/** One undo step: the engine delta, and the page's settings and open scene before it. */
export interface Entry { delta: Uint8Array; settings: Settings; scene: SceneSource | null }

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

export class DocState {
  // ----- the world ------------------------------------------------------------------------------

  w: World | null = null;
  /** An empty world's snapshot: what a new model starts from (no obstacles, default settings). */
  empty: Uint8Array | null = null;
  /** The open scene, if any (its first body is the active body). */
  session: SceneSource | null = null;
  /** The world's call count when it was last synced. */
  syncedAt = -1;

  // ----- the settings, the page's state and undo --------------------------------------------------

  readonly history = new History<Entry>({ limit: HISTORY_STEPS, maxBytes: HISTORY_BYTES, size: (e) => e.delta.byteLength });
  readonly settings: Settings = { dt: 1e-3, substeps: 16, realTime: true, playing: true, keepTension: false, model: 'mushroom', frame: null };
  ui: UiState = { brush: { radius: 0.35 }, tool: 'grab', strengths: {} };
  /**
   * The brush radius (m) the last import fitted to its file's size (`importer.ts`), or null: a
   * built-in loaded while the radius is still that one opens with the built-ins' brush
   * (`opening.ts`), not with one fitted to another model.
   */
  fittedRadius: number | null = null;

  // ----- the stroke under way -------------------------------------------------------------------

  stroke: Stroke | null = null;
  /** The body the stroke acts on (the one under the cursor when it began). */
  strokeOn = 0;
  strokeScope: DeltaScope = 'all';

  // ----- what the page's mirror follows ---------------------------------------------------------

  /** Bumped when the meshes change shape (body replaced, subdivided, scene opened or closed). */
  topologyVersion = 0;
  /** Bumped when masses or pins may have changed. */
  bodyVersion = 0;
  /** Scratch of the strain view (reading.ts `strain`), kept across frames (one per mesh size). */
  strainSum = new Float64Array(0);
  strainCount = new Uint32Array(0);

  // ----- the current model's run (what a new model starts again: `newModel`) --------------------

  /** The simulation paused itself on a failure (a new model plays again). */
  pausedByError = false;
  /** Parameters the user changed on this model, with the simulated time (to name a failure's likely cause). */
  changes: Change[] = [];
  /** Part of the body was below the ground when it was last switched on. */
  groundUnderBody = false;
  /** The model is an import (set by worker/importer.ts): what a stop soon after it names (explain.ts). */
  imported: Imported | undefined = undefined;
  /** What the last `advance` did (null if it failed or was interrupted). */
  lastAdvance: Advance | null = null;
  /** The largest relative residual an implicit step stopped by its deadline was accepted at since `takeAccuracy`. */
  accuracy = 0;
  /** Steps that let go of hinges to finish (since the model was opened: reset in `newModel`). */
  relaxedSteps = 0;
  /** Frames whose implicit step had to be split (since the model was loaded). */
  splitFrames = 0;

  constructor(readonly hooks: DocumentHooks) {}

  /** The empty world's snapshot (a scratch world for an import's trial, `trial.ts`). */
  get emptyWorld(): Uint8Array { return this.empty!; }
  get loaded(): boolean { return this.w !== null && this.w.bodyCount > 0; }
  /** The engine world (for tests and the service; operations go through the document's methods). */
  get world(): World {
    if (!this.w) {
      this.w = World.create();
      this.empty = this.w.snapshot();
    }
    return this.w;
  }

  /** Render positions, pins and stats up to date (synced unless nothing was called since). */
  synced(): void {
    if (this.syncedAt === this.world.epoch) return;
    this.world.sync();
    this.syncedAt = this.world.epoch;
  }
  /** The active body's statistics now. */
  stats(): Stats {
    this.synced();
    return this.world.body(0).stats;
  }

  /** Every body's index: Freeze, Reset, Subdivide and Remesh act on all of them (meshops.ts). */
  get everyBody(): number[] { return Array.from({ length: this.world.bodyCount }, (_, i) => i); }
  /** Vertices of every body. */
  get totalVertices(): number { return this.everyBody.reduce((n, b) => n + this.world.body(b).vertexCount, 0); }

  /** Anything may have changed: send topology, masses and pins again. */
  touched(): void {
    this.topologyVersion++;
    this.bodyVersion++;
    this.world.forgetRewind();
  }

  /**
   * Another model (loaded, imported, sketched, opened): a new `opened` serial (the page frames
   * the view on it even when the file has the old one's name), and nothing of the old model's
   * run carries over: no paused-by-error state, no remembered changes, no rewind points.
   */
  newModel(): void {
    this.settings.opened = Math.max((this.settings.opened ?? 0) + 1, Date.now());
    this.changes = [];
    this.imported = undefined;
    this.groundUnderBody = false;
    this.relaxedSteps = 0;
    if (this.pausedByError) { this.pausedByError = false; this.settings.playing = true; }
  }
}

/** A thrown value's text, as the messages quote it. */
export function errorText(e: unknown): string {
  return e instanceof Error ? e.message : String(e);
}
