// Implicit steps in the page, in as many substeps as keep Newton's method quick (adaptive
// substepping), the grab's anchors moved along the cursor's path across them (anchorpath.ts).
//
// Why (measured: BENCHMARKS.md, "The grab on stiff rubber"): the mass term m / dt² is what
// keeps a backward-Euler step's minimization convex where the springs do not; on a stiff skin
// with little tension and no bending springs ("stiff rubber" on the imported 10,242-vertex
// sphere) it does not at 1/60 s, and Newton wanders — the first grabbed step from rest was
// refused after 3 × 100 iterations and split by the worker, a wait of 8–14 s in the page. At dt/4
// (a mass term 16× larger) the same steps take 3–35 iterations and none is refused.
//
// So each implicit step of dt is taken as `pieces` substeps of dt / pieces: doubled (at most
// MAX_PIECES) after a step whose substeps averaged more than NEWTON_HIGH Newton iterations or
// one that had to be split; halved after LOW_STEPS steps in a row at NEWTON_LOW or fewer per
// substep. A grab starts braced at GRAB_PIECES for its first BRACE_STEPS steps (the first
// grabbed step is the one that stalls; the resting steps before it say nothing, taking 0–1
// Newton iterations), then back to what it was unless a step asked for more. A soft body keeps
// one step per frame.

import { stepSplitting } from './split';

/** Most substeps per step (dt / 8: the split steps' depth as well). */
export const MAX_PIECES = 8;
/** Newton iterations per substep, averaged over a step, above which the substeps double. */
export const NEWTON_HIGH = 24;
/** Newton iterations per substep (average over a step) at or below which, LOW_STEPS steps in a row, they halve. */
export const NEWTON_LOW = 6;
export const LOW_STEPS = 30;
/**
 * Substeps at the start of a grab, for its first BRACE_STEPS steps (`brace`): replayed from the
 * page's resting stiff rubber, the first grabbed steps took 20 then 37 Newton iterations at dt/2
 * and 3 then 35 at dt/4; in the page 88 Newton iterations (~2 s) in halves against 46 (0.6 s) in
 * quarters. On a soft body ten steps in quarters cost little (a few iterations each).
 */
export const GRAB_PIECES = 4;
export const BRACE_STEPS = 10;
/**
 * A substep's Newton solve gives up after NEWTON_STALLED iterations without a new lowest
 * residual or NEWTON_MOST in all (the engine's `GiveUp`), and the substep is split (unless the
 * relaxed retry takes it, where an iterate crushed a face: `Relaxed` in the engine): a step that
 * will not converge is found out in a few iterations instead of the cap (100), in each of its
 * attempts (warm start, cold, without the ground's vertices if it held some). Not at the last
 * split (`split.ts`): a step that converges slowly there beats a refusal the user sees. Measured (BENCHMARKS.md, "A step that will
 * not converge, found out at once"): the mushroom subdivided twice, grabbed with mirror X at
 * ω = 600 1/s, 1 s of pulling took 50.6 s of wall time in Node with the cap alone (its worst
 * frame 15.8 s), 23.1, 23.5 and 25.8 s giving up after 8, 12 and 24 stalled iterations (worst
 * frames 2.0, 2.4, 3.7 s). NEWTON_MOST, twice NEWTON_HIGH (a substep that slow doubles the
 * substeps anyway), is for a solve that creeps without stalling.
 */
export const NEWTON_STALLED = 12;
export const NEWTON_MOST = 2 * NEWTON_HIGH;

/** The anchors of a stroke moving within the tick (the grab's: `anchorpath.ts`), bound to its body. */
export interface Anchors {
  /** Before a substep of `h` s: the anchors where the path is at its end. */
  aim(h: number): void;
  /** The substep of `h` s was taken (the path moves on). */
  took(h: number): void;
  /** A step was taken: `newton` Newton iterations at most in one of its substeps; `split`: one had to be split. */
  stepped(newton: number, split: boolean): void;
}

export class Pace {
  /** Substeps per step. */
  pieces = 1;
  /** The substeps asked for by the steps themselves (more than one: the modeler says so once). */
  raised = false;
  private lowSteps = 0;
  /** Steps left of a grab's brace, and the substeps to go back to after it. */
  private braced = 0;
  private unbraced = 1;

  /** A step was taken in `pieces` substeps with `newton` Newton iterations in all; `split`: one had to be split. */
  adapt(newton: number, split: boolean): void {
    const per = newton / this.pieces;
    if (split || per > NEWTON_HIGH) {
      this.pieces = Math.min(MAX_PIECES, 2 * this.pieces);
      this.raised = true;
      this.lowSteps = 0;
      this.braced = 0;
      return;
    }
    if (this.braced > 0 && --this.braced === 0) {
      this.pieces = this.unbraced;
      this.lowSteps = 0;
      return;
    }
    if (per <= NEWTON_LOW && this.pieces > 1) {
      if (++this.lowSteps >= LOW_STEPS) { this.pieces /= 2; this.lowSteps = 0; }
    } else {
      this.lowSteps = 0;
    }
  }

  /** A grab begins: its first BRACE_STEPS steps in at least GRAB_PIECES substeps. */
  brace(): void {
    if (this.pieces >= GRAB_PIECES) return;
    this.unbraced = this.pieces;
    this.pieces = GRAB_PIECES;
    this.braced = BRACE_STEPS;
    this.lowSteps = 0;
  }

  /** Back to one step per frame (a new model, another integrator). */
  reset(): void {
    this.pieces = 1;
    this.raised = false;
    this.lowSteps = 0;
    this.braced = 0;
  }
}

/**
 * `n` steps of `dt`, each in `pace.pieces` substeps, each substep split if it does not converge
 * (`split.ts`); the anchors, if any, set before every substep. `step(h, last)` takes one
 * substep of `h` s (or throws, the world untouched; `last`: the shortest split, see `StepFn`)
 * and returns its Newton iterations (the most over the bodies). Returns the splits.
 */
export function stepPaced(pace: Pace, anchors: Anchors | null, step: (h: number, last: boolean) => number, dt: number, n: number): number {
  let splits = 0;
  for (let i = 0; i < n; i++) {
    const p = pace.pieces;
    let newton = 0, most = 0, s = 0;
    for (let k = 0; k < p; k++) {
      // One substep per call (n = 1): a failed try leaves the anchors' path where it was.
      s += stepSplitting((h, _n, last) => {
        anchors?.aim(h);
        const it = step(h, last);
        anchors?.took(h);
        newton += it;
        most = Math.max(most, it);
      }, dt / p, 1);
    }
    pace.adapt(newton, s > 0);
    anchors?.stepped(most, s > 0);
    splits += s;
  }
  return splits;
}
