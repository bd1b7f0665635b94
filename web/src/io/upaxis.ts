// The user's last up axis per file format (OBJ, PLY, STL), kept in localStorage: an import whose
// own guess is unsure (io/import.ts `guessUp`) takes it without asking, and a wrong guess fixed in
// Model › up axis is remembered the same way. glTF declares Y-up and is never asked.

import type { Up } from './import';

export const UP_KEY = 'softsculpt.upAxis';

/** The remembered answers by format ({} if none or unreadable). */
export function rememberedUp(): Record<string, Up> {
  try {
    const o = JSON.parse(localStorage.getItem(UP_KEY) ?? '{}') as Record<string, unknown>;
    return Object.fromEntries(Object.entries(o).filter(([, v]) => v === 'y' || v === 'z')) as Record<string, Up>;
  } catch {
    return {};
  }
}

/** Remember `up` as the user's answer for files of `format`. */
export function rememberUp(format: string | undefined, up: Up): void {
  if (!format || format === 'glTF' || format === 'GLB') return;
  try { localStorage.setItem(UP_KEY, JSON.stringify({ ...rememberedUp(), [format]: up })); } catch { /* private mode: not kept */ }
}
