// Where a failed step goes back to. The engine rolls a failed call of steps back to its start
// (world/rollback.rs), but the start of the failing frame may already be collapsing: a body
// turned half inside out, its volume near zero. So the document keeps a few rewind points — whole
// snapshots of the world every REWIND_EVERY simulated seconds since the user's last change — and
// on a failure goes back to the last one known good: the newest point whose body volumes were
// healthy (every gas-filled body at least HEALTHY of its volume after that change) and stayed
// healthy until the next point, REWIND_EVERY later. Nothing older than the user's last change
// is kept (any edit clears the points), so going back never undoes what the user did: at worst
// it is the state the change left.

/** Simulated seconds between rewind points (at least; see REWIND_OVERHEAD). */
export const REWIND_EVERY = 0.25;
/**
 * The share of time the snapshots may take: the interval grows to snapshot ms / this (in
 * Chromium a snapshot takes ~0.2 ms at 642 vertices, ~6 ms at 2,562, ~33 ms at 40,962 and
 * ~170 ms at 163,842: points every 0.25 s, 0.25 s, 1.1 s and 5.7 s of simulated time).
 */
export const REWIND_OVERHEAD = 0.03;
/** Points kept (the newest; REWIND_KEEP × REWIND_EVERY = 2 s of simulated time back). */
export const REWIND_KEEP = 8;
/** …within this many bytes (a 160k-vertex world's snapshot is ~15 MB): the oldest go first, the first point stays. */
export const REWIND_BYTES = 96 * 1024 * 1024;
/** A gas-filled body is healthy while its volume is at least this share of its volume after the last change. */
export const HEALTHY = 0.5;

export interface RewindPoint { time: number; volumes: number[]; snapshot: Uint8Array }

export class Rewind {
  private points: RewindPoint[] = [];
  /** Wall-clock ms of the last snapshot (sets the interval). */
  private costMs = 0;
  /** Simulated seconds between points for this world: REWIND_EVERY, or longer where a snapshot is costly. */
  get every(): number { return Math.max(REWIND_EVERY, this.costMs / 1000 / REWIND_OVERHEAD); }
  /** Per body: its volume at the first point, or 0 for a body without gas (an open surface). */
  private base: number[] = [];

  /** The user changed something: the points before it are no longer the model's past. */
  clear(): void { this.points = []; this.base = []; }

  get size(): number { return this.points.length; }
  get newestTime(): number | null { return this.points.length ? this.points[this.points.length - 1].time : null; }

  /**
   * Keep the state at simulated `time` if it is the first since the last change or `every`
   * after the newest point. `volumes`: every body's volume (m³), `gas`: which bodies hold gas.
   */
  offer(time: number, volumes: () => number[], gas: () => boolean[], snapshot: () => Uint8Array): void {
    const last = this.newestTime;
    if (last !== null && time - last < this.every - 1e-9) return;
    const v = volumes();
    if (this.points.length === 0) { const g = gas(); this.base = v.map((x, b) => (g[b] && x > 0 ? x : 0)); }
    const t0 = performance.now();
    this.points.push({ time, volumes: v, snapshot: snapshot() });
    this.costMs = performance.now() - t0;
    let bytes = this.points.reduce((n, p) => n + p.snapshot.byteLength, 0);
    while (this.points.length > 2 && (this.points.length > REWIND_KEEP || bytes > REWIND_BYTES)) {
      bytes -= this.points[1].snapshot.byteLength;
      this.points.splice(1, 1);
    }
  }

  private healthy(p: RewindPoint): boolean {
    return p.volumes.every((v, b) => !(this.base[b] > 0) || (Number.isFinite(v) && v >= HEALTHY * this.base[b]));
  }

  /**
   * The point to go back to after a failure: the newest healthy one whose successor was healthy
   * too (the newest point's successor is the failure, whose state is not known: it is never
   * chosen unless it is the only one); the first point (the state the user's last
   * change left) if none. The newer points are dropped. Null if there are none.
   */
  takeGood(): RewindPoint | null {
    const p = this.points;
    if (p.length === 0) return null;
    let k = p.length - 2;
    while (k > 0 && !(this.healthy(p[k]) && this.healthy(p[k + 1]))) k--;
    k = Math.max(0, k);
    this.points = p.slice(0, k + 1);
    return p[k];
  }
}
