// The messages between the page (main thread: drawing and input) and the simulation worker
// (engine, document, undo, autosave). Every message either way is one of the types below; both
// sides import them from here and nowhere else.
//
// Main → worker (`Command`): operations on the document, parameter and settings changes, tool
// strokes, and the frame buffers handed back after drawing.
// Worker → main (`Reply`): frames (positions every time; topology, masses and pins, parameters,
// settings and history only when they changed), messages for the user, progress of long
// operations, files to download.
//
// Frames are double-buffered: the worker owns two Float32Array position buffers per mesh size.
// It fills a free one and transfers it with a frame; the page draws it and, once the next frame
// has been drawn, transfers the previous buffer back (`returnBuffer`). So no buffer is allocated
// per frame, and the worker never runs more than one frame ahead of the drawing (it keeps
// stepping meanwhile; only publishing waits).

import type { Obstacle, ParamInfo, ParamValue, Stats } from './engine/world';
import type { ParamId } from './engine/params';
import type { ImportAnswer, ImportFrame, ImportQuestion } from './io/import';

export type { Stats, Obstacle, ParamId, ParamInfo, ParamValue };
/** Parameter values by the engine's table ids (null: not set, e.g. the ground's without ground). */
export type Params = Record<string, ParamValue | null>;
export type Vec3 = [number, number, number];
export type MessageKind = 'info' | 'warn' | 'error';

/** How the simulation runs (the worker's; the page mirrors them). */
export interface Settings {
  /** Time step (s). */
  dt: number;
  /** Steps per frame when not in real time. */
  substeps: number;
  /** Advance simulated time at the pace of the clock (as many steps as wall-clock time allows). */
  realTime: boolean;
  playing: boolean;
  /** Freeze keeps the skin's tension (the gas keeps pressing, rest lengths are corrected so the
   *  shape holds: `World::freeze` with keep_tension) instead of leaving it slack. Off by default. */
  keepTension: boolean;
  /** Name of the model, file or scene (used for file names). */
  model: string;
  /** An imported model's frame: how the file's coordinates became the engine's (exports go back); null otherwise. */
  frame?: ImportFrame | null;
  /** Send each vertex's strain with the frames (the strain view). */
  strain?: boolean;
  /** Which load of a model this is (unique per load, import or open; undo brings the earlier one
   *  back): the page frames the view anew when it changes, even for a file of the same name. */
  opened?: number;
}

/** What the page keeps in a project file besides the body: brush, tool, tool strengths. */
export interface UiState {
  brush: { radius: number };
  tool: string;
  strengths: Record<string, number>;
  /** Mirror symmetry axes (X, Y, Z) for the tools. */
  symmetry?: [boolean, boolean, boolean];
  /**
   * The material's name as the panel shows it (a preset's name, 'modeler' or 'custom'), so an
   * opened project names its material again in a browser that has not seen it (panel-material.ts).
   */
  material?: string;
}

/** The tools whose strokes act on the body (see worker/strokes.ts). */
export type StrokeTool = 'grab' | 'press' | 'inflate' | 'mass' | 'pin';

export interface SceneInfo { name: string; time: number; duration: number; bodies: number }

// ----- main → worker ----------------------------------------------------------------------------

/**
 * Commands that a running step makes way for: the page counts them as it sends them and the
 * worker as it takes them (two Int32 counters in a SharedArrayBuffer, `init.interrupts`, where
 * the page is cross-origin isolated); while they differ the engine abandons the step in
 * progress, the world as before it (`WorldSettings::interrupt`), so Undo, a new model or a
 * parameter change never waits for a slow step. Strokes do not: they act through the steps.
 */
const INTERRUPTING: ReadonlySet<string> = new Set(['loadBuiltin', 'import', 'setUp', 'importAnswer', 'openProject', 'openScene',
  'restartScene', 'freeze', 'reset', 'subdivide', 'remesh', 'undo', 'redo', 'step', 'setParam', 'setMass', 'preset', 'settings', 'sketch']);
export function interrupts(cmd: { type: string }): boolean { return INTERRUPTING.has(cmd.type); }

export type Command =
  /** Load the engine from `wasmUrl` (or its threaded build beside it on `threads` threads, default every core up to 4, where memory can be shared), then open the autosave (if `restore` and there is one) or the mushroom. */
  | { type: 'init'; wasmUrl: string; restore: boolean; interrupts?: SharedArrayBuffer; threads?: number }
  | { type: 'loadBuiltin'; name: string }
  /** A model file (OBJ, PLY, STL, glTF/GLB); `data` is transferred. */
  /** `upAnswers`: the up axis the user chose for files by name (io/upaxis.ts), which settles that file's guess. */
  | { type: 'import'; name: string; data: ArrayBuffer; upAnswers?: Record<string, 'y' | 'z'> }
  /** The imported model turned to another up axis (re-built from the file; undoable). */
  | { type: 'setUp'; up: 'y' | 'z' }
  /** The user's answers for the file waiting (`importQuestion`); null cancels. */
  | { type: 'importAnswer'; answer: ImportAnswer | null }
  /** Start (true) or stop recording the bodies' shapes while the simulation plays. */
  | { type: 'record'; on: boolean }
  /** Reply: a `download` of the recording as GLB morph targets. */
  | { type: 'exportRecording' }
  | { type: 'openProject'; name: string; text: string }
  /** A scene file with the mesh files it names (by file name). */
  | { type: 'openScene'; name: string; text: string; files: Map<string, Uint8Array> }
  | { type: 'restartScene' }
  /** Reply: a `download` of the project file (with `ui`, the page's state). */
  | { type: 'saveProject'; ui: UiState }
  /** Reply: a `download` of the scene file. */
  | { type: 'saveScene' }
  | { type: 'freeze' }
  | { type: 'reset' }
  | { type: 'subdivide' }
  /** Even triangles at the mean edge length (isotropic remeshing; undoable). */
  | { type: 'remesh' }
  | { type: 'undo' }
  | { type: 'redo' }
  /** One frame of steps (settings.substeps) while paused. */
  | { type: 'step' }
  /** A parameter by its table id (engine/world.ts `paramTable`); undoable; a refused value is reported (message) and the parameters are sent again. */
  | { type: 'setParam'; name: ParamId; value: ParamValue }
  /** Total mass (kg) split equally over the vertices (undoable). */
  | { type: 'setMass'; total: number }
  /** A material preset of the core (balloon, jelly, clay…) on the active body, at its size (undoable). */
  | { type: 'preset'; name: string }
  /** Wind along `direction` (unit: across or along the view) at `strength` m/s (undoable). */
  | { type: 'wind'; direction: Vec3; strength: number }
  | { type: 'settings'; patch: Partial<Settings> }
  /** The page's tool state, kept for project files and the autosave. */
  | { type: 'ui'; ui: UiState }
  /**
   * A tool stroke begins at `point` (on the surface): grab takes the vertices within `radius`,
   * press the faces, the brushes paint the vertices. `strength` in the tool's unit; `inverted`:
   * Shift (deflate, lighter, unpin). One undo entry per stroke.
   */
  | {
    type: 'strokeStart'; tool: StrokeTool; point: Vec3; radius: number; strength: number; inverted: boolean;
    /** Mirror symmetry: the axes and the plane's centre (m); the stroke acts at the mirror images too. */
    mirror?: { axes: [boolean, boolean, boolean]; centre: Vec3 };
    /** Pen pressure in (0, 1] scaling the strength (absent: 1, a mouse). */
    pressure?: number;
    /** The body under the cursor (0: the first; an import's pieces and a scene's bodies follow). */
    body?: number;
  }
  /** Grab: the cursor's point on the grab plane; press and brushes: the brush centre (null: off the body). */
  | { type: 'strokeMove'; point: Vec3 | null; inverted: boolean; pressure?: number }
  | { type: 'strokeEnd' }
  /**
   * Sketch: the closed outline `points` (x y pairs, m) in the view plane through `origin` spanned
   * by `right` and `up` (`normal` toward the camera) becomes a balloon replacing the model (undoable).
   */
  | { type: 'sketch'; points: number[]; origin: Vec3; right: Vec3; up: Vec3; normal: Vec3 }
  /** A frame's position buffer, drawn and handed back (transferred). */
  | { type: 'returnBuffer'; buffer: ArrayBuffer }
  /** Send everything again in the next frame (after a lost message). */
  | { type: 'resync' };

// ----- worker → main ----------------------------------------------------------------------------

/** The meshes to draw; sent when they change (load, import, subdivide, undo, scene). */
export interface Topology {
  /** The active body (the one the tools shape). */
  vertexCount: number;
  triangles: Uint32Array;
  springs: Uint32Array;
  /** A scene's other bodies, in order; their positions follow the active body's in the frame buffer. */
  others: { vertexCount: number; triangles: Uint32Array }[];
  obstacles: Obstacle[];
  /** The active body's surface is closed (an open one, cloth-like, has no gas). */
  closed?: boolean;
}

/** A recording under way: frames and simulated seconds so far. */
export interface Recording { frames: number; seconds: number }

export interface Frame {
  /** xyz per vertex (m): the active body, then each other body; transfer back with `returnBuffer`. */
  positions: Float32Array;
  /** The active body's statistics. */
  stats: Stats;
  /** Wall-clock ms spent stepping since the last frame. */
  simMs: number;
  /** The simulation could not keep up with the clock; `realTimeFraction` of real time is simulated. */
  slowMotion: boolean;
  realTimeFraction: number;
  /**
   * The largest relative residual an implicit step since the last frame was accepted at when
   * the frame's solve budget stopped it short of the tolerance (the anytime step); 0: every
   * step converged.
   */
  accuracy: number;
  scene: SceneInfo | null;
  topology?: Topology;
  /** Masses (kg) and pins (0/1) per vertex of the active body, when they changed. */
  body?: { masses: Float64Array; pinned: Uint8Array };
  /** Every parameter of the active body and the world, by table id, when one changed. */
  params?: Params;
  /** The engine's parameter table (ids, units, ranges, help), with the first frame. */
  table?: ParamInfo[];
  /** Threads the engine steps on (the threaded build where the page is cross-origin isolated), with the table. */
  threads?: number;
  /** The core's material presets (name, help), with the table. */
  presets?: { name: string; help: string }[];
  settings?: Settings;
  /** Undo and redo stack sizes, when they changed. */
  history?: [number, number];
  /** A recording under way (absent: none). */
  recording?: Recording;
  /** With `settings.strain`: each vertex's mean spring strain l / L − 1 (active body). */
  strain?: Float32Array;
}

export type Reply =
  | { type: 'frame'; frame: Frame }
  | { type: 'message'; text: string; kind: MessageKind }
  /** A long operation started (`label`, e.g. "subdividing", with `fraction` done if known) or ended (null). */
  | { type: 'progress'; label: string | null; fraction?: number }
  /** A file to save: `text`, or `bytes` when given (binary). */
  | { type: 'download'; filename: string; mime: string; text: string; bytes?: Uint8Array }
  /** An imported file needs answers (up axis, pieces): the page asks and sends `importAnswer`. */
  | { type: 'importQuestion'; question: ImportQuestion }
  /** An opened project's page state (brush, tool, strengths). */
  | { type: 'ui'; ui: Partial<UiState> }
  /** The engine could not start at all. */
  | { type: 'fatal'; text: string };

/** The buffers a reply transfers (the frame's positions, its topology's arrays). */
export function transferables(r: Reply): Transferable[] {
  if (r.type !== 'frame') return [];
  const f = r.frame;
  const out: Transferable[] = [f.positions.buffer as ArrayBuffer];
  if (f.topology) out.push(f.topology.triangles.buffer as ArrayBuffer, f.topology.springs.buffer as ArrayBuffer, ...f.topology.others.map((o) => o.triangles.buffer as ArrayBuffer));
  if (f.body) out.push(f.body.masses.buffer as ArrayBuffer, f.body.pinned.buffer as ArrayBuffer);
  return out;
}
