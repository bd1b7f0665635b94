// Press (P): push the surface under the brush inward, while the button is held: each vertex the
// brush passes over is held by a target spring (inside the implicit step) at where it was when
// first touched, moved inward along its normal by the depth × the brush weight (Shift: outward).
// Released, the dent springs back. Strength: the depth (m) at the brush centre.

import { BaseTool } from './tool';
import { brushUnit, nice } from './scale';

export class PressTool extends BaseTool {
  readonly name = 'press';
  readonly label = 'Press';
  readonly key = 'p';
  readonly tooltip = 'Press (P): dent the surface under the brush while held (strength = depth at the centre, m; Shift: outward)';
  strength = 0.15;
  /** A length: 0.01–0.5 brush units (metres on the built-in models; tools/scale.ts). */
  readonly isLength = true;
  get strengthInfo() { return { label: 'depth (m)', min: nice(0.01 * brushUnit.unit), max: nice(0.5 * brushUnit.unit) }; }
}
