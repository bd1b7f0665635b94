// Seeded strongest-grab drags on the worker's Document (README.md: copy into web/test/ to run).
import { beforeAll, it } from 'vitest';
import { writeFileSync } from 'node:fs';
import { loadEngineFrom, openedDocument, topVertex, vertexAt } from './setup';
import type { Vec3 } from '../src/protocol';

beforeAll(() => loadEngineFrom(process.env.WASM ?? 'public/softsculpt.wasm'));
const top = (doc: any): number => topVertex(doc.world.body(0).positions);
const P = (doc: any, i: number): Vec3 => vertexAt(doc.world.body(0).positions, i);
let seed = Number(process.env.SEED ?? 1);
const rnd = () => { seed = (seed * 16807) % 2147483647; return seed / 2147483647; };
// GRID=1: instead of random drags, the grid of 18 at ω = 3000 (dx × dy × frames, one step per tick).
const GRID = [-0.6, -0.9, -1.1].flatMap((dx) => [0.4, 0.6].flatMap((dy) => [5, 10, 20].map((fr) => [dx, dy, fr])));
const N = process.env.GRID === '1' ? GRID.length : Number(process.env.N ?? 20);
// MODEL: a built-in other than the mushroom (the drags are the same, from its top vertex).
// FROM/TO: only cases FROM..TO-1 (to run a grid in two processes).
const FROM = Number(process.env.FROM ?? 0), TO = Math.min(N, Number(process.env.TO ?? N));
for (let c = FROM; c < TO; c++) {
  seed = Number(process.env.SEED ?? 1) * 7919 + c * 104729 + 1; rnd(); rnd();
  let dx = -0.3 - 0.8 * rnd(), dy = 0.2 + 0.6 * rnd(), dz = (rnd() - 0.5) * 0.6;
  let frames = 1 + Math.floor(rnd() * 30), maxTick = 1 + Math.floor(rnd() * 6), off = (rnd() - 0.5) * 0.1;
  let w = 600 + rnd() * 2400 > 2000 ? 3000 : 600 + Math.floor(rnd() * 2400);
  if (process.env.GRID === '1') [dx, dy, frames, dz, maxTick, off, w] = [...GRID[c], 0, 1, 0, 3000];
  const caseSeed = seed;
  it(`case ${c}: d=(${dx.toFixed(2)},${dy.toFixed(2)},${dz.toFixed(2)}) frames ${frames} tick<=${maxTick} off ${off.toFixed(2)} w ${w}`, () => {
    seed = caseSeed;
    const { doc, messages } = openedDocument();
    if (process.env.MODEL) doc.loadBuiltin(process.env.MODEL, false);
    const dt = doc.settings.dt;
    const mirror = process.env.MIRROR === '0' ? undefined : { axes: [true, false, false] as [boolean, boolean, boolean], centre: [0, 0, 0] as Vec3 };
    for (let i = 0; i < 120; i++) doc.advance(dt, 1);
    let t = top(doc); let p = P(doc, t);
    doc.strokeStart({ tool: 'grab', point: p, radius: 0.35, strength: 600, inverted: false, mirror });
    for (let i = 0; i < 120; i++) { doc.strokeMove([p[0] + 0.23 * Math.min(1, i / 15), p[1] + 0.33 * Math.min(1, i / 15), p[2]], false); doc.updateStroke(dt); if (!doc.advance(dt, 1)) throw new Error('first grab failed ' + messages.join('|')); }
    doc.strokeEnd();
    for (let i = 0; i < 180; i++) doc.advance(dt, 1);
    t = top(doc); p = P(doc, t); p[0] += off;
    // The document steps through the core's `advance` (splits, the relaxed retry): the world
    // before a refused frame to /tmp/fail-N.bin, and before each of the drag's first four frames
    // with a relaxed step to /tmp/relaxed-N-K.bin, to replay.
    const w0: any = doc.world; const origA = w0.advance.bind(w0); let relaxed = 0;
    w0.advance = (...args: unknown[]) => {
      const snap = w0.snapshot();
      try { const a = origA(...args); if (w0.relaxed(0) > 0 && relaxed++ < 4) writeFileSync(`/tmp/relaxed-${c}-${relaxed}.bin`, snap); return a; } catch (e) { writeFileSync(`/tmp/fail-${c}.bin`, snap); throw e; }
    };
    doc.strokeStart({ tool: 'grab', point: p, radius: 0.35, strength: w, inverted: false, mirror });
    const its: string[] = [];
    let f = 0; let worst = 0;
    while (f < 90) {
      const n = 1 + Math.floor(rnd() * maxTick);
      f += n;
      const s = Math.min(1, f / frames);
      doc.strokeMove([p[0] + dx * s, p[1] + dy * s, p[2] + dz * s], false);
      doc.updateStroke(dt * n);
      const t0 = performance.now();
      const ok = doc.advance(dt, n);
      const ms = performance.now() - t0; worst = Math.max(worst, ms);
      its.push(`${f}:${n}/${doc.lastAdvance?.splits ?? '-'}/${(doc as any).newtonIterations()}/${ms.toFixed(0)}`);
      if (!ok) { console.log(its.join(' ')); throw new Error(`tick at frame ${f} failed: ${messages.join(' | ')}`); }
    }
    console.log(`case ${c} worst tick ${worst.toFixed(0)} ms splits ${doc.splitFrames} relaxed ${doc.relaxedSteps}`);
    doc.strokeEnd();
    for (let i = 0; i < 120; i++) if (!doc.advance(dt, 1)) throw new Error('after release failed ' + messages.join('|'));
  }, 600000);
}
