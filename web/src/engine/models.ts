// The built-in models as bodies of a world, standing on the ground, with the modeler's default
// world and a stable time step.

import bunny from 'bunny';
import { World } from './world';
import { gasAmount, placeOnGround, type ModelName } from '../models';

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
  if (name === 'mushroom') {
    // Rooted: the foot of the stem is pinned to the ground, as a mushroom grows (otherwise the
    // heavy cap on a soft stem tips over at the first touch).
    const x = world.body(b).positions;
    const pins = Uint8Array.from({ length: x.length / 3 }, (_, i) => (x[3 * i + 1] < 0.01 ? 1 : 0));
    world.setPins(b, pins);
  }
  return b;
}

/**
 * The modeler's default world for body `b`: gravity, ground at y = 0, gas, damping, and the
 * largest stable time step for the body (see `stableDt`), set as the world's dt.
 */
export function useDefaults(world: World, b: number): number {
  world.setParam(b, 'stiffness', 100);
  // Spring damping as a rate per vertex mass (cs / m = 36 1/s, i.e. 0.1 N·s/m on the 362-vertex
  // mushroom of 1 kg), so fine meshes are damped alike and do not force a tiny step.
  world.setParam(b, 'spring_damping', 36 * minMass(world, b));
  // Bending springs as stiff as the edges: the surface resists folding, so a mushroom's stem
  // carries its cap instead of buckling.
  world.setParam(b, 'bending', 100);
  world.setParam(b, 'damping', 1.5);
  world.setParam(b, 'gravity', 9.81);
  world.setParam(b, 'ground', true);
  world.setParam(b, 'ground.height', 0);
  world.setParam(b, 'ground.friction', 0.5);
  world.setParam(b, 'gas.temperature', 300);
  world.setParam(b, 'gas.amount', gasAmount(30));
  const dt = stableDt(world, b);
  world.setParam(b, 'dt', dt);
  return dt;
}

function minMass(world: World, b: number): number {
  return world.body(b).masses.reduce((a, m) => Math.min(a, m), Infinity);
}

/**
 * The largest stable time step for body `b` (explicit methods need dt ≲ 2/ω with ω² ≈ 12 k / m,
 * and dt ≲ 2 m / (12 cs) for the spring damping), with a safety factor of 0.3, at most 1 ms, a
 * round number.
 */
export function stableDt(world: World, b: number): number {
  const p = world.params(b);
  const m = minMass(world, b);
  const k = (p.stiffness as number) + (p.bending as number), cs = 2 * (p.spring_damping as number);
  const omega = Math.sqrt((12 * k) / m);
  const limits = [1e-3, 0.3 * (2 / omega)];
  if (cs > 0) limits.push((0.3 * 2 * m) / (12 * cs));
  const dt = Math.min(...limits);
  const ten = Math.pow(10, Math.floor(Math.log10(dt)));
  return [5, 2, 1].map((f) => f * ten).find((v) => v <= dt) ?? ten;
}
