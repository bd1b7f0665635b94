// The models the modeler offers, how a mesh is placed on the ground, gas as nRT.
// (Loading them into the engine and their default settings: engine/models.ts.)

import { GAS_CONSTANT } from './engine/params';

/** R (J/(mol·K)), the engine's (generated from its parameter table). */
export { GAS_CONSTANT };

export const MODELS = ['mushroom', 'sphere', 'octopus', 'kangaroo', 'bunny'] as const;
export type ModelName = (typeof MODELS)[number];

/** Positions scaled to fit a `size` m bounding-box diagonal (if `fit`), centred in x and z, lowest point at y = 0. */
export function placeOnGround(positions: Float64Array, fit: number | null = null): { positions: Float64Array; scale: number } {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) for (let d = 0; d < 3; d++) { lo[d] = Math.min(lo[d], positions[i + d]); hi[d] = Math.max(hi[d], positions[i + d]); }
  const diag = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const scale = fit && diag > 0 ? fit / diag : 1;
  const c = [(lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2];
  const out = new Float64Array(positions.length);
  for (let i = 0; i < positions.length; i += 3) for (let d = 0; d < 3; d++) out[i + d] = (positions[i + d] - c[d]) * scale;
  return { positions: out, scale };
}

/** Gas as the product nRT (J) → amount n (mol) at temperature T (K). */
export function gasAmount(nrt: number, temperature = 300): number {
  return nrt / (GAS_CONSTANT * temperature);
}
