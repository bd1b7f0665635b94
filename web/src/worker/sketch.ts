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
