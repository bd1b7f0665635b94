// The models the modeler offers, and how a body is placed and given stable default settings.

import bunny from 'bunny';
import { SoftBody } from './engine/softbody';
import { GAS_CONSTANT } from './engine/params';

export const MODELS = ['mushroom', 'sphere', 'octopus', 'bunny'] as const;
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

/** A built-in model (or the Stanford bunny), standing on y = 0. */
export function loadModel(name: ModelName): SoftBody {
  let positions: Float64Array, indices: Uint32Array, weld = false;
  if (name === 'bunny') {
    positions = new Float64Array((bunny.positions as number[][]).flat());
    indices = new Uint32Array((bunny.cells as number[][]).flat());
    weld = true;
    positions = placeOnGround(positions, 2.5).positions;
  } else {
    const b = SoftBody.builtin(name);
    positions = placeOnGround(b.positions().slice()).positions;
    indices = b.triangles().slice();
    b.free();
  }
  const body = SoftBody.fromMesh(positions, indices, 1, weld);
  if (name === 'mushroom') {
    // Rooted: the foot of the stem is pinned to the ground, as a mushroom grows (otherwise the
    // heavy cap on a soft stem tips over at the first touch).
    const x = body.positions();
    for (let i = 0; i < body.vertexCount; i++) if (x[3 * i + 1] < 0.01) body.setPinned(i, true);
  }
  return body;
}

/** Gas as the product nRT (J) → amount n (mol) at temperature T (K). */
export function gasAmount(nrt: number, temperature = 300): number {
  return nrt / (GAS_CONSTANT * temperature);
}

/**
 * The default world: gravity, ground at y = 0, gas, damping; the largest stable time step for the
 * body (explicit methods need dt ≲ 2/ω with ω² ≈ 12 k / m, and dt ≲ 2 m / (12 cs) for the spring
 * damping), taken with a safety factor of 0.3 and at most 1 ms.
 */
export function defaultSettings(body: SoftBody): { dt: number } {
  body.set('stiffness', 100);
  // Spring damping as a rate per vertex mass (cs / m = 36 1/s, i.e. 0.1 N·s/m on the 362-vertex
  // mushroom of 1 kg), so fine meshes are damped alike and do not force a tiny step.
  const m = body.masses().reduce((a, b) => Math.min(a, b), Infinity);
  body.set('springDamping', 36 * m);
  // Bending springs as stiff as the edges: the surface resists folding, so a mushroom's stem
  // carries its cap instead of buckling.
  body.set('bendingStiffness', 100);
  body.set('damping', 1.5);
  body.set('gravity', 9.81);
  body.set('groundOn', 1);
  body.set('groundHeight', 0);
  body.set('friction', 0.5);
  body.set('temperature', 300);
  body.set('gasAmount', gasAmount(30));
  return { dt: stableDt(body) };
}

export function stableDt(body: SoftBody): number {
  const m = body.masses().reduce((a, b) => Math.min(a, b), Infinity);
  const k = body.get('stiffness') + body.get('bendingStiffness'), cs = 2 * body.get('springDamping');
  const omega = Math.sqrt((12 * k) / m);
  const limits = [1e-3, 0.3 * (2 / omega)];
  if (cs > 0) limits.push((0.3 * 2 * m) / (12 * cs));
  const dt = Math.min(...limits);
  // A round number: 1, 2 or 5 times a power of ten.
  const p = Math.pow(10, Math.floor(Math.log10(dt)));
  return [5, 2, 1].map((f) => f * p).find((v) => v <= dt) ?? p;
}
