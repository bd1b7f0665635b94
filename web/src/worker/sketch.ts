// The sketch tool's work in the worker: the outline drawn in the view plane becomes a balloon
// (the engine's `sketch`: a pillow of a quality triangulation, inflated to rest), placed back in
// that plane and standing on the ground.

import { World } from '../engine/world';
import { placeOnGround } from '../models';
import type { Command } from '../protocol';

export type SketchCommand = Extract<Command, { type: 'sketch' }>;

/** The balloon of `cmd`'s outline: positions in the world (standing on y = 0) and triangles. Throws the engine's error for a bad outline. */
export function sketchBalloon(cmd: SketchCommand): { positions: Float64Array; triangles: Uint32Array } {
  const scratch = World.create();
  try {
    scratch.addSketch(Float64Array.from(cmd.points));
    const b = scratch.body(0);
    const x = b.positions, out = new Float64Array(x.length);
    const { origin: o, right: r, up: u, normal: n } = cmd;
    // The sketch's x y are the plane's coordinates; its z (the thickness) goes along the normal.
    for (let i = 0; i < x.length; i += 3) {
      for (let d = 0; d < 3; d++) out[i + d] = o[d] + x[i] * r[d] + x[i + 1] * u[d] + x[i + 2] * n[d];
    }
    return { positions: placeOnGround(out).positions, triangles: b.triangles.slice() };
  } finally {
    scratch.free();
  }
}

/**
 * Whether a drawn outline was left open: its ends farther apart than a quarter of its size (the
 * larger side of its bounding box). The core closes any outline with a straight edge, which is
 * what a user who stopped short means, but one who drew an open curve (an S) gets a flat balloon
 * and should hear why. `points`: x, y pairs (m) in the sketch plane.
 */
export function sketchOpen(points: ArrayLike<number>): boolean {
  const n = points.length / 2;
  if (n < 2) return false;
  const lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  for (let i = 0; i < n; i++) for (let d = 0; d < 2; d++) { lo[d] = Math.min(lo[d], points[2 * i + d]); hi[d] = Math.max(hi[d], points[2 * i + d]); }
  const size = Math.max(hi[0] - lo[0], hi[1] - lo[1]);
  const gap = Math.hypot(points[2 * n - 2] - points[0], points[2 * n - 1] - points[1]);
  return size > 0 && gap > 0.25 * size;
}

/**
 * The core's reason a sketch was refused, in the page's words: the core names a crossing by its
 * edges' numbers and coordinates (what a CLI user, whose outline is a file of points, needs);
 * on the page the user drew it, so the advice is what to draw.
 */
export function sketchWhy(why: string): string {
  return /crosses itself/.test(why) ? 'the outline crosses itself; draw it without crossing' : why;
}
