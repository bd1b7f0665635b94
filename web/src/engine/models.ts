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

/** The step an integrator gets when chosen: 1/60 s implicit, else the stable explicit step. */
export function dtFor(world: World, b: number, integrator: string): number {
  return integrator === 'implicit' ? FRAME_DT : stableDt(world, b, integrator);
}

function minMass(world: World, b: number): number {
  return world.body(b).masses.reduce((a, m) => Math.min(a, m), Infinity);
}

/**
 * Forward Euler's share of that step. Its amplification on an undamped mode of frequency ω is
 * √(1 + ω² dt²) > 1 at any dt: it is stable only where damping outweighs that, dt ≲ 2 γ / ω²
 * for a mode damped at rate γ — and the skin's transverse (wrinkling) modes get no spring
 * damping (it acts along the springs), only the viscous c. Measured: the modeler's resting
 * mushroom switched to Euler at the symplectic step (5e-4 s) grew a mode ~8× a second from 6 s
 * on (6.5e-5 J at 10 s; a new-user trial saw 3 m/s and 0.2 J), while at 2e-4 and 1e-4 s it
 * stayed at rest (test/explicit.test.ts); natively, from the unsettled mushroom, 5e-4 s still
 * moved at 0.09 m/s after 4 s, 2.5e-4 s settled. A quarter leaves a margin of two over that.
 */
const EULER_SHARE = 0.25;

/**
 * The hinges' share of the stiffness in `stableDt` (N/m, as if springs): their Gauss–Newton
 * matrix D w ∇θ ∇θᵀ (crates/softsculpt/src/body/hinges.rs) bounded by Gershgorin on a vertex of
 * a near-equilateral mesh of shortest edge h: |∇θ| ≤ 2/(√3 h) at each of a hinge's four
 * vertices, w = 2/√3, 12 hinges around a vertex: ω² ≤ 12 · D (2/√3)(2/(√3 h))(4 · 2/(√3 h)) / m
 * = 74 D / (h² m), against 12 k / m for springs: k_h = 6.2 D / h² (it grows 4× per
 * subdivision: bending limits explicit steps as h², where the implicit step does not care).
 */
function hingeStiffness(world: World, b: number): number {
  const d = (world.params(b).rigidity as number | undefined) ?? 0;
  if (!(d > 0)) return 0;
  const h = world.body(b).rest.reduce((a, l) => (l > 0 ? Math.min(a, l) : a), Infinity);
  return Number.isFinite(h) ? (6.2 * d) / (h * h) : 0;
}

/**
 * The largest stable time step for body `b` (explicit methods need dt ≲ 2/ω with ω² ≈ 12 k / m,
 * and dt ≲ 2 m / (12 cs) for the spring damping), with a safety factor of 0.3 (and
 * [`EULER_SHARE`] of that for forward Euler), at most 1 ms, a round number.
 */
export function stableDt(world: World, b: number, integrator = 'symplectic'): number {
  const p = world.params(b);
  const m = minMass(world, b);
  const k = (p.stiffness as number) + (p.bending as number) + hingeStiffness(world, b), cs = 2 * (p.spring_damping as number);
  const omega = Math.sqrt((12 * k) / m);
  const limits = [1e-3, 0.3 * (2 / omega)];
  if (cs > 0) limits.push((0.3 * 2 * m) / (12 * cs));
  // The hinges' damping D w τ θ̇ (τ = c_s / k, core: body/hinges.rs) like the springs' c_s: a
  // mode of ω_h² = 12 k_h / m damped at τ ω_h² / 2 needs dt ≲ 2 / (τ ω_h²). Forward Euler on
  // such a mode (amplification √((1 − γ dt)² + ω² dt²), γ = (c + τ ω²) / 2) is stable for
  // dt ≤ 2γ / (ω² + γ²) ≈ τ / (1 + τ² ω² / 4) where τ ω² dominates, else only while
  // dt ≤ c / ω_h² (the viscous c alone; [`EULER_SHARE`] leaves a margin of four on both).
  const kh = hingeStiffness(world, b);
  if (kh > 0) {
    const w2 = (12 * kh) / m, tau = (p.stiffness as number) > 0 ? (p.spring_damping as number) / (p.stiffness as number) : 0;
    if (tau > 0) limits.push((0.3 * 2) / (tau * w2));
    // (Neither τ nor c: forward Euler has no stable step on these modes; the others' limit stands.)
    const euler = Math.max(tau / (1 + (tau * tau * w2) / 4), (p.damping as number) / w2);
    if (integrator === 'euler' && euler > 0) limits.push(euler);
  }
  const dt = Math.min(...limits) * (integrator === 'euler' ? EULER_SHARE : 1);
  const ten = Math.pow(10, Math.floor(Math.log10(dt)));
  return [5, 2, 1].map((f) => f * ten).find((v) => v <= dt) ?? ten;
}
