// Implicit steps in the page, in as many substeps as keep Newton's method quick (adaptive
// substepping), the grab's anchors moved along the cursor's path across them (anchorpath.ts).
//
// Why: a backward-Euler step minimizes the incremental potential ½ |v⁺ − v|²_M + Φ(x + dt v⁺);
// the mass term m / dt² is what keeps it convex where the springs do not. A stiff skin at rest
// with little tension and no bending stiffness (the "stiff rubber" material: half its springs
// compressed by up to 0.13 % on the imported 10,242-vertex sphere) has per-spring transverse
// stiffnesses k (1 − L/l) of about ±3.8 N/m against m / dt² = 0.9 N/m at 1/60 s: the step's
// minimization is non-convex (the skin wrinkles), the projected Newton matrix a poor model of it,
// and Newton wanders. Measured natively from the page's own state (BENCHMARKS.md): the first
// grabbed step at 1/60 s did not converge (3 × 100 Newton iterations, 4.5 s; ~9–14 s in the
// page, which then split it), and tight linear solves do not help; at dt/4 (m / dt² 16× larger)
// the same steps take 3–35 Newton iterations, none fails. So the page takes each step of dt as
// `pieces` substeps of dt / pieces: doubled (at most MAX_PIECES) after a frame whose substeps
// took more than NEWTON_HIGH Newton iterations on average, or had to be split; halved after
// LOW_FRAMES frames in a row at NEWTON_LOW or fewer. A soft body stays at one step per frame.

import { stepSplitting } from './split';

/** Most substeps per step (dt / 8: the split steps' depth as well). */
export const MAX_PIECES = 8;
/** Newton iterations per substep (average over a step) above which the substeps double. */
export const NEWTON_HIGH = 24;
/** Newton iterations per substep at or below which, for LOW_FRAMES steps in a row, they halve. */
export const NEWTON_LOW = 6;
export const LOW_FRAMES = 30;
/** Substeps at least at the start of a grab (`brace`). */
export const GRAB_PIECES = 2;

/** The anchors of a stroke moving within the tick (the grab's `StrokePath`). */
export interface Anchors {
  /** Before a substep of `h` s: the anchors where the path is at its end. */
  aim(h: number): void;
  /** The substep of `h` s was taken (the path moves on). */
  took(h: number): void;
  /** A step of the tick was taken in `pieces` substeps, `newton` Newton iterations at most in one; `split`: one had to be split. */
  stepped(pieces: number, newton: number, split: boolean): void;
}

export class Pace {
  /** Substeps per step. */
  pieces = 1;
  private lowFrames = 0;

  /** A step was taken in `pieces` substeps with `newton` Newton iterations in all; `split`: one had to be split. */
  adapt(newton: number, split: boolean): void {
    const per = newton / this.pieces;
    if (split || per > NEWTON_HIGH) {
      this.pieces = Math.min(MAX_PIECES, 2 * this.pieces);
      this.lowFrames = 0;
    } else if (per <= NEWTON_LOW && this.pieces > 1) {
      if (++this.lowFrames >= LOW_FRAMES) { this.pieces /= 2; this.lowFrames = 0; }
    } else {
      this.lowFrames = 0;
    }
  }

  /**
   * A grab begins: its first steps at least in halves. From a body at rest the first grabbed
   * step is where Newton stalls (the page's stiff rubber: 3 × 100 iterations and a split, 8 s in
   * the page, when the resting steps before it had taken 0–1); at dt / 2 it converged in 20.
   */
  brace(): void {
    this.pieces = Math.max(this.pieces, GRAB_PIECES);
    this.lowFrames = 0;
  }

  /** Back to one step per frame (a new model). */
  reset(): void { this.pieces = 1; this.lowFrames = 0; }
}

/**
 * `n` steps of `dt`, each in `pace.pieces` substeps, each substep split if it does not converge
 * (`split.ts`); the anchors, if any, set before every substep. `step(h)` takes one substep of
 * `h` s (or throws, the world untouched) and returns its Newton iterations (the most over the
 * bodies). Returns the splits.
 */
export function stepPaced(pace: Pace, anchors: Anchors | null, step: (h: number) => number, dt: number, n: number): number {
  let splits = 0;
  for (let i = 0; i < n; i++) {
    const p = pace.pieces;
    let newton = 0, most = 0, s = 0;
    for (let k = 0; k < p; k++) {
      // One substep per call (n = 1): a failed try leaves the anchors' path where it was.
      s += stepSplitting((h) => {
        anchors?.aim(h);
        const it = step(h);
        anchors?.took(h);
        newton += it;
        most = Math.max(most, it);
      }, dt / p, 1);
    }
    pace.adapt(newton, s > 0);
    anchors?.stepped(p, most, s > 0);
    splits += s;
  }
  return splits;
}
