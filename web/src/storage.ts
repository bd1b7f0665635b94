// Autosave: the working world's snapshot with the project's name, the page's state and the
// simulation settings, in IndexedDB, written after every operation (debounced by the caller) and
// read back when the page opens. Failures (private mode, quota) are reported, never fatal.
//
// Crash-safe: two record slots and a pointer. A save writes the slot the pointer does not name
// and moves the pointer to it in one transaction, so the previous record stays whole until the
// new one is complete: a crash or a failed write mid-save loses nothing. Version-1 autosaves
// (project text under the key 'autosave', from earlier modelers) are still read.

const DB = 'softsculpt';
const STORE = 'projects';
const POINTER = 'autosave-current';
const SLOTS = ['autosave-a', 'autosave-b'] as const;
const LEGACY = 'autosave';

export interface AutosaveRecord {
  name: string;
  ui: Record<string, unknown>;
  /** World snapshot bytes (docs/snapshot.md). */
  snapshot: Uint8Array;
  savedAt: number;
  /**
   * The newest undo and redo steps (oldest first), taken with the snapshot, so a reload can
   * still undo. Each entry's state is opaque here (the document's: an engine delta, settings,
   * the open scene). Absent in older autosaves.
   */
  history?: { undo: { label: string; state: unknown }[]; redo: { label: string; state: unknown }[] };
}

/** What the autosave holds: a record, or a version-1 project's text. */
export type Autosave = { record: AutosaveRecord } | { legacyText: string };

function open(): Promise<IDBDatabase> {
  return new Promise((resolve, reject) => {
    const r = indexedDB.open(DB, 1);
    r.onupgradeneeded = () => r.result.createObjectStore(STORE);
    r.onsuccess = () => resolve(r.result);
    r.onerror = () => reject(r.error);
  });
}

function done(tx: IDBTransaction): Promise<void> {
  return new Promise((resolve, reject) => {
    tx.oncomplete = () => resolve();
    tx.onerror = () => reject(tx.error);
    tx.onabort = () => reject(tx.error ?? new Error('the autosave was not written'));
  });
}

function get(store: IDBObjectStore, key: string): Promise<unknown> {
  return new Promise((resolve, reject) => {
    const r = store.get(key);
    r.onsuccess = () => resolve(r.result);
    r.onerror = () => reject(r.error);
  });
}

/** Write the record into the free slot and point at it, in one transaction. */
export async function saveAutosave(record: AutosaveRecord): Promise<void> {
  const db = await open();
  try {
    const tx = db.transaction(STORE, 'readwrite');
    const finished = done(tx);
    const store = tx.objectStore(STORE);
    const current = await get(store, POINTER);
    const next = current === SLOTS[0] ? SLOTS[1] : SLOTS[0];
    store.put(record, next);
    store.put(next, POINTER);
    await finished;
  } finally {
    db.close();
  }
}

/** The last complete autosave, or null; throws if it is there but unreadable. */
export async function loadAutosave(): Promise<Autosave | null> {
  const db = await open();
  try {
    const store = db.transaction(STORE, 'readonly').objectStore(STORE);
    const slot = await get(store, POINTER);
    if (typeof slot === 'string') {
      const r = (await get(store, slot)) as Partial<AutosaveRecord> | undefined;
      if (!r || !(r.snapshot instanceof Uint8Array)) throw new Error('the autosave is corrupted (its record has no snapshot)');
      const history = r.history && Array.isArray(r.history.undo) && Array.isArray(r.history.redo) ? r.history : undefined;
      return { record: { name: typeof r.name === 'string' ? r.name : 'autosave', ui: r.ui && typeof r.ui === 'object' ? r.ui : {}, snapshot: r.snapshot, savedAt: Number(r.savedAt) || 0, history } };
    }
    const legacy = await get(store, LEGACY);
    return typeof legacy === 'string' ? { legacyText: legacy } : null;
  } finally {
    db.close();
  }
}

export async function clearAutosave(): Promise<void> {
  const db = await open();
  try {
    const tx = db.transaction(STORE, 'readwrite');
    const finished = done(tx);
    for (const k of [POINTER, ...SLOTS, LEGACY]) tx.objectStore(STORE).delete(k);
    await finished;
  } finally {
    db.close();
  }
}
