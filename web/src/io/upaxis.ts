// The up axis the user chose for a file, by file name, kept in localStorage: a file imported again
// takes it without asking (whatever io/import.ts `guessUp` says), and a wrong guess fixed in
// Model › up axis is remembered the same way. Per file, not per format: one Z-up OBJ says nothing
// about the next OBJ. glTF declares Y-up and is never asked. (The per-format memory of before
// lived under `softsculpt.upAxis`; it is no longer read.)

import type { Up } from './import';

export const UP_KEY = 'softsculpt.upAxisByFile';
/** Files remembered at most (the oldest forgotten first), so the entry stays small. */
const MOST = 200;

/** The remembered answers by file name ({} if none or unreadable). */
export function rememberedUp(): Record<string, Up> {
  try {
    const o = JSON.parse(localStorage.getItem(UP_KEY) ?? '{}') as Record<string, unknown>;
    return Object.fromEntries(Object.entries(o).filter(([, v]) => v === 'y' || v === 'z')) as Record<string, Up>;
  } catch {
    return {};
  }
}

/** Remember `up` for the file `name` (of `format`: glTF's own Y is not an answer). */
export function rememberUp(name: string | undefined, format: string | undefined, up: Up): void {
  if (!name || format === 'glTF' || format === 'GLB') return;
  const kept = Object.entries(rememberedUp()).filter(([k]) => k !== name).slice(-(MOST - 1));
  try { localStorage.setItem(UP_KEY, JSON.stringify(Object.fromEntries([...kept, [name, up]]))); } catch { /* private mode: not kept */ }
}
