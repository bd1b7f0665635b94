// The grab's anchors follow the cursor at a travel per step that adapts to how hard the steps
// are (load stepping, as automatic load incrementation does in nonlinear statics).
//
// Why: the grab's target springs (ω = 600 1/s by default: dt² k_t / m = 100 at 1/60 s) put each
// grabbed vertex where its anchor is by the end of the step, so an anchor that jumps by J in one
// step asks one backward-Euler step for the body's response to a displacement J of its grabbed
// patch. Newton converges from the step's start when J is small against the brush; on a stiff
// body it does not for large J. Measured natively (BENCHMARKS.md "Stiff rubber grabbed in the
// page": the 10,242-vertex sphere at rest, stiff rubber, brush 0.35 m, one step of 1/60 s): a
// jump of 5 cm takes 50 Newton iterations, 14 cm 207 (6.5 s), 28 and 56 cm do not converge
// (3 × 100 iterations, 8 s; the page then split the step). The same 56 cm in 8 steps of 7 cm
// (dt/8 each): 96 Newton iterations, 0.9 s. And in the page a slow step made the next jump larger
// (the cursor moved on meanwhile): the grab stalled for good ("waiting for a step: 11 s").
//
// So the anchors move towards the cursor by at most `travel` (m) per step: each tick of the
// stepper takes them from where they are towards the cursor, linearly in simulated time over
// the tick's steps and substeps (`pace.ts`; a substep split in halves moves them half as far in
// each), by at most `travel` per step; the rest follows over the next ticks (as the body lags
// the cursor in slow motion). `travel` starts at TRAVEL_START brush radii and adapts, like
// automatic load incrementation in nonlinear statics, on the steps where it held the anchors
// back (they moved at least half of it): doubled after one whose substeps took at most
// NEWTON_GROW Newton iterations each, halved after one that took more than NEWTON_SHRINK in a
// substep or had to be split; within [TRAVEL_MIN, TRAVEL_MAX] brush radii. Once the substeps
// are short enough to converge quickly the travel hardly matters (the page's stiff rubber at
// dt/4: 130–190 Newton iterations for 4 steps whether the anchors travel 1.5 or 24 cm a step),
// so it grows whenever they do; a soft body soon steps with the anchors at the cursor.

import type { Vec3 } from '../protocol';

/** The first travel per step, in brush radii (the rubber sphere: 5 cm steps converge in ~50 Newton iterations, 14 cm in 207). */
export const TRAVEL_START = 1 / 8;
/** Bounds of the travel per step, in brush radii. */
export const TRAVEL_MIN = 1 / 64;
export const TRAVEL_MAX = 4;
/** Newton iterations of a substep (of a step that held the anchors back) above which the travel halves, at or below which it doubles. */
export const NEWTON_SHRINK = 48;
export const NEWTON_GROW = 24;

export class AnchorPath {
  /** Where the anchors' reference point was at the tick's start, and where the tick takes it. */
  private from: Vec3;
  private goal: Vec3;
  /** Simulated seconds of the tick, and how much of it the steps have covered. */
  private span = 0;
  private done = 0;
  /** Most travel of the anchors in one step (m). */
  travel: number;

  constructor(start: Vec3, private readonly radius: number) {
    this.from = [...start];
    this.goal = [...start];
    this.travel = TRAVEL_START * radius;
  }

  /** The reference point at `t` simulated seconds into the tick. */
  at(t: number): Vec3 {
    const s = this.span > 0 ? Math.min(1, Math.max(0, t / this.span)) : 1;
    return [0, 1, 2].map((d) => this.from[d] + s * (this.goal[d] - this.from[d])) as Vec3;
  }

  /** Where the anchors are now (the end of the last step taken). */
  get point(): Vec3 { return this.at(this.done); }

  /** The reference point at the end of a step of `h` s from where the steps are now. */
  next(h: number): Vec3 { return this.at(this.done + h); }

  /**
   * A tick of `span` simulated seconds in steps of `dt` begins, the cursor at `cursor`: the path
   * goes from the current point towards it, at most `travel` per step (none while paused).
   */
  aim(cursor: Vec3, span: number, dt: number): void {
    const now = this.point;
    const d = [0, 1, 2].map((k) => cursor[k] - now[k]);
    const len = Math.hypot(d[0], d[1], d[2]);
    const most = span > 0 && dt > 0 ? this.travel * Math.max(1, Math.round(span / dt)) : 0;
    const s = len > most ? most / len : 1;
    this.from = now;
    this.goal = [0, 1, 2].map((k) => now[k] + s * d[k]) as Vec3;
    this.span = span;
    this.done = 0;
  }

  /** Travel of the anchors in the current step so far (m). */
  private moved = 0;

  /** A substep of `h` s was taken: the anchors are at `next(h)`. */
  took(h: number): void {
    const a = this.point, b = this.next(h);
    this.moved += Math.hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    this.done += h;
  }

  /** A step was taken (`pace.ts`), `newton` Newton iterations at most in a substep; `split`: one had to be split. */
  stepped(newton: number, split: boolean): void {
    const held = this.moved >= 0.5 * this.travel;
    this.moved = 0;
    if (!held) return;
    if (split || newton > NEWTON_SHRINK) this.travel = Math.max(TRAVEL_MIN * this.radius, 0.5 * this.travel);
    else if (newton <= NEWTON_GROW) this.travel = Math.min(TRAVEL_MAX * this.radius, 2 * this.travel);
  }
}
