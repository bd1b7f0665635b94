// The panel's parameter controls, made from the engine's parameter table (ids, units, valid
// ranges, choices and help text: engine/world.ts `paramTable`, sent with the first frame). This
// file only chooses which parameters the panel shows, in which folder, with which label and
// slider range; everything else comes from the table. Edits go to the worker by table id.

import type GUI from 'lil-gui';
import type { Controller } from 'lil-gui';
import type { ParamId, ParamInfo, ParamValue, Params } from './protocol';
import { nice } from './tools/scale';

/**
 * Where a parameter goes, its short label and the slider's range (a UI hint, not the valid
 * range), made for the built-in models (length unit 1 m); `power`: the range scales with the
 * model's length unit to this power, the exponent of the parameter's unit under similarity
 * (`params/similarity.rs`: an import keeps its size and gets the modeler's values scaled so,
 * e.g. k × s², nRT × s⁴), so a 5 cm import's values fall inside its sliders.
 */
interface Shown { folder: string; label: string; slider?: [number, number, number?]; power?: number }

export const SHOWN: Record<string, Shown> = {
  integrator: { folder: 'sim', label: 'integrator' },
  tolerance: { folder: 'sim', label: 'implicit tolerance' },
  stiffness: { folder: 'sim', label: 'stiffness k', slider: [0, 5000], power: 2 },
  spring_damping: { folder: 'sim', label: 'spring damping', slider: [0, 5], power: 2.5 },
  bending: { folder: 'sim', label: 'bending k_b', slider: [0, 5000], power: 2 },
  rigidity: { folder: 'sim', label: 'rigidity D', slider: [0, 0.5], power: 4 },
  damping: { folder: 'sim', label: 'damping c', slider: [0, 20], power: -0.5 },
  self_collision: { folder: 'sim', label: 'self-collision' },
  yield: { folder: 'sim', label: 'yield strain (clay)', slider: [0, 0.1, 0.001] },
  flow: { folder: 'sim', label: 'plastic flow', slider: [0, 20, 0.1] },
  mass: { folder: 'sim', label: 'total mass', slider: [0.01, 100], power: 3 },
  contact_thickness: { folder: 'sim', label: 'contact thickness', slider: [0, 0.05, 0.0005], power: 1 },
  contact_friction: { folder: 'sim', label: 'contact friction μ', slider: [0, 2] },
  gravity: { folder: 'world', label: 'gravity g', slider: [0, 30] },
  ground: { folder: 'world', label: 'ground' },
  'ground.height': { folder: 'world', label: 'ground height', slider: [-5, 5], power: 1 },
  'ground.friction': { folder: 'world', label: 'friction μ', slider: [0, 2] },
  'ground.restitution': { folder: 'world', label: 'restitution e', slider: [0, 1] },
  'gas.amount': { folder: 'gas', label: 'amount n', slider: [0, 0.1, 0.0001], power: 4 },
  'gas.temperature': { folder: 'gas', label: 'temperature T', slider: [1, 1000] },
  'gas.volume': { folder: 'gas', label: 'volume' },
  wind_drag: { folder: 'wind', label: 'drag cw', slider: [0, 10], power: 0.5 },
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
  set: (id: ParamId, v: ParamValue) => void, tip: (c: Controller, text: string) => Controller): void {
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
 * Rescale the sliders of parameters whose range follows the model's size (`power`) to the
 * length unit `unit` (m); rounded to 2 significant digits.
 */
export function scaleSliders(controllers: Controller[], unit: number): void {
  for (const c of controllers) {
    const s = typeof c.property === 'string' ? SHOWN[c.property] : undefined;
    if (!s?.slider || !s.power) continue;
    const f = Math.pow(unit, s.power);
    const [min, max, step] = s.slider;
    c.min(nice(min * f)).max(nice(max * f));
    if (step !== undefined) c.step(nice(step * f));
    // Off the built-ins' unit two more digits: the model's own values sit anywhere in the
    // power-of-ten range (the unit rounds the size; to a power 4 that is up to a factor 10²).
    const extra = unit === 1 ? 0 : 2;
    c.decimals(Math.min(10, extra + decimalsFor(nice(max * f), step === undefined ? undefined : nice(step * f))));
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
