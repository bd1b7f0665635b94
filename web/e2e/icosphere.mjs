// An icosphere as OBJ text, for the browser tests and benchmarks: level L has 10·4^L + 2
// vertices and 20·4^L faces (the same mesh as ../../shared/bench/gen_icosphere.py, written
// with 9 significant digits, which is plenty for a test mesh).

import { writeFileSync } from 'node:fs';
import { join } from 'node:path';

export function icosphere(level) {
  const t = (1 + Math.sqrt(5)) / 2;
  const v = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]];
  const unit = (p) => { const n = Math.hypot(...p); return p.map((x) => x / n); };
  let verts = v.map(unit);
  let faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
    [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]];
  for (let l = 0; l < level; l++) {
    const mid = new Map();
    const m = (a, b) => {
      const key = a < b ? a * 1e7 + b : b * 1e7 + a;
      let i = mid.get(key);
      if (i === undefined) {
        i = verts.length;
        verts.push(unit([0, 1, 2].map((d) => (verts[a][d] + verts[b][d]) / 2)));
        mid.set(key, i);
      }
      return i;
    };
    const next = [];
    for (const [a, b, c] of faces) {
      const ab = m(a, b), bc = m(b, c), ca = m(c, a);
      next.push([a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]);
    }
    faces = next;
  }
  return { verts, faces };
}

export function icosphereObj(level) {
  const { verts, faces } = icosphere(level);
  const lines = verts.map((p) => `v ${p.map((x) => x.toPrecision(9)).join(' ')}`);
  for (const f of faces) lines.push(`f ${f[0] + 1} ${f[1] + 1} ${f[2] + 1}`);
  return lines.join('\n') + '\n';
}

/** Write icosphere_L{level}.obj into `dir`; returns its path. */
export function writeIcosphere(dir, level) {
  const path = join(dir, `icosphere_L${level}.obj`);
  writeFileSync(path, icosphereObj(level));
  return path;
}

/**
 * The icosphere of `level` with slivers, as a poorly made file has them: every other triangle
 * split at a point `at` of the way from a corner (three triangles, two of them long and thin,
 * edges ~2 % of the mean at 1 %).
 */
export function sliverObj(level, at = 0.01) {
  const { verts, faces } = icosphere(level);
  const out = [];
  faces.forEach(([a, b, c], k) => {
    if (k % 2) { out.push([a, b, c]); return; }
    const m = verts.length;
    verts.push([0, 1, 2].map((d) => (1 - 2 * at) * verts[a][d] + at * verts[b][d] + at * verts[c][d]));
    out.push([a, b, m], [b, c, m], [c, a, m]);
  });
  const lines = verts.map((p) => `v ${p.map((x) => x.toPrecision(9)).join(' ')}`);
  for (const f of out) lines.push(`f ${f[0] + 1} ${f[1] + 1} ${f[2] + 1}`);
  return lines.join('\n') + '\n';
}
