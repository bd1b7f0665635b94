// Project files: the whole world as a snapshot (docs/snapshot.md), with the project's name and
// the page's state, as JSON text:
//   {"format": "softsculpt-project", "version": 2, "name": "…", "ui": {…}, "snapshot": "<base64>"}
// Version 1 files (a body's arrays as JSON, written by earlier modelers) still open: the engine
// migrates them (`World.openProjectV1`). Anything else is refused with one message naming what
// is wrong.

export const PROJECT_FORMAT = 'softsculpt-project';
export const PROJECT_VERSION = 2;

export interface Project {
  name: string;
  ui: Record<string, unknown>;
  /** The world's snapshot bytes. */
  snapshot: Uint8Array;
}

/** A parsed project file: version 2 as it is, version 1 as its text (the engine reads it). */
export type ParsedProject = ({ version: 2 } & Project) | { version: 1; text: string };

export class ProjectError extends Error {}

/** Base64 of bytes, in chunks (a snapshot can be tens of MB). */
export function toBase64(bytes: Uint8Array): string {
  const parts: string[] = [];
  for (let i = 0; i < bytes.length; i += 0x8000) parts.push(String.fromCharCode(...bytes.subarray(i, i + 0x8000)));
  return btoa(parts.join(''));
}

export function fromBase64(text: string): Uint8Array {
  const s = atob(text);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
  return out;
}

/** Project file text. */
export function serialize(p: Project): string {
  return JSON.stringify({ format: PROJECT_FORMAT, version: PROJECT_VERSION, name: p.name, ui: p.ui, snapshot: toBase64(p.snapshot) });
}

/** Read a project file; throws a ProjectError saying what is wrong (the engine checks the snapshot itself). */
export function parse(text: string): ParsedProject {
  if (text.trim() === '') throw new ProjectError('the project file is empty');
  let j: any;
  try {
    j = JSON.parse(text);
  } catch (e) {
    const why = e instanceof Error ? e.message : '';
    if (/end of (JSON )?input|Unterminated|Unexpected end/i.test(why)) throw new ProjectError('the project file is truncated (its JSON ends early)');
    throw new ProjectError('not a SoftSculpt project (not JSON)');
  }
  if (!j || typeof j !== 'object' || j.format !== PROJECT_FORMAT) throw new ProjectError('not a SoftSculpt project (no "format": "softsculpt-project")');
  const v = j.version;
  if (!Number.isInteger(v) || v < 1) throw new ProjectError('the project has no valid "version"');
  if (v > PROJECT_VERSION) throw new ProjectError(`project version ${v} is newer than this modeler reads (≤ ${PROJECT_VERSION}); update SoftSculpt to open it`);
  if (v === 1) return { version: 1, text };
  if (typeof j.snapshot !== 'string' || j.snapshot === '') throw new ProjectError('the project has no "snapshot" (the model)');
  let snapshot: Uint8Array;
  try {
    snapshot = fromBase64(j.snapshot);
  } catch {
    throw new ProjectError('the project\'s "snapshot" is not valid base64 (the file is corrupted)');
  }
  return {
    version: 2,
    name: typeof j.name === 'string' ? j.name : 'project',
    ui: typeof j.ui === 'object' && j.ui ? j.ui : {},
    snapshot,
  };
}

/** A file name's base for downloads: 'bunny.obj' → 'bunny', 'x.softsculpt.json' → 'x'. */
export function baseName(name: string): string {
  return name.replace(/\.[^.]*$/, '').replace(/\.softsculpt$/, '') || 'softsculpt';
}
