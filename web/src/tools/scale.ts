// The brush's lengths follow the model's size. Imports keep their units (a 5 cm ball stays 5 cm),
// so a brush radius of 0.02–2 m in 0.01 m steps, or a press 0.15 m deep, would cover a small
// model whole and leave five steps of radius to choose from. Every brush length (the radius, its
// slider and key limits, the press's depth) is in a length unit: a power of ten near the model's
// size, the ground grid's square (view/viewport.ts), 1 m for the built-in models. A model of
// another unit rescales the brush's current lengths by the ratio, so the brush covers the same
// part of it.

/** The length unit (m) of a model of bounding-sphere `radius` (m): 10^round(log10(radius / 1.25)). */
export function lengthUnit(radius: number): number {
  return radius > 0 && Number.isFinite(radius) ? Math.pow(10, Math.round(Math.log10(radius / 1.25))) : 1;
}

/** The brush's unit now, and when a new model's lengths are to be rescaled. */
export class BrushUnit {
  /** Metres per brush unit (1 for the built-in models). */
  unit = 1;
  private first = true;
  /** What a saved state (a project, the autosave, an import's fitted brush) just set, in the next model's units. */
  private restored = { radius: false, strengths: false };

  /** Lengths just came from a saved state: the radius and/or the tools' strengths, in the units of the model that follows. */
  tookUi(what: { radius: boolean; strengths: boolean }): void {
    this.restored = { radius: this.restored.radius || what.radius, strengths: this.restored.strengths || what.strengths };
  }

  /**
   * A model of bounding-sphere `radius` (m) is shown: its unit becomes the brush's; returns the
   * factors to rescale the brush radius and the length strengths by (1 for the first model and
   * for lengths restored with it, which are already in its units).
   */
  model(radius: number): { radius: number; strengths: number } {
    const unit = lengthUnit(radius);
    const f = this.first ? 1 : unit / this.unit;
    const out = { radius: this.restored.radius ? 1 : f, strengths: this.restored.strengths ? 1 : f };
    this.first = false;
    this.restored = { radius: false, strengths: false };
    this.unit = unit;
    return out;
  }
}

/** The one brush unit of the page (the tools' ranges and the panel's sliders read it). */
export const brushUnit = new BrushUnit();

/** Round a range's end to 2 significant digits (the floats of unit × 0.01 print long). */
export function nice(v: number): number {
  return Number(v.toPrecision(2));
}

/** Rescale the brush's lengths: the radius and every strength that is a length, by their factors. */
export function rescaleBrush(brush: { radius: number }, tools: { strength: number; isLength?: boolean }[], f: { radius: number; strengths: number }): void {
  if (f.radius > 0) brush.radius *= f.radius;
  if (f.strengths > 0) for (const t of tools) if (t.isLength) t.strength *= f.strengths;
}
