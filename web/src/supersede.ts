// A frame from the worker that arrives before the page drew the previous one supersedes it:
// the newer positions and statistics are drawn, and what the older one brought that the newer
// lacks carries over — the fields sent only when they change (topology, masses and pins,
// parameters, settings, undo sizes) or only once (the parameter table, the material presets, the engine's thread count).
// Per-frame fields whose absence means something (`recording` absent: none) are the newer's.

import type { Frame } from './protocol';

export function supersede(older: Frame, newer: Frame): Frame {
  const { topology, body, params, table, presets, threads, settings, history } = older;
  return { topology, body, params, table, presets, threads, settings, history, ...stripUndefined(newer) };
}

function stripUndefined<T extends object>(o: T): T {
  return Object.fromEntries(Object.entries(o).filter(([, v]) => v !== undefined)) as T;
}
