// Project files and the autosave in the document: the world written as a project (its snapshot
// with the settings and the page's state) or as the autosave's record (with the newest undo
// steps), and read back — a version-2 project checked in a scratch world first, a version-1 file
// migrated by the engine — as one undo step; the page opens on the autosave, else the mushroom.

import { World } from '../engine/world';
import type { ImportFrame } from '../io/import';
import { parse, ProjectError, serialize } from '../project';
import type { Settings, UiState } from '../protocol';
import type { Autosave, AutosaveRecord } from '../storage';
import { errorText, type DocState, type Entry } from './docstate';
import { edit } from './editing';
import { fresh, loadBuiltin } from './opening';

/** Undo steps kept across a reload: the newest that fit in this many bytes (the autosave is written after every operation). */
export const HISTORY_KEPT_BYTES = 48 * 1024 * 1024;

/** What a version-2 project holds. */
type ProjectRecord = { name: string; ui: Record<string, unknown>; snapshot: Uint8Array };

/** Open on the autosave if there is one (and it reads), else the default model. */
export function open(d: DocState, autosave: Autosave | null): void {
  if (autosave) {
    try {
      if ('record' in autosave) openRecordOrThrow(d, autosave.record, false);
      else openProjectText(d, autosave.legacyText, false);
      const kept = 'record' in autosave ? takeHistory(d, autosave.record.history) : 0;
      // The same model as before the reload: its load serial too, so undoing into the kept
      // history does not look like another model to the page (which would frame it anew).
      const opened = 'record' in autosave ? (autosave.record.ui as { opened?: unknown }).opened : undefined;
      if (typeof opened === 'number' && Number.isFinite(opened)) d.settings.opened = opened;
      d.hooks.message(`restored your last session (autosaved)${kept > 0 ? `, with ${kept} undo ${kept === 1 ? 'step' : 'steps'}` : ''}`);
      return;
    } catch (e) {
      d.hooks.message(`the autosave could not be read (${errorText(e)}); opened the default model instead`, 'warn');
    }
  }
  loadBuiltin(d, 'mushroom', false);
}

export function projectText(d: DocState): string {
  return serialize({ name: d.settings.model, ui: { ...d.settings, ...d.ui }, snapshot: d.world.snapshot() });
}

/** The autosave's record of the world as it is now, with the newest undo steps (HISTORY_KEPT_BYTES). */
export function autosaveRecord(d: DocState, now: number): AutosaveRecord {
  return { name: d.settings.model, ui: { ...d.settings, ...d.ui }, snapshot: d.world.snapshot(), savedAt: now, history: d.history.newest(HISTORY_KEPT_BYTES) };
}

/** Open a project file the user chose (undoable); what is wrong with it is one message. */
export function openProject(d: DocState, name: string, text: string): void {
  try {
    openProjectText(d, text, true, name);
    d.hooks.message(`opened ${name}`);
  } catch (e) {
    d.hooks.message(`could not open ${name}: ${errorText(e)} — the current model is unchanged`, 'error');
  }
}

/** Open project text (version 2, or a version-1 file migrated by the engine); throws what is wrong. */
export function openProjectText(d: DocState, text: string, undoable = true, label?: string): void {
  const p = parse(text);
  if (p.version === 2) { openRecordOrThrow(d, p, undoable, label); return; }
  const w = d.world;
  w.mark();
  let meta: { name: string; ui: Record<string, unknown> };
  try {
    meta = w.openProjectV1(p.text);
  } catch (e) {
    throw new ProjectError(errorText(e));
  }
  // Opened: record it as one undo step like any other.
  const settings = { ...d.settings }, scene = d.session;
  d.session = null;
  d.newModel();
  takeUi(d, meta.name, meta.ui);
  if (undoable) d.history.push(`open ${label ?? meta.name}`, { delta: w.delta('all'), settings, scene });
  d.touched();
  d.hooks.changed();
}

/** Undo steps from an autosave (taken with its snapshot): well-formed ones only. Returns how many. */
function takeHistory(d: DocState, h: AutosaveRecord['history']): number {
  if (!h) return 0;
  const ok = (i: { label: string; state: unknown }) => typeof i.label === 'string' && i.state !== null && typeof i.state === 'object' &&
    (i.state as Entry).delta instanceof Uint8Array && typeof (i.state as Entry).settings === 'object';
  if (!h.undo.every(ok) || !h.redo.every(ok)) return 0;
  d.history.load(h.undo as { label: string; state: Entry }[], h.redo as { label: string; state: Entry }[]);
  return d.history.sizes[0];
}

/** A version-2 project: its snapshot must restore, or nothing changes and this throws why. */
function openRecordOrThrow(d: DocState, p: ProjectRecord, undoable: boolean, label?: string): void {
  // Check the snapshot in a scratch world first, so a bad file says exactly what is wrong.
  const scratch = World.create();
  try { scratch.restore(p.snapshot); } catch (e) { throw new ProjectError(`the project's model: ${errorText(e)}`); } finally { scratch.free(); }
  openRecord(d, p, undoable, label);
}

function openRecord(d: DocState, r: ProjectRecord, undoable: boolean, label?: string): void {
  const ok = edit(d, `open ${label ?? r.name}`, undoable, () => {
    fresh(d);
    d.world.restore(r.snapshot);
    takeUi(d, r.name, r.ui);
  });
  if (!ok) throw new ProjectError('it was not opened');
}

/** A project's settings and page state, each taken only if it is well formed; the page is told its part. */
function takeUi(d: DocState, name: string, ui: Record<string, unknown>): void {
  const u = ui as Partial<Settings & UiState>;
  d.settings.dt = d.world.params(0).dt as number;
  if (typeof u.substeps === 'number' && u.substeps >= 1) d.settings.substeps = u.substeps;
  if (typeof u.playing === 'boolean') d.settings.playing = u.playing;
  if (typeof u.realTime === 'boolean') d.settings.realTime = u.realTime;
  if (typeof u.keepTension === 'boolean') d.settings.keepTension = u.keepTension;
  d.settings.model = name;
  d.settings.frame = validFrame(u.frame);
  const page: Partial<UiState> = {};
  if (u.brush && typeof u.brush.radius === 'number') page.brush = { radius: u.brush.radius };
  if (typeof u.tool === 'string') page.tool = u.tool;
  if (u.strengths && typeof u.strengths === 'object') page.strengths = u.strengths;
  if (Array.isArray(u.symmetry) && u.symmetry.length === 3 && u.symmetry.every((a) => typeof a === 'boolean')) page.symmetry = u.symmetry;
  if (typeof u.material === 'string') page.material = u.material;
  d.ui = { ...d.ui, ...page };
  d.hooks.ui(page);
}

/** An import frame from a project file, if it is one. */
function validFrame(f: unknown): ImportFrame | null {
  const x = f as ImportFrame | null | undefined;
  if (!x || (x.up !== 'y' && x.up !== 'z') || !Array.isArray(x.offset) || x.offset.length !== 3 || !x.offset.every(Number.isFinite)) return null;
  return { up: x.up, offset: [x.offset[0], x.offset[1], x.offset[2]], ...(typeof x.format === 'string' ? { format: x.format } : {}), ...(typeof x.file === 'string' ? { file: x.file } : {}) };
}
