// The panel's parameter controls, made from the engine's parameter table (ids, units, valid
// ranges, choices and help text: engine/world.ts `paramTable`, sent with the first frame). This
// file only chooses which parameters the panel shows, in which folder, with which label and
// slider range; everything else comes from the table. Edits go to the worker by table id.

import type GUI from 'lil-gui';
import type { Controller } from 'lil-gui';
import type { ParamInfo, ParamValue, Params } from './protocol';

/** Where a parameter goes, its short label and the slider's range (a UI hint, not the valid range). */
interface Shown { folder: string; label: string; slider?: [number, number, number?] }

export const SHOWN: Record<string, Shown> = {
  integrator: { folder: 'sim', label: 'integrator' },
  tolerance: { folder: 'sim', label: 'implicit tolerance' },
  stiffness: { folder: 'sim', label: 'stiffness k', slider: [0, 5000] },
  spring_damping: { folder: 'sim', label: 'spring damping', slider: [0, 5] },
  bending: { folder: 'sim', label: 'bending k_b', slider: [0, 5000] },
  damping: { folder: 'sim', label: 'damping c', slider: [0, 20] },
  self_collision: { folder: 'sim', label: 'self-collision' },
  mass: { folder: 'sim', label: 'total mass', slider: [0.01, 100] },
  contact_thickness: { folder: 'sim', label: 'contact thickness', slider: [0, 0.05, 0.0005] },
  contact_friction: { folder: 'sim', label: 'contact friction μ', slider: [0, 2] },
  gravity: { folder: 'world', label: 'gravity g', slider: [0, 30] },
  ground: { folder: 'world', label: 'ground' },
  'ground.height': { folder: 'world', label: 'ground height', slider: [-5, 5] },
  'ground.friction': { folder: 'world', label: 'friction μ', slider: [0, 2] },
  'ground.restitution': { folder: 'world', label: 'restitution e', slider: [0, 1] },
  'gas.amount': { folder: 'gas', label: 'amount n', slider: [0, 0.1, 0.0001] },
  'gas.temperature': { folder: 'gas', label: 'temperature T', slider: [1, 1000] },
  'gas.volume': { folder: 'gas', label: 'volume' },
  wind_drag: { folder: 'wind', label: 'drag cw', slider: [0, 10] },
};

/** "≥ 0", "> 0", "between 0 and 1", "finite". */
function validText(r: ParamInfo): string {
  if (r.choices.length) return r.choices.join(', ');
  if (typeof r.default === 'boolean') return 'on or off';
  if (r.min !== null && r.max !== null) return `between ${r.min} and ${r.max}`;
  if (r.min !== null) return `${r.min_open ? '>' : '≥'} ${r.min}`;
  if (r.max !== null) return `≤ ${r.max}`;
  return 'finite';
}

/** The tooltip of a parameter: its help, unit, valid values, default and id. */
export function tooltip(r: ParamInfo): string {
  const unit = r.unit ? ` ${r.unit}` : '';
  const def = Array.isArray(r.default) ? r.default.join(', ') : String(r.default);
  return `${r.help}. Valid: ${validText(r)}${unit}; default ${def}${unit} (${r.id})`;
}

/**
 * Add the shown parameters of `table` to `folders`; `values` is the object the controllers
 * bind to (the caller refreshes it from the mirror), `set` sends an edit.
 */
export function addParams(table: ParamInfo[], folders: Record<string, GUI>, values: Record<string, ParamValue>,
  set: (id: string, v: ParamValue) => void, tip: (c: Controller, text: string) => Controller): void {
  for (const r of table) {
    const s = SHOWN[r.id];
    if (!s) continue;
    const folder = folders[s.folder];
    const label = r.unit ? `${s.label} (${r.unit})` : s.label;
    values[r.id] ??= r.default;
    let c: Controller;
    if (r.choices.length) c = folder.add(values, r.id, r.choices).onChange((v: string) => set(r.id, v));
    else if (typeof r.default === 'boolean') c = folder.add(values, r.id).onChange((v: boolean) => set(r.id, v));
    else {
      const [min, max, step] = s.slider ?? [];
      c = folder.add(values, r.id, min, max, step).onFinishChange((v: number) => set(r.id, Number(v))).decimals(decimalsFor(max, step));
    }
    tip(c.name(label), tooltip(r));
  }
}

/**
 * Decimals shown for a number: those of the slider's step, else three significant digits of the
 * slider's largest value (5000 → 0, 5 → 2, 0.05 → 4); fields without a slider show 4.
 */
export function decimalsFor(max?: number, step?: number): number {
  if (step !== undefined && step > 0) return Math.max(0, Math.min(8, Math.ceil(-Math.log10(step) - 1e-9)));
  if (max === undefined || !(max > 0)) return 4;
  return Math.max(0, Math.min(8, 2 - Math.floor(Math.log10(max))));
}

/** Copy the mirror's parameters into the controllers' object (a parameter without a value keeps its last). */
export function takeParams(values: Record<string, ParamValue>, params: Params): void {
  for (const [k, v] of Object.entries(params)) if (v !== null) values[k] = v;
}
