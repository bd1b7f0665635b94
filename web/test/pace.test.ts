// The HUD's pace line (view/pace.ts): it says when the page waits for a step that takes seconds
// instead of repeating the last frame's "real time".
import { describe, expect, it } from 'vitest';
import { paceText, STALL_MS, viewText } from '../src/view/pace';
import { Stepper } from '../src/worker/stepper';
import type { Document } from '../src/worker/document';

const base = { playing: true, busy: false, slowMotion: false, realTimeFraction: 1, sinceFrameMs: 16 };

describe('the HUD pace', () => {
  it('shows the last frame’s pace while frames come', () => {
    expect(paceText(base)).toBe('real time');
    expect(paceText({ ...base, slowMotion: true, realTimeFraction: 0.126 })).toBe('13% of real time (slow motion)');
    // Never "0%" or "100%" in slow motion (a new-user trial read "100 % of real time (slow motion)").
    expect(paceText({ ...base, slowMotion: true, realTimeFraction: 0.004 })).toBe('0.4% of real time (slow motion)');
    expect(paceText({ ...base, slowMotion: true, realTimeFraction: 0.0004 })).toBe('0.04% of real time (slow motion)');
    expect(paceText({ ...base, slowMotion: true, realTimeFraction: 0.996 })).toBe('99.6% of real time (slow motion)');
    expect(paceText({ ...base, slowMotion: true, realTimeFraction: 0.9999 })).toBe('99.9% of real time (slow motion)');
    expect(paceText({ ...base, slowMotion: true, realTimeFraction: 1.2 })).toBe('99.9% of real time (slow motion)');
  });
  it('says it waits, and how long, when no frame came for a second while playing', () => {
    expect(paceText({ ...base, sinceFrameMs: STALL_MS - 1 })).toBe('real time');
    expect(paceText({ ...base, sinceFrameMs: 2345 })).toBe('waiting for a step: 2.3 s so far');
  });
  it('says paused when paused, and leaves a long operation to its progress line', () => {
    expect(paceText({ ...base, playing: false, sinceFrameMs: 60000 })).toBe('paused');
    expect(paceText({ ...base, busy: true, sinceFrameMs: 60000 })).toBe('real time');
  });
  it('says, in slow motion, how often the shape changes, not only how often the view redraws it', () => {
    expect(viewText(44.2, 43.9, false)).toBe('view 44 fps');
    expect(viewText(44.2, 2.04, true)).toBe('view 44 fps, new shape 2.0/s');
    expect(viewText(30, 12.4, true)).toBe('view 30 fps, new shape 12/s');
  });

  it('says how accurate time-limited steps were, beside the speed', () => {
    expect(paceText({ ...base, accuracy: 0.031 })).toBe('real time, steps accurate to 3% (time-limited)');
    expect(paceText({ ...base, slowMotion: true, realTimeFraction: 0.5, accuracy: 0.004 })).toBe('50% of real time (slow motion), steps accurate to 0.4% (time-limited)');
    expect(paceText({ ...base, accuracy: 0 })).toBe('real time');
  });
});

describe('the worker’s fraction of real time (stepper.ts)', () => {
  // A fake clock and a document whose step takes `costMs` of it: the fraction shown is
  // simulated seconds over wall seconds, from one tick's end to the next's.
  const run = (costMs: number, ticks: number, waitMs: number | ((i: number) => number) = 2) => {
    let t = 1000;
    const dt = 1 / 60;
    const doc: { lastAdvance: null | { simulated: number } } & Record<string, unknown> = {
      settings: { playing: true, realTime: true, dt, substeps: 1 },
      updateStroke() {},
      implicit: true,
      lastAdvance: null,
      // As `World::advance` under a real-time budget: steps while the budget lasts, at least one.
      advance(h: number, n: number, seconds: number) {
        const t0 = t;
        let k = 0;
        while (k < n && (k === 0 || t - t0 < seconds * 1000)) { t += costMs; k++; }
        doc.lastAdvance = { simulated: k * h };
        return true;
      },
    };
    const stepper = new Stepper(() => t);
    const fractions: number[] = [];
    for (let i = 0; i < ticks; i++) {
      t += typeof waitMs === 'number' ? waitMs : waitMs(i); // the worker's wait between ticks
      stepper.tick(doc as unknown as Document);
      fractions.push(stepper.slowMotion ? stepper.realTimeFraction : NaN);
    }
    return fractions;
  };

  it('a step of 1 s reads as 1/60 of real time, not the steps done over the 0.1 s of steps wanted', () => {
    const f = run(1000, 5).slice(1);
    // Each tick: one step (dt = 1/60 s) in 1002 ms from the last tick's end.
    for (const x of f) expect(x).toBeCloseTo((1 / 60) / 1.002, 6);
  });

  it('steps of 50 ms at 1/60 s read as a third of real time', () => {
    const f = run(50, 60).slice(25);
    // The solve budget (12 ms) lets one 50 ms step run per tick: 16.7 ms simulated in 52 ms.
    for (const x of f) expect(x).toBeCloseTo((1000 / 60) / 52, 6);
  });

  it('ticks 150 ms apart simulate 0.1 s each: two thirds of real time, not "real time"', () => {
    // Cheap steps, but the worker comes back only every 150 ms (busy drawing or answering):
    // each tick simulates its most, 0.1 s (6 steps), so the clock runs ahead. Before, every
    // tick did the steps it wanted and the HUD said "real time".
    const f = run(0.1, 30, 150).slice(10);
    for (const x of f) expect(x).toBeCloseTo(0.1 / 0.1506, 3);
  });

  it('a slow tick among quick ones reads as the average over the last second, not that tick alone', () => {
    // Cheap steps; every other tick comes 150 ms after the last (slow: 0.1 s simulated), the
    // others 2 ms after. Over a second the clock gives ~152 ms per pair of ticks and the
    // simulation 0.1 s + what the quick tick catches up (~0): about 0.66 — the slow tick alone
    // would read the same here, but never more than the average allows.
    const f = run(0.1, 40, (i) => (i % 2 ? 150 : 2)).slice(8).filter((x) => !Number.isNaN(x));
    expect(f.length).toBeGreaterThan(5);
    for (const x of f) expect(x).toBeGreaterThan(0.6);
    for (const x of f) expect(x).toBeLessThan(0.72);
  });

  it('steps that fit the clock are not slow motion', () => {
    // NaN marks a tick not in slow motion (the page then says "real time").
    expect(run(2, 20).slice(2).every((x) => Number.isNaN(x))).toBe(true);
  });
});
