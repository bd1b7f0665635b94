// Which material the body is made of, for the panel's Material list: the modeler's own (what a
// model is loaded with), a preset of the core's (balloon, jelly, clay, cloth, stiff rubber), or
// "custom" once a material parameter departs from them.
//
// The page knows a preset by the values it set: the body's material parameters (MATERIAL_KEYS)
// just after the preset's undo step arrived. A material is those values, so undo and redo show
// the right name by themselves (undoing clay brings back the values the modeler's had). What was
// learned is kept in the browser (a restored session, a project, another model of the same size
// name their material too); an imported model's values are scaled to its size, and learned
// for it when its first frame arrives.

import type { Params } from './protocol';

/** The body's material parameters (those a material preset may set, params/presets.rs); gas as n at T. */
export const MATERIAL_KEYS = ['stiffness', 'spring_damping', 'bending', 'rigidity', 'damping', 'yield', 'flow', 'gas.amount', 'gas.temperature'] as const;
/**
 * Material parameters added after browsers began keeping what they learned, with the value every
 * material had before: at that value (or absent) they are left out of the key, so a material
 * learned earlier is still named.
 */
const LATER_KEYS: Partial<Record<(typeof MATERIAL_KEYS)[number], number>> = { rigidity: 0 };
/** The modeler's material, which every model is loaded with. */
export const MODELER = 'modeler';
export const CUSTOM = 'custom';
const STORE_KEY = 'softsculpt.materials';
const STORE_MAX = 64;

/** The body's material as a comparable string (relative differences below 1e-9 are the same material). */
export function materialKey(p: Params): string {
  return MATERIAL_KEYS.filter((k) => !(k in LATER_KEYS && (p[k] ?? LATER_KEYS[k]) === LATER_KEYS[k])).map((k) => {
    const v = p[k];
    return typeof v === 'number' ? Number(v.toPrecision(9)) : String(v);
  }).join(',');
}

export class MaterialTracker {
  /** Material values → name, newest last. */
  private readonly known: Map<string, string>;
  private expecting: { name: string; history: string } | null = null;

  constructor(private readonly storage: Pick<Storage, 'getItem' | 'setItem'> | null = safeStorage()) {
    let saved: [string, string][] = [];
    try { saved = JSON.parse(this.storage?.getItem(STORE_KEY) ?? '[]'); } catch { /* unreadable: start afresh */ }
    this.known = new Map(Array.isArray(saved) ? saved.filter((e) => Array.isArray(e) && e.length === 2).map((e) => [String(e[0]), String(e[1])]) : []);
  }

  /** A preset was chosen in the list: its values are those after its undo step arrives. */
  expect(name: string, history: [number, number]): void {
    this.expecting = { name, history: history.join(',') };
  }

  /**
   * The name of the material `params` hold. `history` (undo, redo sizes) tells when an expected
   * preset has landed; `fresh`: a model just loaded with the modeler's material (its values are
   * learned as the modeler's unless they are known already); `given`: with `fresh`, the name
   * an opened project gives its material.
   */
  name(params: Params, history: [number, number], fresh: boolean, given: string | null = null): string {
    const key = materialKey(params);
    if (this.expecting && history.join(',') !== this.expecting.history) {
      this.learn(key, this.expecting.name);
      this.expecting = null;
    }
    // `given`: the name an opened project says its material has (UiState.material); custom
    // values stay unnamed.
    if (fresh && given) {
      if (given === CUSTOM) return CUSTOM;
      this.learn(key, given);
      return given;
    }
    const known = this.known.get(key);
    if (known) return known;
    if (fresh) { this.learn(key, MODELER); return MODELER; }
    return CUSTOM;
  }

  private learn(key: string, name: string): void {
    this.known.delete(key);
    this.known.set(key, name);
    while (this.known.size > STORE_MAX) this.known.delete(this.known.keys().next().value!);
    try { this.storage?.setItem(STORE_KEY, JSON.stringify([...this.known])); } catch { /* private mode: this session only */ }
  }
}

function safeStorage(): Storage | null {
  try { return typeof localStorage === 'undefined' ? null : localStorage; } catch { return null; }
}
