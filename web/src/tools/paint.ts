// The painting brushes: they act every tick on the vertices under the cursor while the button is
// held (worker/strokes.ts), and Shift inverts them. Mass and pin show an overlay.
// - Inflate (I): lengthen the rest lengths (Shift: shorten); strength = rate (1/s).
// - Mass (M): make vertices heavier (Shift: lighter) to localise deformation; strength = rate (1/s).
// - Pin (N): pin vertices so they never move (Shift: unpin).

import { BaseTool, type BodyView } from './tool';
import { divergingColor } from './brush';

export class InflateTool extends BaseTool {
  readonly name = 'inflate';
  readonly label = 'Inflate';
  readonly key = 'i';
  readonly tooltip = 'Inflate (I): lengthen rest lengths under the brush; Shift deflates (strength = rate, 1/s)';
  strength = 0.3;
  readonly strengthInfo = { label: 'growth rate (1/s)', min: 0.01, max: 3 };
}

export class MassTool extends BaseTool {
  readonly name = 'mass';
  readonly label = 'Mass';
  readonly key = 'm';
  readonly tooltip = 'Mass (M): paint vertices heavier so they move less; Shift paints lighter (strength = rate, 1/s)';
  /**
   * 0.5 1/s: a second of brushing makes the vertices under the centre e^0.5 = 1.65× heavier. At
   * 2 1/s (×7.4) a second's scrub over one side of the mushroom's cap toppled it (its top fell
   * 0.75 m); at 0.5 it leans 0.15 m and stands. Painting adds mass rather than moving it from the
   * rest of the body: keeping the total would shift the centre of mass as far (the same torque
   * tips it), and the panel's total mass stays the way to set the body's weight.
   */
  strength = 0.5;
  readonly strengthInfo = { label: 'mass rate (1/s)', min: 0.05, max: 20 };
  overlay(colors: Float32Array, body: BodyView): void {
    const m = body.masses;
    const mean = m.reduce((a, b) => a + b, 0) / m.length;
    for (let i = 0; i < m.length; i++) {
      // log2(m / mean) in [−3, 3] → blue (light) .. white .. red (heavy).
      divergingColor(colors, i, Math.log2(m[i] / mean) / 3);
    }
  }
}

export class PinTool extends BaseTool {
  readonly name = 'pin';
  readonly label = 'Pin';
  readonly key = 'n';
  readonly tooltip = 'Pin (N): pin the vertices under the brush so they never move; Shift unpins';
  strength = 0;
  readonly strengthInfo = null;
  overlay(colors: Float32Array, body: BodyView): void {
    const p = body.pinned;
    for (let i = 0; i < p.length; i++) colors.set(p[i] ? [0.9, 0.15, 0.15] : [0.85, 0.85, 0.85], 3 * i);
  }
}
