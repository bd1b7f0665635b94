// Importing a model file: what to ask the user (the up axis where the format does not say it,
// and what to do with several pieces), and the frame that maps the file's coordinates to the
// engine's (turned Y-up, standing on the ground at the origin) and back, for exports. The file
// itself is read by the engine, as the command line reads it (World.addFile: every format, one
// weld, checks, orientation, piece count). Nothing is rescaled: a model keeps the file's units,
// the view is fitted to it and its defaults are scaled to its size (engine/models.ts).

import type { FileReport } from '../engine/world';

export const IMPORT_EXTENSIONS = ['.obj', '.ply', '.stl', '.gltf', '.glb'];

/** Bounding-box diagonal (m) of the models the modeler's defaults were tuned on (the mushroom). */
export const REFERENCE_DIAGONAL = 2.5;

export type Up = 'y' | 'z';
export type Vec3 = [number, number, number];

/**
 * How a file's coordinates became the engine's: turned from Z-up to Y-up (if `up` is 'z'), then
 * moved by −`offset` (centred in x and z, lowest point at y = 0). Lengths are unchanged.
 */
export interface ImportFrame { up: Up; offset: Vec3; /** The file's format (OBJ, PLY, STL, glTF). */ format?: string; /** The file's name, to remember an up axis chosen later for it (io/upaxis.ts). */ file?: string }
export const IDENTITY_FRAME: ImportFrame = { up: 'y', offset: [0, 0, 0] };

/** What the page asks about a file before it is imported. */
export interface ImportQuestion {
  name: string;
  format: string;
  /** The up axis the format declares (glTF: Y), or null when it says none. */
  declaredUp: Up | null;
  /** The axis offered first, and why. */
  guessedUp: Up;
  guessReason: string;
  /** The guess is sure enough not to ask (declared by the format, the exporter, the shape, or the user's last answer for this format). */
  upSure?: boolean;
  /** Largest first. */
  pieces: { vertices: number; faces: number; closed: boolean }[];
  /** Bounding box size (file units, taken as metres). */
  size: Vec3;
  /** Its triangles and a trial run (worker/trial.ts): whether Remesh is recommended, and why. */
  cost?: MeshCost;
  /**
   * A model too coarse to shape (`tooCoarse`): the vertices Remesh would give it (tried on a
   * scratch copy; 0 if refused). Where that is no more than it has (an even coarse mesh, a
   * 42-vertex icosphere) Subdivide is recommended instead of Remesh.
   */
  remeshed?: number;
}

/** What a file's triangles will cost to simulate (worker/trial.ts: its triangles and a trial run). */
export interface MeshCost {
  /** The smallest angle (°), the share of angles below 25°, the shortest edge over the mean edge: the worst piece's. */
  minAngle: number; smallShare: number; shortest: number;
  /** Frames the trial finished, and its wall-clock ms per frame (its whole time if none finished). */
  frames: number; msPerFrame: number;
  /** Remesh recommended (asked, checked in the dialog); why, in one line with the numbers (also for poor triangles that run fast: '' if even), and in a few words ('' unless recommended). */
  remesh: boolean; why: string; reason: string;
}

/**
 * `remesh`: remeshed at once after the import (its own undo step); `subdivide`: subdivided so
 * (a model too coarse to shape, `tooCoarse`). `inflate`: a closed piece's
 * gas swells it as the modeler's preset gives it; else (the default) it rests at the file's own
 * shape (`Importer.addPieces`: the freeze under load), so re-importing an export gives back the
 * shape that was exported.
 */
export interface ImportAnswer { up: Up; pieces: 'each' | 'largest'; remesh?: boolean; subdivide?: boolean; inflate?: boolean }

/**
 * A closed model with fewer vertices than this is too coarse for the tools to shape (an
 * 8-vertex box: a grab takes a corner, and a brush between corners finds no vertex): the import
 * dialog offers Remesh and Subdivide.
 */
export const COARSE_VERTICES = 100;

/** The file is a closed model too coarse to shape (fewer than COARSE_VERTICES vertices in all). */
export function tooCoarse(q: Pick<ImportQuestion, 'pieces'>): boolean {
  return q.pieces.some((p) => p.closed) && q.pieces.reduce((n, p) => n + p.vertices, 0) < COARSE_VERTICES;
}

/** What the dialog recommends for a model too coarse to shape: Remesh where it adds vertices (it keeps the shape), else Subdivide. */
export function coarseRemedy(q: Pick<ImportQuestion, 'pieces' | 'remeshed'>): 'remesh' | 'subdivide' {
  const v = q.pieces.reduce((n, p) => n + p.vertices, 0);
  return q.remeshed === undefined || q.remeshed > v ? 'remesh' : 'subdivide';
}

/** Whether anything is left to ask: the up axis is unsure, there are several pieces, Remesh is recommended, or the model is too coarse to shape. */
export function needsAnswer(q: ImportQuestion): boolean {
  return !(q.declaredUp !== null || q.upSure === true) || q.pieces.length > 1 || q.cost?.remesh === true || tooCoarse(q);
}

/** (x, y, z) → (x, z, −y): a Z-up file turned Y-up (−90° about x; windings and lengths kept). */
export function zUpToYUp(p: Float64Array): void {
  for (let i = 0; i < p.length; i += 3) { const y = p[i + 1]; p[i + 1] = p[i + 2]; p[i + 2] = -y; }
}
/** The inverse: (x, y, z) → (x, −z, y). */
export function yUpToZUp(p: Float64Array): void {
  for (let i = 0; i < p.length; i += 3) { const z = p[i + 2]; p[i + 2] = p[i + 1]; p[i + 1] = -z; }
}

export function bounds(lists: ArrayLike<number>[]): { lo: Vec3; hi: Vec3 } {
  const lo: Vec3 = [Infinity, Infinity, Infinity], hi: Vec3 = [-Infinity, -Infinity, -Infinity];
  for (const p of lists) for (let i = 0; i < p.length; i += 3) for (let d = 0; d < 3; d++) {
    lo[d] = Math.min(lo[d], p[i + d]);
    hi[d] = Math.max(hi[d], p[i + d]);
  }
  return { lo, hi };
}

/** A guess of the up axis: the axis, why, and whether it is sure enough to import without asking. */
export interface UpGuess { up: Up; reason: string; sure: boolean }

/**
 * SoftSculpt's own STL and OBJ exports (io/export.ts `exportHeader`): "SoftSculpt export, Y-up, …"
 * at the start of the file (the binary STL's header, an OBJ comment), with the up axis they were
 * written in: Y for built-in models, the imported file's for an import exported back to its frame.
 */
export const OWN_EXPORT = /^\s*(?:#\s*)?SoftSculpt export, ([YZ])-up\b/i;

/**
 * Exporters named in a file's header or comments, with the up axis they write by default
 * (`stated`: the axis the header names, its first group): SoftSculpt says which; Blender writes
 * OBJ Y-up (its OBJ exporter's default: −Z forward, Y up) but STL and PLY in its own Z-up frame
 * (Y forward, Z up); CAD programs and slicers are Z-up.
 */
const EXPORTERS: { re: RegExp; formats: string[]; up: Up | 'stated'; name: string }[] = [
  { re: OWN_EXPORT, formats: ['STL', 'OBJ'], up: 'stated', name: 'SoftSculpt' },
  { re: /blender/i, formats: ['OBJ'], up: 'y', name: "Blender's OBJ export (Y-up by default)" },
  { re: /blender/i, formats: ['STL', 'PLY'], up: 'z', name: "Blender's STL and PLY export (Z-up by default)" },
  { re: /solidworks|autodesk|fusion ?360|inventor|onshape|freecad|openscad|catia|creo|rhino|sketchup|prusaslicer|cura|tinkercad|meshmixer|3ds ?max|zbrush/i,
    formats: ['STL', 'OBJ', 'PLY'], up: 'z', name: 'a Z-up CAD or 3D-printing program' },
];

/** A flat sheet: its thinnest extent at most this share of its largest (a cloth: 0; the
 * kangaroo balloon, the flattest figure among the test models, 0.28). */
const FLAT_SHEET = 0.01;

/** The axis (y: 1 or z: 2) along which extents `ext` make a flat sheet: strictly the thinnest and
 * at most FLAT_SHEET of the largest (a sheet thin along x says nothing of up). */
function flatAxis(ext: number[]): 1 | 2 | undefined {
  const largest = Math.max(...ext);
  return ([1, 2] as const).find((d) => ext[d] <= FLAT_SHEET * largest && ext.every((e, k) => k === d || ext[d] < e));
}

/** Whether the faces at the bottom along axis `d` make a flat base (share of the box's cross-section). */
function flatBase(lists: ArrayLike<number>[], triangles: ArrayLike<number>[], d: number, lo: number, tol: number): number {
  let area = 0;
  lists.forEach((x, k) => {
    const t = triangles[k];
    if (!t) return;
    for (let f = 0; f < t.length; f += 3) {
      const a = 3 * t[f], b = 3 * t[f + 1], c = 3 * t[f + 2];
      if (x[a + d] - lo > tol || x[b + d] - lo > tol || x[c + d] - lo > tol) continue;
      const u = [x[b] - x[a], x[b + 1] - x[a + 1], x[b + 2] - x[a + 2]], v = [x[c] - x[a], x[c + 1] - x[a + 1], x[c + 2] - x[a + 2]];
      area += 0.5 * Math.hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
    }
  });
  return area;
}

/**
 * The up axis to offer for a file that does not declare one, and whether the guess is sure:
 * 1. the exporter its header or comments name (`EXPORTERS`), or the axis SoftSculpt's own
 *    export states on its first line (`OWN_EXPORT`);
 * 2. a flat sheet (one extent, y or z, at most 1 % of the largest) lies flat: that axis is up,
 *    whatever the exporter's default (a cloth exported Z-up from Blender with a Y-up default
 *    header would stand as a wall on its edge); an axis the header states still wins;
 * 3. the shape: a model is made standing on its ground plane — resting on z = 0 and not on
 *    y = 0 says Z-up (and the other way round); else a flat base (faces lying at the lowest
 *    level covering ≥ 10 % of the box's cross-section) at min z and not at min y says Z-up
 *    (and the other way round). Not the flattest extent: a flat figure stands as often as it
 *    lies (the kangaroo balloon, 2.1 × 1.9 × 0.59 m, stands in Y and is thinnest along z; a
 *    sheet of cloth lies flat in Y and is thinnest along y);
 * 4. otherwise unsure: the format's usual convention, STL (CAD and 3D printing) → Z, OBJ and
 *    PLY (Blender's OBJ export, scanners) → Y, and the page asks.
 */
export function guessUp(format: string, lists: ArrayLike<number>[], triangles: ArrayLike<number>[] = [], header = ''): UpGuess {
  const { lo, hi } = bounds(lists);
  const ext = [0, 1, 2].map((d) => hi[d] - lo[d]);
  const exporter = EXPORTERS.map((e) => ({ e, m: e.formats.includes(format) ? e.re.exec(header) : null })).find((x) => x.m);
  if (exporter?.e.up === 'stated') {
    const up = exporter.m![1].toLowerCase() as Up;
    return { up, reason: `written by ${exporter.e.name} as ${up.toUpperCase()}-up`, sure: true };
  }
  const thin = flatAxis(ext);
  if (thin !== undefined) {
    const up: Up = thin === 1 ? 'y' : 'z';
    const against = exporter && exporter.e.up !== up ? `, not ${exporter.e.name}'s default` : '';
    return { up, reason: `it is a flat sheet, lying flat${against}`, sure: true };
  }
  if (exporter) return { up: exporter.e.up as Up, reason: `written by ${exporter.e.name}`, sure: true };
  const diag = Math.hypot(ext[0], ext[1], ext[2]);
  const onPlane = (d: number) => Math.abs(lo[d]) <= 1e-6 * diag;
  if (onPlane(2) && !onPlane(1)) return { up: 'z', reason: 'it rests on the plane z = 0', sure: true };
  if (onPlane(1) && !onPlane(2)) return { up: 'y', reason: 'it rests on the plane y = 0', sure: true };
  const tol = 1e-4 * diag;
  const base = (d: number) => flatBase(lists, triangles, d, lo[d], tol) >= 0.1 * ext[(d + 1) % 3] * ext[(d + 2) % 3];
  const [by, bz] = [base(1), base(2)];
  if (bz && !by) return { up: 'z', reason: 'its flat base is at its lowest z', sure: true };
  if (by && !bz) return { up: 'y', reason: 'its flat base is at its lowest y', sure: true };
  if (format === 'STL') return { up: 'z', reason: 'STL files mostly come from CAD and 3D printing, which are Z-up', sure: false };
  return { up: 'y', reason: `${format} files mostly come Y-up (Blender's OBJ export and scanners)`, sure: false };
}

/** A file's first bytes as text (headers and comments name their exporter): at most `n` bytes, printable ASCII only. */
export function headerText(data: Uint8Array, n = 4096): string {
  let s = '';
  for (let i = 0; i < Math.min(n, data.length); i++) { const c = data[i]; s += c >= 32 && c < 127 ? String.fromCharCode(c) : ' '; }
  return s;
}

/**
 * The question for a file the engine has read (`lists`: each piece's positions, as in the file;
 * `triangles` its faces; `header` its first bytes as text). `remembered`: the up axis the user
 * chose or corrected for files by name (io/upaxis.ts), which settles this file's guess, sure
 * or not, without asking (not a glTF's declared Y).
 */
export function question(name: string, report: FileReport, lists: ArrayLike<number>[], triangles: ArrayLike<number>[] = [], header = '', remembered: Record<string, Up> = {}): ImportQuestion {
  const format = report.format ?? '?';
  const declaredUp = report.up_axis === 'unknown' ? null : report.up_axis;
  let guess: UpGuess = declaredUp ? { up: declaredUp, reason: `${format} files are Y-up by specification`, sure: true } : guessUp(format, lists, triangles, header);
  const last = declaredUp ? undefined : remembered[name];
  if (last === 'y' || last === 'z') guess = { up: last, reason: `as you chose for ${name} before`, sure: true };
  const { lo, hi } = bounds(lists);
  return {
    name, format, declaredUp, guessedUp: guess.up, guessReason: guess.reason, upSure: guess.sure,
    pieces: report.pieces.map((p) => ({ vertices: p.vertices, faces: p.faces, closed: p.closed })),
    size: [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]],
  };
}

/**
 * The pieces' positions in the engine's frame (turned Y-up if `up` is 'z', then standing on the
 * ground at the origin, all by one offset), and that frame.
 */
export function place(lists: Float64Array[], up: Up): { positions: Float64Array[]; frame: ImportFrame } {
  const turned = lists.map((p) => { const q = p.slice(); if (up === 'z') zUpToYUp(q); return q; });
  const { lo, hi } = bounds(turned);
  const offset: Vec3 = [(lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2];
  for (const p of turned) for (let i = 0; i < p.length; i += 3) for (let d = 0; d < 3; d++) p[i + d] -= offset[d];
  return { positions: turned, frame: { up, offset } };
}

/** Engine positions back in the file's coordinates; `yUp` keeps them Y-up (glTF's convention). */
export function toFile(positions: ArrayLike<number>, frame: ImportFrame, yUp = false): Float64Array {
  const out = Float64Array.from(positions);
  for (let i = 0; i < out.length; i += 3) for (let d = 0; d < 3; d++) out[i + d] += frame.offset[d];
  if (frame.up === 'z' && !yUp) yUpToZUp(out);
  return out;
}

/** The model's size relative to the modeler's reference model (bounding-box diagonal / 2.5 m). */
export function sizeFactor(lists: ArrayLike<number>[]): number {
  const { lo, hi } = bounds(lists);
  const diag = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  return diag > 0 && Number.isFinite(diag) ? diag / REFERENCE_DIAGONAL : 1;
}

/** Closed and manifold: every edge of the triangles is shared by exactly two of them. */
export function isClosed(triangles: ArrayLike<number>): boolean {
  const count = new Map<number, number>();
  const n = triangles.length;
  for (let t = 0; t < n; t += 3) for (let k = 0; k < 3; k++) {
    const a = triangles[t + k], b = triangles[t + ((k + 1) % 3)];
    const key = Math.min(a, b) * 0x100000000 + Math.max(a, b);
    count.set(key, (count.get(key) ?? 0) + 1);
  }
  for (const c of count.values()) if (c !== 2) return false;
  return n > 0;
}
