// The wind W blows by default: a speed chosen for the body, not a fixed 5 m/s (which blew a
// light sketched balloon out of view in 4 s and hardly moved a heavy one). The model's wind is a
// linear, one-sided drag (docs/model.md): a face whose outward normal n̂ meets the wind w = s d̂
// (d̂ · n̂ < 0) feels F = cw · area · (w · n̂) n̂, so at rest the drag along d̂ is
//
//     F = cw s Σ area (d̂ · n̂)²        (windward faces)
//
// and the speed whose drag is a fraction φ of the body's weight is s = φ m g / (cw Σ area (d̂·n̂)²).
// With φ = 0.2 the wind leans a body by what a fifth of its weight pushing sideways does: the
// pinned mushroom bends visibly (5 m/s bent its stem over), and a free body drifts at most
// φ g / c = 1.3 m/s at the modeler's damping c = 1.5 1/s (a light sketched balloon at 5 m/s
// left the view in 4 s); the view follows a drifting body (view/camera.ts `follow`).

import { Vector3, type Camera } from 'three';
import type { Vec3 } from '../protocol';
import type { Mirror } from '../mirror';

/** The default wind's drag on a body at rest, as a fraction of its weight. */
export const WIND_WEIGHT_FRACTION = 0.2;
/** g used when gravity is off (standard gravity, m/s²): the wind still scales with the body. */
const STANDARD_GRAVITY = 9.81;
/** The panel's wind slider ends here (m/s); the default stays within it. */
export const WIND_MAX = 30;

/** Σ area (d̂ · n̂)² over the faces facing into the wind along unit `d` (m²). */
export function windwardArea(positions: ArrayLike<number>, triangles: ArrayLike<number>, d: Vec3): number {
  let sum = 0;
  for (let f = 0; f < triangles.length; f += 3) {
    const a = 3 * triangles[f], b = 3 * triangles[f + 1], c = 3 * triangles[f + 2];
    const u = [positions[b] - positions[a], positions[b + 1] - positions[a + 1], positions[b + 2] - positions[a + 2]];
    const v = [positions[c] - positions[a], positions[c + 1] - positions[a + 1], positions[c + 2] - positions[a + 2]];
    // n · area = (u × v) / 2; (d̂ · n̂)² area = (d̂ · (u × v))² / (2 |u × v|).
    const cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
    const dn = d[0] * cx + d[1] * cy + d[2] * cz, len = Math.hypot(cx, cy, cz);
    if (dn < 0 && len > 0) sum += (dn * dn) / (2 * len);
  }
  return sum;
}

/**
 * The default wind speed (m/s) along unit `d` for a body of `mass` kg at `positions` with
 * `triangles`, under drag coefficient `cw` (N·s/m³) and gravity `g` (m/s²): its drag at rest is
 * WIND_WEIGHT_FRACTION of the weight, within (0, WIND_MAX]. Without drag (cw = 0) the wind does
 * nothing at any speed: 5 m/s, the old default.
 */
export function defaultWindSpeed(positions: ArrayLike<number>, triangles: ArrayLike<number>, mass: number, d: Vec3, cw: number, g: number): number {
  const area = windwardArea(positions, triangles, d);
  if (!(cw > 0) || !(area > 0) || !(mass > 0)) return 5;
  const weight = mass * (g !== 0 ? Math.abs(g) : STANDARD_GRAVITY);
  return Math.min(WIND_MAX, (WIND_WEIGHT_FRACTION * weight) / (cw * area));
}

/**
 * The direction W blows: across the view, from the screen's left to its right, level (the
 * camera's right on the ground plane, unit). A wind along the line of sight leans the model
 * towards or away from the viewer, where a lean of 10 cm shows as a few pixels. A camera whose
 * right is vertical (a trackball rolled a quarter round) blows across the view direction's
 * level part instead.
 */
export function acrossView(camera: Camera): Vec3 {
  camera.updateMatrixWorld();
  const e = camera.matrixWorld.elements;
  let x = e[0], z = e[2];
  if (Math.hypot(x, z) < 1e-6) {
    // Right is vertical: the view direction (−local z) turned a quarter round about up.
    x = e[10]; z = -e[8];
  }
  const n = Math.hypot(x, z);
  return n > 1e-9 ? [x / n, 0, z / n] : [1, 0, 0];
}

/** The direction along the view (unit): where the camera looks. */
export function alongView(camera: Camera): Vec3 {
  const d = camera.getWorldDirection(new Vector3());
  return [d.x, d.y, d.z];
}

/**
 * The default speed for a wind along unit `d` (W's: across the view, `acrossView`), for the
 * active body as it is.
 */
export function viewWindSpeed(app: { mirror: Mirror; viewport: { camera: Camera } }, d: Vec3 = acrossView(app.viewport.camera)): number {
  const m = app.mirror, p = m.params;
  const num = (v: unknown, fallback: number) => (typeof v === 'number' ? v : fallback);
  return defaultWindSpeed(m.positions, m.triangles, m.totalMass, d, num(p.wind_drag, 1), num(p.gravity, STANDARD_GRAVITY));
}
