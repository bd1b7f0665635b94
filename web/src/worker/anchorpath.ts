// The grab's anchors follow the cursor at a travel per step that adapts to how hard the steps
// are (load stepping, as automatic load incrementation does in nonlinear statics).
//
// Why (measured: BENCHMARKS.md, "The grab on stiff rubber"): the grab's target springs
// (ω = 600 1/s: dt² k_t / m = 100 at 1/60 s) put each grabbed vertex where its anchor is by the
// end of the step, so an anchor that jumps by J asks one backward-Euler step for the body's whole
// response to it; on stiff rubber a jump of 28 cm or more in one step was refused, one of 14 cm
// took 207 Newton iterations, the same jumps in 4–8 substeps with the anchors moved in equal
// parts 72–96. And in the page a slow step let the cursor run further ahead, so the next jump
// was larger: the grab stalled for good.
//
// So the anchors move towards the cursor by at most `travel` (m) per step: each tick of the
// stepper takes them from where they are towards the cursor, to the point the tick's steps end
// at (`Document.advance`, set once before the core's `World::advance`, which may split a refused
// step: its halves pull towards the tick's point); what the travel held back follows over the
// next ticks (as the body lags the cursor in slow motion). `travel` starts at TRAVEL_START brush radii and adapts on the ticks it held the
// anchors back: doubled after a step whose substeps took at most NEWTON_GROW Newton iterations
// each (once the substeps converge quickly the travel hardly matters: stiff rubber at dt/4 took
// 133–194 Newton iterations for 4 steps whether the anchors travelled 1.5 or 24 cm a step),
// halved after one with a substep over NEWTON_SHRINK or a split; within [TRAVEL_MIN, TRAVEL_MAX]
// brush radii. A soft body soon steps with the anchors at the cursor.

import type { Vec3 } from '../protocol';

/** The first travel per step, in brush radii (stiff rubber from rest: 5 cm in one step took 50 Newton iterations, 14 cm 207). */
export const TRAVEL_START = 1 / 8;
/** Bounds of the travel per step, in brush radii. */
export const TRAVEL_MIN = 1 / 64;
export const TRAVEL_MAX = 4;
/**
 * Newton iterations of a tick's last step (the most over the bodies) above which the travel halves, and at or below which it doubles, on a tick it held the anchors back.
 */
export const NEWTON_SHRINK = 48;
export const NEWTON_GROW = 24;

export class AnchorPath {
  /** Where the anchors' reference point was at the tick's start, and where the tick takes it. */
  private from: Vec3;
  private goal: Vec3;
  /** Simulated seconds of the tick, and how much of it the steps have covered. */
  private span = 0;
  private done = 0;
  /** Whether this tick's travel held the anchors back (they would have gone further). */
  private limited = false;
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
   * goes from the current point towards it, at most `travel` per step. `span` = 0 (paused, or
   * a tick that steps nothing) keeps the anchors where they are.
   */
  aim(cursor: Vec3, span: number, dt: number): void {
    const now = this.point;
    const d = [0, 1, 2].map((k) => cursor[k] - now[k]);
    const len = Math.hypot(d[0], d[1], d[2]);
    const most = span > 0 && dt > 0 ? this.travel * Math.max(1, Math.round(span / dt)) : 0;
    this.limited = len > most;
    const s = this.limited ? most / len : 1;
    this.from = now;
    this.goal = [0, 1, 2].map((k) => now[k] + s * d[k]) as Vec3;
    this.span = span;
    this.done = 0;
  }

  /** The body was put back (a rewind after a failed step): the anchors start again from `point`. */
  rebase(point: Vec3): void {
    this.from = [...point];
    this.goal = [...point];
    this.span = 0;
    this.done = 0;
  }

  /** A substep of `h` s was taken: the anchors are at `next(h)`. */
  took(h: number): void { this.done += h; }

  /** A step was taken, `newton` Newton iterations in its hardest substep; `split`: one had to be split. */
  stepped(newton: number, split: boolean): void {
    if (!this.limited) return;
    if (split || newton > NEWTON_SHRINK) this.travel = Math.max(TRAVEL_MIN * this.radius, 0.5 * this.travel);
    else if (newton <= NEWTON_GROW) this.travel = Math.min(TRAVEL_MAX * this.radius, 2 * this.travel);
  }
}
