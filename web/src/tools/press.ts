// Press (P): push on the faces under the brush with an external pressure along their inward
// normal, while the button is held; the brush follows the surface under the pointer.
// Strength: the pressure (Pa) at the brush centre.

import { BaseTool } from './tool';

export class PressTool extends BaseTool {
  readonly name = 'press';
  readonly label = 'Press';
  readonly key = 'p';
  readonly tooltip = 'Press (P): push the faces under the brush inward (strength = pressure, Pa)';
  strength = 60;
  readonly strengthInfo = { label: 'pressure (Pa)', min: 1, max: 2000 };
}
