// The sketch tool's words (worker/sketch.ts, worker/document.ts): an outline left open is said
// to have been closed; a crossing is explained as what to draw.
import { describe, expect, it } from 'vitest';
import { sketchOpen, sketchWhy } from '../src/worker/sketch';

const circle = (n: number, r: number, turns = 1) => Array.from({ length: n }, (_, i) => [r * Math.cos((2 * Math.PI * turns * i) / n), r * Math.sin((2 * Math.PI * turns * i) / n)]).flat();

describe('the sketch tool’s messages', () => {
  it('calls an outline open when its ends are far apart for its size, not when the hand stopped just short', () => {
    // A whole circle drawn with 64 points: the last point is one step (~10 % of the radius)
    // from the first, 5 % of the 2 m size: closed.
    expect(sketchOpen(circle(64, 1))).toBe(false);
    // Three quarters of a circle: its ends 1.4 m apart on a 2 m outline: open.
    expect(sketchOpen(circle(48, 1, 0.75))).toBe(true);
    // An S: its ends at opposite corners.
    const s = Array.from({ length: 40 }, (_, i) => [Math.sin((i / 39) * 2 * Math.PI), i / 39]).flat();
    expect(sketchOpen(s)).toBe(true);
  });

  it('turns the core’s crossing report into what to draw, and leaves other reasons alone', () => {
    expect(sketchWhy('the outline crosses itself: edge 1 (-0.000, 0.044)–(0.037, 0.016) m meets edge 30 (points are numbered from 1)')).toBe('the outline crosses itself; draw it without crossing');
    expect(sketchWhy('an outline needs at least 3 distinct points, got 2')).toBe('an outline needs at least 3 distinct points, got 2');
  });
});
