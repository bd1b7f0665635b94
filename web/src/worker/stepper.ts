// Real-time stepping in the worker: each tick asks the core for as many steps as the wall-clock
// time since the last tick holds (at most 0.1 s of it; fractions of a step carry over), in one
// `World::advance` under a wall-clock budget, so that commands (the grab's cursor, a press) are
// read between ticks. The core owns how the frame is stepped (crates/softsculpt/src/world/
// advance.rs): implicit steps are anytime steps (past the budget each is accepted at its first
// iterate within the minimum accuracy, and the HUD shows the accuracy reached:
// `Document.takeAccuracy`), refused ones are split, explicit steps run while the budget lasts.
// If the steps do not fit in the budget the simulation runs in slow motion and says so.

import type { Advance } from '../engine/world';
import type { Settings } from '../protocol';

/**
 * What the stepper needs of the document it steps (worker/document.ts's `Document` is one):
 * declared here, below the document, so that the stepper does not import it (issue #39, no
 * circles: the document imports the importer, which imports the trial, which imports this file).
 */
export interface Stepped {
  readonly settings: Pick<Settings, 'playing' | 'realTime' | 'dt' | 'substeps'>;
  /** The model steps implicitly (its steps' solves get the solve budget). */
  readonly implicit: boolean;
  /** What the last `advance` did (null if it failed or was interrupted). */
  readonly lastAdvance: Pick<Advance, 'simulated'> | null;
  /** The stroke acts for `dt` simulated seconds (before the steps of a tick). */
  updateStroke(dt: number): void;
  /** `n` steps of `dt` under a wall-clock budget of `seconds` (0: every step to the tolerance);
   *  false if a step failed or a waiting command interrupted one. */
  advance(dt: number, n: number, seconds?: number): boolean;
}

/**
 * Wall-clock ms a tick's implicit solves may take before each step is accepted at its first
 * iterate within the engine's minimum accuracy (the rest of the 16 ms tick draws, publishes and
 * reads commands). Measured: BENCHMARKS.md, "Every frame on time".
 */
export const SOLVE_BUDGET_MS = 12;

export class Stepper {
  private last = 0;
  private carry = 0;
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
  /**
   * The last ticks' wall-clock and simulated seconds, about a second of wall time: the fraction
   * shown is their ratio, so one quick tick among slow ones does not swing it (the HUD read
   * 66–94 % while the clock measured 0.52).
   */
  private recent: { wall: number; sim: number }[] = [];

  /**
   * `budgetMs`: the wall-clock budget of a tick's explicit steps; `solveBudgetMs`: of its
   * implicit solves (an implicit step's solve stops at its deadline, drawing then takes the rest).
   */
  constructor(private readonly now: () => number, private readonly budgetMs = 30, private readonly solveBudgetMs = SOLVE_BUDGET_MS) {}

  /** One tick; returns whether it stepped. */
  tick(doc: Stepped): boolean {
    const now = this.now();
    // At most 0.1 s of clock is simulated per tick: a longer gap (the worker busy elsewhere, a
    // frame that took long to draw) is time the simulation fell behind, slow motion too.
    const gap = this.last ? (now - this.last) / 1000 : 1 / 60;
    const elapsed = Math.min(0.1, gap);
    this.last = now;
    const s = doc.settings;
    if (!s.playing) {
      doc.updateStroke(0);
      this.slowMotion = false;
      this.carry = 0;
      this.lastEnd = 0;
      this.recent = [];
      return false;
    }
    const want = s.realTime ? elapsed / s.dt + this.carry : s.substeps;
    // A tenth of a step of slack: at dt = 1/60 s (implicit) a 16 ms tick still takes its step,
    // and the carry (then slightly negative) keeps the average on the clock.
    const n = s.realTime ? Math.floor(want + 0.1) : want;
    this.carry = s.realTime ? want - n : 0;
    doc.updateStroke(s.dt * n);
    const done = this.run(doc, s.dt, n, doc.implicit ? this.solveBudgetMs : this.budgetMs);
    this.slowMotion = done < n || (s.realTime && gap > 0.1);
    if (this.slowMotion) this.carry = 0;
    const end = this.now();
    // The first tick after a start or a pause has no tick before it: its own span only, kept
    // out of the window.
    const first = !this.lastEnd;
    const wall = (end - (this.lastEnd || now)) / 1000;
    this.lastEnd = end;
    const fraction = first ? (wall > 0 ? Math.min(1, (done * s.dt) / wall) : 1) : this.fraction(wall, done * s.dt);
    this.realTimeFraction = this.slowMotion ? fraction : 1;
    return done > 0;
  }

  /** Simulated over wall seconds over the last second or so of ticks, this one included (≤ 1). */
  private fraction(wall: number, sim: number): number {
    const r = this.recent;
    r.push({ wall, sim });
    let total = r.reduce((a, x) => a + x.wall, 0);
    while (r.length > 1 && total - r[0].wall >= 1) total -= r.shift()!.wall;
    const simulated = r.reduce((a, x) => a + x.sim, 0);
    return total > 0 ? Math.min(1, simulated / total) : 1;
  }

  /**
   * `n` steps of `dt` under a wall-clock budget of `budgetMs` (Infinity: every step to the
   * tolerance, all of them); returns how many steps of `dt` they covered (0 if a step failed or
   * a command interrupted it).
   */
  run(doc: Stepped, dt: number, n: number, budgetMs = Infinity): number {
    if (n <= 0) return 0;
    const t0 = this.now();
    const ok = doc.advance(dt, n, Number.isFinite(budgetMs) ? budgetMs / 1000 : 0);
    this.spent += this.now() - t0;
    const a = doc.lastAdvance;
    return ok && a ? Math.min(n, Math.round(a.simulated / dt)) : 0;
  }

  /** Wall-clock ms spent stepping since the last call (for the frame). */
  take(): number {
    const ms = this.spent;
    this.spent = 0;
    return ms;
  }
}
