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
export interface ImportFrame { up: Up; offset: Vec3 }
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
  /** Largest first. */
  pieces: { vertices: number; faces: number; closed: boolean }[];
  /** Bounding box size (file units, taken as metres). */
  size: Vec3;
}

export interface ImportAnswer { up: Up; pieces: 'each' | 'largest' }

/** Whether anything is left to ask: the up axis is not declared, or there are several pieces. */
export function needsAnswer(q: ImportQuestion): boolean {
  return q.declaredUp === null || q.pieces.length > 1;
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

/**
 * The up axis to offer for a file that does not declare one. A model is usually made standing
 * on its ground plane: if it rests on z = 0 and not on y = 0 it is Z-up, and the other way
 * round; otherwise STL (CAD and 3D printing, Z-up) → Z, OBJ and PLY (Blender's and the scanners'
 * default exports) → Y.
 */
export function guessUp(format: string, lists: ArrayLike<number>[]): { up: Up; reason: string } {
  const { lo, hi } = bounds(lists);
  const diag = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const onPlane = (d: number) => Math.abs(lo[d]) <= 1e-6 * diag;
  if (onPlane(2) && !onPlane(1)) return { up: 'z', reason: 'it rests on the plane z = 0' };
  if (onPlane(1) && !onPlane(2)) return { up: 'y', reason: 'it rests on the plane y = 0' };
  if (format === 'STL') return { up: 'z', reason: 'STL files mostly come from CAD and 3D printing, which are Z-up' };
  return { up: 'y', reason: `${format} files mostly come Y-up (Blender's and scanners' default)` };
}

/** The question for a file the engine has read (`lists`: each piece's positions, as in the file). */
export function question(name: string, report: FileReport, lists: ArrayLike<number>[]): ImportQuestion {
  const format = report.format ?? '?';
  const declaredUp = report.up_axis === 'unknown' ? null : report.up_axis;
  const guess = declaredUp ? { up: declaredUp, reason: `${format} files are Y-up by specification` } : guessUp(format, lists);
  const { lo, hi } = bounds(lists);
  return {
    name, format, declaredUp, guessedUp: guess.up, guessReason: guess.reason,
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
