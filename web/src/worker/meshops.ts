// The operations on every body's mesh and rest shape: Freeze, Reset, Remesh and Subdivide, each
// one undo step, each saying what it did (and Subdivide what to expect before it runs).
//
// They act on every body (an import's pieces, a scene's bodies), not the one under the cursor:
// they are panel buttons and keys with no point on the model, and a multi-piece import is, as
// Blender selects every object a file brings in, one model whose pieces the user shapes together
// (Blender's Apply, Subdivide and Remesh act on every selected object). The tools act on the
// piece under the cursor (stroking.ts).

import type { FreezeReport, RemeshReport } from '../engine/world';
import { stepsPerFrame } from '../engine/models';
import { percent as pct, precision3 as fmt, sig3 } from '../format';
import type { DocState } from './docstate';
import { edit } from './editing';
import { setDt } from './parameters';

/** The volume change (relative) up to which a subdivision says it kept the shape. */
const SUBDIVIDE_KEPT = 0.02;

/**
 * Vertices up to which the modeler's steps converge in real time on a machine like this one
 * (BENCHMARKS.md, "Every frame on time": the mushroom subdivided once, 1,442 vertices, runs in
 * real time; twice, 5,762, at a quarter of it while grabbed): past it Subdivide says what to expect.
 */
export const REAL_TIME_VERTICES = 1_500;

/**
 * Freeze: under gravity the body keeps carrying its weight (no sag); keeping the tension (an
 * option, off by default: see docs/model.md, "Freeze") the gas keeps pressing and the rest
 * lengths are corrected so this shape holds, taut as it is now; otherwise the skin goes slack
 * (P_ref := P).
 */
export function freeze(d: DocState): void {
  const reports: FreezeReport[] = [];
  if (edit(d, 'freeze', true, () => {
    const underLoad = d.world.params(0).gravity !== 0;
    for (const b of d.everyBody) reports.push(d.world.freeze(b, underLoad, d.settings.keepTension));
  })) {
    const sum = (k: 'residual' | 'load' | 'clamped') => reports.reduce((s, r) => s + (r?.[k] ?? 0), 0);
    const clamped = sum('clamped');
    const kept = d.settings.keepTension && reports.length ? ` (skin taut; residual ${fmt(sum('residual'))} N of ${fmt(sum('load'))} N${clamped ? `, ${clamped} springs at their limit` : ''})` : ' (skin slack)';
    d.hooks.message(`frozen: this shape is the new rest shape${reports.length > 1 ? ` of all ${reports.length} bodies` : ''}${kept}`);
  }
}

export function reset(d: DocState): void { edit(d, 'reset', true, () => { for (const b of d.everyBody) d.world.reset(b); }); }

/**
 * Remesh: even triangles at the body's mean edge length (isotropic remeshing in the core;
 * masses and pins carried to the nearest new vertices), frozen under load under gravity as
 * Subdivide is, so the shape holds; undoable. Every body, each at its own mean edge length.
 * The core keeps the shape or refuses (docs/meshing.md, "The shape is kept"): a body too coarse
 * for its mean edge (an imported 8-vertex box) is remeshed at a half or a quarter of it, or
 * keeping its sharp edges, and the message says so; one that cannot be kept is one error, and
 * every body is as it was.
 */
export function remesh(d: DocState): void {
  const before = d.everyBody.map((b) => d.world.quality(b));
  const reports: RemeshReport[] = [];
  const done = edit(d, 'remesh', true, () => {
    d.hooks.progress('remeshing');
    const underLoad = d.world.params(0).gravity !== 0;
    for (const b of d.everyBody) {
      const gas = d.world.params(b)['gas.ambient'];
      reports.push(d.world.remeshReporting(b, before[b].edge_mean, underLoad));
      if (!underLoad && typeof gas === 'number') d.world.setParam(b, 'gas.ambient', gas);
    }
  }, 'all', (why) => `not remeshed: ${why.replace(/^remesh: /, '')} — the model is as it was before`);
  if (!done) return;
  const after = d.everyBody.map((b) => d.world.quality(b));
  const share = (q: typeof before) => Math.max(...q.map((x) => x.small_angle_share));
  const least = (q: typeof before) => Math.min(...q.map((x) => x.min_angle_deg));
  // What the core had to do to keep the shape: the edge it used instead of the mean edge.
  const shortened = reports.filter((r) => r.tries > 1);
  const r = shortened[0];
  const how = r ? `; made at edge ${sig3(r.edge)} m${r.crease_deg !== null ? ', keeping its sharp edges,' : ''} since the mean edge ${sig3(r.requested)} m would have changed the shape (too coarse for it)${r.distance > 1e-6 * r.edge ? `; the surface moved ≤ ${sig3(r.distance)} m` : ''}${shortened.length > 1 ? `; ${shortened.length} bodies so` : ''}` : '';
  d.hooks.message(`remeshed: ${d.totalVertices} vertices${after.length > 1 ? ` in ${after.length} bodies` : ''}; angles below 25°: ${pct(share(before))} → ${pct(share(after))}, smallest ${least(before).toFixed(0)}° → ${least(after).toFixed(0)}°${how}`);
}

export function subdivide(d: DocState): void {
  if (d.totalVertices > 200_000) { d.hooks.message('the mesh is already very fine; not subdividing', 'warn'); return; }
  // What to expect, said before it runs: Loop subdivision makes V + E ≈ 4V − 6 vertices of a
  // closed mesh of V (E = 3V − 6 edges).
  const next = d.everyBody.reduce((n, b) => n + 4 * d.world.body(b).vertexCount - 6, 0);
  if (next > REAL_TIME_VERTICES) d.hooks.message(`subdividing to about ${next.toLocaleString('en-US')} vertices: past ~${REAL_TIME_VERTICES.toLocaleString('en-US')} the steps here cannot all converge in real time while you shape it — expect slow motion and time-limited accuracy then (the HUD says both); Ctrl+Z undoes`, 'warn');
  edit(d, 'subdivide', true, () => {
    d.hooks.progress('subdividing');
    let dropped = 0, underLoad = false;
    const n0 = d.totalVertices;
    const volume = () => { d.synced(); return d.everyBody.reduce((v, b) => v + d.world.body(b).stats.volume, 0); };
    const v0 = volume();
    for (const b of d.everyBody) {
      const before = d.world.params(b);
      dropped += d.world.subdivide(b);
      // The subdivided body comes plainly frozen at its current shape: springs at rest, the
      // ambient pressure raised to the gas pressure. Under gravity nothing would then carry the
      // weight and it would sag (the mushroom to half its height). As Freeze does under gravity:
      // the gas as it was, and the rest shape frozen under load, so the shape holds.
      if (before.gravity !== 0) {
        d.world.setParam(b, 'gas.ambient', before['gas.ambient'] as number);
        d.world.freeze(b, true);
        underLoad = true;
      }
    }
    // Said, so the last operation's message does not stay on screen as if it were this one's.
    // Loop subdivision moves every vertex towards a smooth limit surface: a fine mesh keeps its
    // shape, a coarse one is rounded (an 8-vertex unit cube loses half its volume), and the
    // message says which.
    const change = volume() / v0 - 1;
    // (An open mesh has no volume to compare: no change said.)
    const kept = !Number.isFinite(change) || !(v0 > 0) || Math.abs(change) <= SUBDIVIDE_KEPT;
    const shape = kept ? `the shape kept${underLoad ? ' under its weight' : ''}` : `smoothing rounded the shape: volume ${change > 0 ? '+' : '−'}${pct(Math.abs(change))}${underLoad ? ', held under its weight' : ''}`;
    d.hooks.message(`subdivided: ${n0.toLocaleString('en-US')} → ${d.totalVertices.toLocaleString('en-US')} vertices, ${shape} (Ctrl+Z undoes)`, kept ? 'info' : 'warn');
    if (dropped > 0) d.hooks.message(`${dropped} pending scene events of the bodies no longer fit their meshes and were dropped`, 'warn');
    // Implicit steps keep dt (the parameters do not depend on the resolution); an explicit
    // integrator needs the finer mesh's stable step.
    const integrator = String(d.world.params(0).integrator);
    if (integrator !== 'implicit') setDt(d, Math.min(d.settings.dt, d.world.stableDt(integrator)));
    d.settings.substeps = stepsPerFrame(d.settings.dt);
  });
}
