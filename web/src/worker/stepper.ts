// Real-time stepping in the worker: each tick runs as many steps as the wall-clock time since
// the last tick holds (at most 0.1 s of it; fractions of a step carry over), in chunks of about
// 2 ms, within a time budget so that commands (the grab's cursor, a press) are read between
// ticks. If the steps do not fit in the budget the simulation runs in slow motion and says so.
//
// Implicit steps are anytime steps under a solve budget (SOLVE_BUDGET_MS per tick): past it the
// engine stops each step's Newton solve at its first iterate within its minimum accuracy
// (`WorldSettings::deadline`, crates/softsculpt/src/world/advance.rs), so a frame of a large or
// poorly shaped mesh ends about on time instead of waiting for a converged step; the HUD shows
// the accuracy reached (`Document.takeAccuracy`).

import type { Document } from './document';

/**
 * Wall-clock ms a tick's implicit solves may take before each step is accepted at its first
 * iterate within the engine's minimum accuracy (the rest of the 16 ms tick draws, publishes and
 * reads commands). Measured: BENCHMARKS.md, "Every frame on time".
 */
export const SOLVE_BUDGET_MS = 12;

export class Stepper {
  private last = 0;
  private carry = 0;
  /** Measured cost of one step (ms), to size the chunks of steps between budget checks. */
  private stepCostMs = 0.05;
  /** Wall-clock ms spent stepping since `take()`. */
  private spent = 0;
  slowMotion = false;
  /**
   * Simulated time over wall-clock time (1: real time), over the last tick: from the end of the
   * tick before it to its own end (its steps and the wait before them). Not the steps done over
   * the steps wanted: those are for at most 0.1 s of clock, so a step that takes 1 s read as 1/6
   * of real time instead of 1/60 (the page said 17 % at 2–7 %).
   */
  realTimeFraction = 1;
  /** When the last tick ended (ms), 0 before the first. */
  private lastEnd = 0;

  constructor(private readonly now: () => number, private readonly budgetMs = 30, private readonly solveBudgetMs = SOLVE_BUDGET_MS) {}

  /** One tick; returns whether it stepped. */
  tick(doc: Document): boolean {
    const now = this.now();
    const elapsed = this.last ? Math.min(0.1, (now - this.last) / 1000) : 1 / 60;
    this.last = now;
    const s = doc.settings;
    if (!s.playing) {
      doc.updateStroke(0);
      this.slowMotion = false;
      this.carry = 0;
      this.lastEnd = 0;
      return false;
    }
    const want = s.realTime ? elapsed / s.dt + this.carry : s.substeps;
    // A tenth of a step of slack: at dt = 1/60 s (implicit) a 16 ms tick still takes its step,
    // and the carry (then slightly negative) keeps the average on the clock.
    const n = s.realTime ? Math.floor(want + 0.1) : want;
    this.carry = s.realTime ? want - n : 0;
    doc.updateStroke(s.dt * n);
    doc.setDeadline(this.solveBudgetMs / 1000);
    let done = 0;
    try {
      done = this.run(doc, s.dt, n, this.budgetMs);
    } finally {
      doc.setDeadline(-1);
    }
    this.slowMotion = done < n;
    if (this.slowMotion) this.carry = 0;
    const end = this.now();
    const wall = (end - (this.lastEnd || now)) / 1000;
    this.lastEnd = end;
    this.realTimeFraction = this.slowMotion && wall > 0 ? Math.min(1, (done * s.dt) / wall) : 1;
    return done > 0;
  }

  /** `n` steps of `dt` in chunks, stopping once `budgetMs` is spent or a step fails; returns how many ran. */
  run(doc: Document, dt: number, n: number, budgetMs = Infinity): number {
    let done = 0;
    const t0 = this.now();
    while (done < n) {
      const chunk = Math.min(n - done, Math.max(1, Math.floor(2 / this.stepCostMs)));
      const c0 = this.now();
      if (!doc.advance(dt, chunk)) break;
      this.stepCostMs = 0.8 * this.stepCostMs + 0.2 * Math.max(1e-4, (this.now() - c0) / chunk);
      done += chunk;
      if (this.now() - t0 > budgetMs) break;
    }
    this.spent += this.now() - t0;
    return done;
  }

  /** Wall-clock ms spent stepping since the last call (for the frame). */
  take(): number {
    const ms = this.spent;
    this.spent = 0;
    return ms;
  }
}
