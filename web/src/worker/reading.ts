// What the page draws and reads of the document: every body's positions for a frame, the open
// scene's line, the meshes' topology, the active body's masses and pins, and its strain.

import type { SceneInfo, Topology } from '../protocol';
import { isClosed } from '../io/import';
import type { DocState } from './docstate';

/** Floats the frame buffer holds: xyz of every body, the active one first. */
export function renderLength(d: DocState): number {
  let n = 0;
  for (let i = 0; i < d.world.bodyCount; i++) n += 3 * d.world.body(i).vertexCount;
  return n;
}

/** Every body's positions (f32) into `out` (renderLength floats); refreshes the stats. */
export function renderInto(d: DocState, out: Float32Array): void {
  const w = d.world;
  d.synced();
  let at = 0;
  for (let i = 0; i < w.bodyCount; i++) {
    const r = w.body(i).render;
    out.set(r, at);
    at += r.length;
  }
}

export function sceneInfo(d: DocState): SceneInfo | null {
  if (!d.session) return null;
  return { name: d.session.name, time: d.stats().time, duration: d.session.duration, bodies: d.world.bodyCount };
}

export function topology(d: DocState): Topology {
  const w = d.world, b = w.body(0);
  const others = [];
  for (let i = 1; i < w.bodyCount; i++) others.push({ vertexCount: w.body(i).vertexCount, triangles: w.body(i).triangles.slice() });
  const triangles = b.triangles.slice();
  return { vertexCount: b.vertexCount, triangles, springs: b.springs.slice(), others, obstacles: w.obstacles(), closed: isClosed(triangles) };
}

export function bodyData(d: DocState): { masses: Float64Array; pinned: Uint8Array } {
  d.synced();
  const b = d.world.body(0);
  return { masses: b.masses.slice(), pinned: b.pinned.slice() };
}

/**
 * Each vertex's strain: the mean over its springs of l / L − 1 (l the current length, L the
 * rest length; > 0 stretched, < 0 compressed), what would spring back if released.
 */
export function strain(d: DocState): Float32Array {
  const b = d.world.body(0), x = b.positions, e = b.springs, rest = b.rest;
  const n = b.vertexCount;
  if (d.strainSum.length !== n) { d.strainSum = new Float64Array(n); d.strainCount = new Uint32Array(n); }
  const sum = d.strainSum.fill(0), count = d.strainCount.fill(0);
  for (let k = 0; k < rest.length; k++) {
    const i = 3 * e[2 * k], j = 3 * e[2 * k + 1];
    const l = Math.hypot(x[i] - x[j], x[i + 1] - x[j + 1], x[i + 2] - x[j + 2]);
    const s = rest[k] > 0 ? l / rest[k] - 1 : 0;
    sum[e[2 * k]] += s; count[e[2 * k]]++;
    sum[e[2 * k + 1]] += s; count[e[2 * k + 1]]++;
  }
  const out = new Float32Array(n);
  for (let i = 0; i < n; i++) out[i] = count[i] ? sum[i] / count[i] : 0;
  return out;
}
