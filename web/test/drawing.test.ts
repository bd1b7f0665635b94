// The view's drawing buffer on a software renderer (view/viewport.ts `pixelRatio`): within the
// pixel budget up to 4.8 Mpx windows (at 1/4 of a CSS pixel beyond), the screen's own ratio with
// a GPU or when asked for.
import { describe, expect, it } from 'vitest';
import { pixelRatio, SOFTWARE_PIXELS } from '../src/view/viewport';

describe('the drawing buffer', () => {
  it('keeps a software renderer within its pixel budget up to 4.8 Mpx windows', () => {
    for (const [w, h] of [[1280, 800], [1920, 1080], [2560, 1440], [800, 600]]) {
      const r = pixelRatio(true, 1, w, h);
      const pixels = w * r * (h * r);
      // At the budget (the ratio is a square root: its rounding is ~1e-16 relative), or the
      // screen's own when the window is small enough.
      expect(pixels).toBeLessThanOrEqual(SOFTWARE_PIXELS * (1 + 1e-12));
      if (w * h > SOFTWARE_PIXELS) expect(pixels).toBeCloseTo(SOFTWARE_PIXELS, 3);
      else expect(r).toBe(1);
    }
  });

  it('draws at the screen\'s ratio with a GPU, or when the user asks for full resolution', () => {
    expect(pixelRatio(false, 1, 1920, 1080)).toBe(1);
    expect(pixelRatio(false, 2, 1920, 1080)).toBe(2);
    expect(pixelRatio(false, 3, 1920, 1080)).toBe(2); // at most 2, as before
  });

  it('never goes below a quarter of a CSS pixel, nor breaks on an unsized canvas', () => {
    // 10⁸ CSS pixels: the budget would need ratio 0.055; drawn at ¼ (6.25 Mpx) instead.
    expect(pixelRatio(true, 1, 10000, 10000)).toBe(0.25);
    expect(pixelRatio(true, 2, 0, 0)).toBe(2);
    expect(pixelRatio(true, 1, 320, 200)).toBe(1); // 64,000 pixels: within the budget already
  });
});
