// Every modeling operation as one undo step, and undo and redo. Undo keeps deltas (the engine's
// `mark` before an operation, `delta` after it): a brush stroke keeps what it painted and the
// state of those vertices ('touched', stroking.ts), a drag or any other operation the whole state
// ('all'; a topology change keeps the whole earlier world). Entries are limited to HISTORY_STEPS
// and HISTORY_BYTES in all (docstate.ts), the oldest dropped first.

import type { DeltaScope } from '../engine/world';
import { travel as travelHistory } from '../history';
import { errorText, type DocState, type Entry, type SceneSource } from './docstate';
import { strokeEnd } from './stroking';

/**
 * Run a modeling operation as one undoable step (a delta of `scope` against the world before
 * it). If it fails, it is reported and the world goes back to how it was. Returns whether it
 * succeeded.
 */
export function edit(d: DocState, label: string, undoable: boolean, op: () => void, scope: DeltaScope = 'all', failText?: (why: string) => string): boolean {
  if (d.stroke) strokeEnd(d);
  const w = d.world;
  const settings = { ...d.settings }, scene = d.session;
  const hadModel = w.bodyCount > 0;
  w.mark();
  try {
    op();
  } catch (e) {
    Object.assign(d.settings, settings);
    d.session = scene;
    // Back to the mark: the same meshes, masses and pins as the page has.
    try { w.applyDelta(w.delta('all')); } catch { /* the engine left it as it was */ }
    const why = errorText(e);
    d.hooks.message(failText ? failText(why) : `${label}: ${why}${hadModel ? ' — the model is as it was before' : ''}`, 'error');
    return false;
  } finally {
    d.hooks.progress(null);
  }
  if (undoable && hadModel) d.history.push(label, { delta: w.delta(scope), settings, scene });
  d.touched();
  d.hooks.changed();
  return true;
}

/** Undo or redo one step (not while a stroke is under way); says what it did. */
export function travel(d: DocState, dir: 'undo' | 'redo'): void {
  if (d.stroke) return;
  try {
    const item = travelHistory(d.history, dir, (e) => apply(d, e));
    if (!item) { d.hooks.message(`nothing to ${dir}`); return; }
    d.hooks.message(`${dir === 'undo' ? 'undid' : 'redid'} ${item.label}`);
  } catch (e) {
    d.hooks.message(`${dir} failed: ${errorText(e)}`, 'error');
  }
  d.hooks.changed();
}

/** Apply an undo step; returns the step that takes the world back to how it is now. */
function apply(d: DocState, entry: Entry): Entry {
  const w = d.world;
  const now: Entry = { delta: new Uint8Array(0), settings: { ...d.settings }, scene: d.session };
  now.delta = w.applyDelta(entry.delta);
  if (entry.scene !== d.session) rejoinScene(d, entry.scene);
  Object.assign(d.settings, entry.settings);
  d.touched();
  return now;
}

/**
 * Undo or redo crossed a scene's opening: the world is back, but the engine's record of the
 * scene (names, obstacles and events as written, for saving) is the other one. Re-open the
 * scene (or forget it) and put the world back into it.
 */
function rejoinScene(d: DocState, scene: SceneSource | null): void {
  const w = d.world, snap = w.snapshot();
  if (scene) w.openScene(scene.text, scene.files); else w.clear();
  w.restore(snap);
  d.session = scene;
}
