// The built-in models as bodies of a world, standing on the ground, with the modeler's default
// world: implicit steps of 1/60 s, material parameters independent of the mesh resolution.

import bunny from 'bunny';
import { World } from './world';
import { placeOnGround, type ModelName } from '../models';

/** A built-in model (or the Stanford bunny), standing on y = 0, added to `world`; its index. */
export function addModel(world: World, name: ModelName): number {
  let positions: Float64Array, indices: Uint32Array, prepare = false;
  if (name === 'bunny') {
    positions = placeOnGround(new Float64Array((bunny.positions as number[][]).flat()), 2.5).positions;
    indices = new Uint32Array((bunny.cells as number[][]).flat());
    prepare = true;
  } else {
    const scratch = World.create();
    try {
      scratch.addBuiltin(name);
      positions = placeOnGround(scratch.body(0).positions.slice()).positions;
      indices = scratch.body(0).triangles.slice();
    } finally {
      scratch.free();
    }
  }
  const b = world.addMesh(positions, indices, 1, prepare);
  if (name === 'mushroom' || name === 'kangaroo') {
    // Rooted: the foot of the stem is pinned to the ground, as a mushroom grows (otherwise the
    // heavy cap on a soft stem tips over at the first touch); the kangaroo, a sketched pillow
    // thin across, stands on its pinned feet instead of falling on its side.
    const x = world.body(b).positions;
    let lo = Infinity;
    for (let i = 1; i < x.length; i += 3) lo = Math.min(lo, x[i]);
    // The pillow's sole is its seam: a band 8 cm high pins both faces of the feet, not a hinge.
    const band = name === 'kangaroo' ? 0.08 : 0.01;
    const pins = Uint8Array.from({ length: x.length / 3 }, (_, i) => (x[3 * i + 1] < lo + band ? 1 : 0));
    world.setPins(b, pins);
  }
  return b;
}

/** The modeler's step: one backward-Euler step of 1/60 s per frame. */
export const FRAME_DT = 1 / 60;

/** Steps of `dt` (s) in one frame of FRAME_DT: the nearest whole number, at least one. */
export function stepsPerFrame(dt: number): number {
  return Math.max(1, Math.round(FRAME_DT / dt));
}
/**
 * The modeler's default world for body `b`: gravity, ground at y = 0, gas, damping, implicit
 * stepping at dt = 1/60 s (set as the world's dt, returned).
 *
 * Every material parameter is independent of the mesh resolution, so a subdivision keeps the
 * body's behaviour (docs: web/README.md, "Defaults"):
 * - springs: a lattice of springs k has the membrane (2D Young's) modulus 2k/√3 whatever its
 *   edge length, so k stays 100 N/m on every mesh;
 * - spring damping: likewise a membrane viscosity 2cs/√3 (N·s/m), so cs stays fixed (0.1 N·s/m,
 *   what the 362-vertex mushroom had); explicit steps of fine meshes then need smaller dt (they
 *   get it from `stableDt`), implicit ones do not;
 * - viscous damping c (1/s) and gravity act per unit mass; the mass (1 kg) is spread over the
 *   vertices, so density per area is fixed; the gas amount is set by a pressure;
 * - bending springs k_b = k: their in-plane share is resolution-independent like the edges';
 *   their resistance to folding falls with the edge length, which hinges of flexural rigidity
 *   D (J) make up for: D does not depend on the resolution (crates/softsculpt/src/body/hinges.rs);
 * - the implicit tolerance 1e-3 was measured in the browser at 1e-3, 1e-4 and 1e-6
 *   (BENCHMARKS.md, "The modeler on implicit steps").
 */
export function useDefaults(world: World, b: number): number {
  // The values and why each is what it is: the core's `modeler` preset
  // (crates/softsculpt/src/params/presets.rs, docs/parameters.md).
  world.applyPreset(b, 'modeler');
  return FRAME_DT;
}

/**
 * The step an integrator gets when chosen: 1/60 s implicit, else the stable explicit step of
 * every body (the core's `World::stable_dt`, docs/model.md).
 */
export function dtFor(world: World, integrator: string): number {
  return integrator === 'implicit' ? FRAME_DT : world.stableDt(integrator);
}

