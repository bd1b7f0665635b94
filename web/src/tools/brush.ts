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

/**
 * A tool's target spring on one vertex of mass `mass` under brush weight `weight`, at angular
 * frequency ω (1/s): stiffness m w ω² (N/m) and critical damping 2 m w ω (N·s/m). Scaling with
 * the vertex mass makes the pull per unit of surface the same on any mesh resolution; the
 * implicit step takes it exactly, so any ω is stable.
 */
export function targetSpring(mass: number, weight: number, omega: number): { stiffness: number; damping: number } {
  return { stiffness: mass * weight * omega * omega, damping: 2 * mass * weight * omega };
}

/** Unit outward vertex normals (area-weighted face normals) of a closed, outward-oriented mesh. */
export function vertexNormals(positions: ArrayLike<number>, triangles: ArrayLike<number>): Float64Array {
  const n = new Float64Array(positions.length);
  for (let f = 0; f < triangles.length; f += 3) {
    const a = 3 * triangles[f], b = 3 * triangles[f + 1], c = 3 * triangles[f + 2];
    const u = [positions[b] - positions[a], positions[b + 1] - positions[a + 1], positions[b + 2] - positions[a + 2]];
    const v = [positions[c] - positions[a], positions[c + 1] - positions[a + 1], positions[c + 2] - positions[a + 2]];
    const cr = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    for (const i of [a, b, c]) for (let d = 0; d < 3; d++) n[i + d] += cr[d];
  }
  for (let i = 0; i < n.length; i += 3) {
    const l = Math.hypot(n[i], n[i + 1], n[i + 2]) || 1;
    n[i] /= l; n[i + 1] /= l; n[i + 2] /= l;
  }
  return n;
}

/** A diverging colour for t in [−1, 1] (clamped) into `colors` at vertex i: blue (−1), white (0), red (+1). */
export function divergingColor(colors: Float32Array, i: number, t: number): void {
  const c = Math.max(-1, Math.min(1, t));
  colors.set(c >= 0 ? [1, 1 - c, 1 - c] : [1 + c, 1 + c, 1], 3 * i);
}

/** Per-vertex rest-length factor for one frame of the inflate brush (rate in 1/s, dt in s). */
export function inflateFactor(weight: number, rate: number, dt: number, deflate: boolean): number {
  const f = 1 + rate * weight * dt;
  return deflate ? 1 / f : f;
}
