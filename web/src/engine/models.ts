// The built-in models as engine bodies, standing on the ground, with the modeler's default world
// and a stable time step.

import bunny from 'bunny';
import { SoftBody } from './softbody';
import { gasAmount, placeOnGround, type ModelName } from '../models';

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
