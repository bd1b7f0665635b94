// Mirror symmetry for the tools (as SculptGL and Blender's sculpt mode): a stroke at a point also
// acts at its mirror images across the planes through the model's centre normal to the chosen
// axes (X, Y, Z; several axes give every combination: up to 8 points). X is on by default for a
// model that is symmetric across x (`isSymmetric`).

import type { Vec3 } from '../protocol';

export type Axes = [boolean, boolean, boolean];

/** Where a stroke's mirror images are: the chosen axes and the plane's centre (m). */
export interface Symmetry { axes: Axes; centre: Vec3 }

/** The reflections to apply: sign triples, the identity first. */
export function reflections(axes: Axes): Vec3[] {
  const out: Vec3[] = [[1, 1, 1]];
  for (let mask = 1; mask < 8; mask++) {
    if ([0, 1, 2].some((d) => (mask >> d) & 1 && !axes[d])) continue;
    out.push([0, 1, 2].map((d) => ((mask >> d) & 1 ? -1 : 1)) as Vec3);
  }
  return out;
}

/** `p` reflected by the sign triple `s` about `centre`. */
export function reflect(p: ArrayLike<number>, s: Vec3, centre: Vec3): Vec3 {
  return [0, 1, 2].map((d) => centre[d] + s[d] * (p[d] - centre[d])) as Vec3;
}

/** A direction (an offset, a normal) reflected by `s`. */
export function reflectVector(v: ArrayLike<number>, s: Vec3): Vec3 {
  return [s[0] * v[0], s[1] * v[1], s[2] * v[2]];
}

/** The centre of the bounding box of flat xyz `positions`. */
export function boxCentre(positions: ArrayLike<number>): Vec3 {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) {
    for (let d = 0; d < 3; d++) {
      lo[d] = Math.min(lo[d], positions[i + d]);
      hi[d] = Math.max(hi[d], positions[i + d]);
    }
  }
  return positions.length ? [0, 1, 2].map((d) => (lo[d] + hi[d]) / 2) as Vec3 : [0, 0, 0];
}

/**
 * Whether the point cloud is its own mirror image across the plane through its box centre normal
 * to `axis`, up to `tolerance` (m): every vertex's image has a vertex within it (a hash grid of
 * that cell size; each image looks in its cell and the 26 around it). A shape tessellated without
 * mirrored vertices (the mushroom) is symmetric up to about an edge length: pass a fraction of
 * the mean edge length (`meanEdge`).
 */
export function isSymmetric(positions: ArrayLike<number>, axis: 0 | 1 | 2, tolerance: number): boolean {
  const n = positions.length / 3;
  if (n === 0 || !(tolerance > 0)) return false;
  const c = boxCentre(positions);
  const h = tolerance;
  const key = (x: number, y: number, z: number) => `${Math.floor(x / h)},${Math.floor(y / h)},${Math.floor(z / h)}`;
  const grid = new Map<string, number[]>();
  for (let i = 0; i < n; i++) {
    const k = key(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    const cell = grid.get(k);
    if (cell) cell.push(i); else grid.set(k, [i]);
  }
  const s: Vec3 = [1, 1, 1];
  s[axis] = -1;
  for (let i = 0; i < n; i++) {
    const p = reflect([positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]], s, c);
    const [gx, gy, gz] = p.map((v) => Math.floor(v / h));
    let found = false;
    for (let dx = -1; dx <= 1 && !found; dx++) for (let dy = -1; dy <= 1 && !found; dy++) for (let dz = -1; dz <= 1 && !found; dz++) {
      for (const j of grid.get(`${gx + dx},${gy + dy},${gz + dz}`) ?? []) {
        if (Math.hypot(positions[3 * j] - p[0], positions[3 * j + 1] - p[1], positions[3 * j + 2] - p[2]) <= h) { found = true; break; }
      }
    }
    if (!found) return false;
  }
  return true;
}

/** The mean length (m) of the edges `pairs` (flat vertex index pairs) at `positions`. */
export function meanEdge(positions: ArrayLike<number>, pairs: ArrayLike<number>): number {
  let sum = 0;
  for (let k = 0; k < pairs.length; k += 2) {
    const i = 3 * pairs[k], j = 3 * pairs[k + 1];
    sum += Math.hypot(positions[i] - positions[j], positions[i + 1] - positions[j + 1], positions[i + 2] - positions[j + 2]);
  }
  return pairs.length ? sum / (pairs.length / 2) : 0;
}
