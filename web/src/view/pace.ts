// The HUD's first words: how fast the simulation goes. The worker reports its pace with each
// frame (real time, or the fraction of it in slow motion); a step that takes seconds (a stiff
// body at 10,242 vertices lifting off the ground: one step ~2 s in wasm) sends no frame for
// that long, and the last frame's "real time" would stay on screen while the model sits still.
// So after STALL_MS without a frame the line says the page is waiting, and for how long.

/** Milliseconds without a new frame (while playing, nothing else under way) after which the HUD says it waits for a step. */
export const STALL_MS = 1000;

export interface PaceInput {
  /** The simulation plays (not paused by the user or an error). */
  playing: boolean;
  /** A long operation (import, subdivide, …) shows its own progress. */
  busy: boolean;
  /** The last frame's slow-motion flag and its fraction of real time (0–1). */
  slowMotion: boolean;
  realTimeFraction: number;
  /** The relative residual time-limited steps were accepted at (0: every step converged; `Frame.accuracy`). */
  accuracy?: number;
  /** Milliseconds since the last frame arrived. */
  sinceFrameMs: number;
}

/** The pace as the HUD shows it. */
export function paceText(p: PaceInput): string {
  if (!p.playing) return 'paused';
  if (!p.busy && p.sinceFrameMs >= STALL_MS) return `waiting for a step: ${(p.sinceFrameMs / 1000).toFixed(1)} s so far`;
  const speed = p.slowMotion ? `${fractionText(p.realTimeFraction)} of real time (slow motion)` : 'real time';
  return p.accuracy ? `${speed}, steps accurate to ${accuracyText(p.accuracy)} (time-limited)` : speed;
}

/**
 * A fraction of real time in slow motion as a percentage that never contradicts it: whole
 * percents, one decimal below 1 % (0.004 reads "0.4%", not "0%") and above 99 % (0.996 reads
 * "99.6%", not "100%"), and never 100 %.
 */
export function fractionText(f: number): string {
  const pct = Math.max(0, f * 100);
  if (pct < 1) return `${pct < 0.1 ? pct.toPrecision(1) : pct.toFixed(1)}%`;
  if (pct < 99) return `${pct.toFixed(0)}%`;
  return `${Math.min(99.9, Math.floor(pct * 10) / 10).toFixed(1)}%`;
}

/** A relative residual as the HUD says it: "3%", "0.4%". */
export function accuracyText(residual: number): string {
  const pct = residual * 100;
  return `${pct >= 1 ? pct.toFixed(0) : pct.toFixed(1)}%`;
}

/**
 * The drawing's rate as the HUD shows it: the view's frames per second, and in slow motion how
 * often the shape itself changes (the view redraws the same shape many times between the
 * worker's frames: "view 44 fps" alone read as smooth while the model moved twice a second).
 */
export function viewText(fps: number, shapesPerSecond: number, slowMotion: boolean): string {
  const view = `view ${fps.toFixed(0)} fps`;
  return slowMotion ? `${view}, new shape ${shapesPerSecond.toFixed(shapesPerSecond < 10 ? 1 : 0)}/s` : view;
}
