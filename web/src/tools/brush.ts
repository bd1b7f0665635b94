// Brush maths shared by the tools: which vertices and faces a brush covers, and how much.

/** Smooth falloff (1 − (d/r)²)² for d < r, else 0: 1 at the centre, zero slope at the rim. */
export function falloff(d: number, r: number): number {
  if (!(r > 0) || d >= r) return 0;
  const q = 1 - (d * d) / (r * r);
  return q * q;
}

export interface Weighted {
  indices: number[];
  weights: number[];
}

/** Vertices (flat xyz positions) within `radius` of `centre`, with their falloff weights. */
export function verticesAround(positions: ArrayLike<number>, centre: [number, number, number], radius: number): Weighted {
  const out: Weighted = { indices: [], weights: [] };
  for (let i = 0; i < positions.length / 3; i++) {
    const dx = positions[3 * i] - centre[0], dy = positions[3 * i + 1] - centre[1], dz = positions[3 * i + 2] - centre[2];
    const w = falloff(Math.sqrt(dx * dx + dy * dy + dz * dz), radius);
    if (w > 0) { out.indices.push(i); out.weights.push(w); }
  }
  return out;
}

/** Faces whose centroid lies within `radius` of `centre`, with falloff weights. */
export function facesAround(positions: ArrayLike<number>, triangles: ArrayLike<number>, centre: [number, number, number], radius: number): Weighted {
  const out: Weighted = { indices: [], weights: [] };
  for (let f = 0; f < triangles.length / 3; f++) {
    const c = [0, 0, 0];
    for (let k = 0; k < 3; k++) for (let d = 0; d < 3; d++) c[d] += positions[3 * triangles[3 * f + k] + d] / 3;
    const w = falloff(Math.hypot(c[0] - centre[0], c[1] - centre[1], c[2] - centre[2]), radius);
    if (w > 0) { out.indices.push(f); out.weights.push(w); }
  }
  return out;
}

/**
 * Grab spring on one vertex (N): F = m w (ω² (target − x) − ω v). A critically-damped-ish pull
 * whose stiffness scales with the vertex mass, so every body feels the same under the mouse
 * and the explicit step stays stable (ω dt ≪ 2).
 */
export function grabForce(mass: number, weight: number, omega: number, target: number, x: number, v: number): number {
  return mass * weight * (omega * omega * (target - x) - omega * v);
}

/** Per-vertex rest-length factor for one frame of the inflate brush (rate in 1/s, dt in s). */
export function inflateFactor(weight: number, rate: number, dt: number, deflate: boolean): number {
  const f = 1 + rate * weight * dt;
  return deflate ? 1 / f : f;
}
