// The panel's number fields show their values in significant digits (format.ts `fieldText`):
// lil-gui writes a field's number as JavaScript prints it (0.20254629629629634 after `[` three
// times, 0.35000000000000003 after `[` and `]`), or with a fixed number of decimals when
// `decimals()` was set (dt 1e-6 as "0.00000", g 9.81 as "9.8"). Only the text changes: the value
// the field holds is the one set until the user types another.

import { NumberController } from 'lil-gui';
import { fieldText } from './format';

/** What lil-gui's number field has that this module uses (not in its types). */
interface NumberField {
  $input: HTMLInputElement;
  _inputFocused?: boolean;
  getValue(): number;
}

let installed = false;

/** Make every lil-gui number field (made before or after) show significant digits. */
export function showSignificantDigits(): void {
  if (installed) return;
  installed = true;
  const proto = NumberController.prototype as unknown as { updateDisplay(this: NumberField): unknown };
  const update = proto.updateDisplay;
  proto.updateDisplay = function (this: NumberField) {
    const r = update.call(this);
    // While the user types, the field is theirs (lil-gui leaves it alone too).
    if (!this._inputFocused) this.$input.value = fieldText(this.getValue());
    return r;
  };
}
