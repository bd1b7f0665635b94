// What an imported mesh will cost to simulate, measured before it is imported: its triangles
// (`World.quality`) and a trial run — the model built as the import would build it, in a scratch
// world, dropped under the modeler's defaults with every step converged, for at most
// TRIAL_FRAMES frames or TRIAL_SECONDS of wall-clock time. Long thin triangles make short, stiff
// springs and an ill-conditioned step: a mesh with slivers (smallest angle 0.8°, shortest edge 3 %
// of the mean) took 53 s for its first converged frame and 4–11 s per frame under the page's
// 12 ms budget, where the same sphere evenly meshed (Remesh) takes 4 ms (BENCHMARKS.md, "Poor
// imports"). So the import dialog offers Remesh, checked, where the triangles are uneven and
// the trial slow, with the reason in one line.

import { World, type Quality } from '../engine/world';
import { FRAME_DT, stepsPerFrame } from '../engine/models';
import type { MeshCost } from '../io/import';
import { SOLVE_BUDGET_MS } from './stepper';

/** Wall-clock seconds the trial may take (past them the step in progress ends at its next iterate). */
export const TRIAL_SECONDS = 0.5;
/** Frames of 1/60 s the trial runs at most (a drop's first tenth of a second: the costly part). */
export const TRIAL_FRAMES = 6;
/**
 * A converged frame slower than this (ms) is slow: the page limits each frame's solve to
 * SOLVE_BUDGET_MS and accepts the step less converged, which holds up to a few budgets' worth of
 * converged work (the evenly meshed 2,562-vertex sphere: 64 ms converged, 30 ms a frame under
 * the budget); far past it a frame cannot be kept on time.
 */
export const SLOW_FRAME_MS = 8 * SOLVE_BUDGET_MS;
/** Triangles are uneven for simulation with an angle below this (°) or an edge below SHORT_EDGE × the mean. */
export const SLIVER_DEG = 10;
export const SHORT_EDGE = 0.1;

/** The worst quality over the pieces. */
export function worst(qs: Quality[]): { minAngle: number; smallShare: number; shortest: number; poor: boolean } {
  return {
    minAngle: Math.min(...qs.map((q) => q.min_angle_deg)),
    smallShare: Math.max(...qs.map((q) => q.small_angle_share)),
    shortest: Math.min(...qs.map((q) => (q.edge_mean > 0 ? q.edge_min / q.edge_mean : 1))),
    poor: qs.some((q) => q.poor),
  };
}

/**
 * The verdict from the triangles and the trial: Remesh is recommended (asked, checked) where the
 * trial was slow and the triangles hold slivers (an angle below SLIVER_DEG, an edge below
 * SHORT_EDGE of the mean) or are poor by the core's measure; a mesh that is merely large is not
 * helped by remeshing it. Poor triangles that run fast are only named (`why`, said after the
 * import), as before.
 */
export function verdict(q: ReturnType<typeof worst>, frames: number, msPerFrame: number): MeshCost {
  const slivers = q.minAngle < SLIVER_DEG || q.shortest < SHORT_EDGE;
  const slow = frames === 0 || msPerFrame > SLOW_FRAME_MS;
  const speed = frames === 0
    ? `a trial frame did not finish in ${TRIAL_SECONDS} s (real time needs ${(1000 * FRAME_DT).toFixed(1)} ms)`
    : `a trial frame took ${msPerFrame.toFixed(0)} ms (real time needs ${(1000 * FRAME_DT).toFixed(1)} ms)`;
  const shape = `smallest angle ${q.minAngle.toFixed(1)}°, shortest edge ${(100 * q.shortest).toFixed(0)} % of the mean`;
  let why = '', reason = '';
  if (slow && slivers) {
    reason = 'long thin triangles make stiff, slow springs';
    why = `${speed}: long thin triangles (${shape}) make stiff, slow springs`;
  } else if (slow && q.poor) {
    reason = 'uneven triangles make uneven, slow springs';
    why = `${speed}: uneven triangles (${(100 * q.smallShare).toFixed(0)} % of angles below 25°) make uneven, slow springs`;
  } else if (q.poor) {
    // Not slow: said after the import (as before the trial), not asked.
    why = `uneven triangles (${(100 * q.smallShare).toFixed(0)} % of angles below 25°)`;
  }
  return { minAngle: q.minAngle, smallShare: q.smallShare, shortest: q.shortest, frames, msPerFrame, remesh: reason !== '', why, reason };
}

/**
 * Run the trial on a world that `build` fills (a scratch world from `empty`, the modeler's
 * empty world); null if the trial could not run (the build failed, or a command interrupted it).
 */
export function trial(empty: Uint8Array, build: (w: World) => void, now: () => number = () => performance.now()): { frames: number; msPerFrame: number } | null {
  const w = World.create();
  try {
    w.restore(empty);
    build(w);
    // Each frame under a real-time budget of what is left of TRIAL_SECONDS: past it a step
    // ends at its next Newton iterate (any accuracy), so the trial overruns TRIAL_SECONDS by at
    // most one linear solve.
    // A frame is the nearest whole number of steps of dt (World::advance), so a whole one may
    // simulate up to dt/2 less than FRAME_DT; a frame the budget cut lacks at least one step.
    const dt = Number(w.params(0).dt), whole = stepsPerFrame(dt) * dt - dt / 2;
    const t0 = now();
    let frames = 0, finished = t0;
    while (frames < TRIAL_FRAMES) {
      const left = TRIAL_SECONDS - (now() - t0) / 1000;
      if (left <= 0) break;
      const a = w.advance(FRAME_DT, left, 1e9);
      const t = now();
      // A step stopped by its deadline, or a frame not all simulated: not a converged frame.
      if (a.early > 0 || a.simulated < whole || t - t0 > 1000 * TRIAL_SECONDS) break;
      frames++;
      finished = t;
    }
    // Over the frames that finished (not the one the deadline cut); its whole time if none did.
    return { frames, msPerFrame: frames > 0 ? (finished - t0) / frames : now() - t0 };
  } catch (e) {
    // A refused step is a slow mesh; an interrupt (the user moved on) says nothing.
    const f = e as { kind?: string; fields?: Record<string, unknown> } | null;
    return f?.kind === 'step' && f.fields?.cause !== 'interrupted' ? { frames: 0, msPerFrame: 1000 * TRIAL_SECONDS } : null;
  } finally {
    w.free();
  }
}
