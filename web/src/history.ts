// Undo/redo: two stacks of entries. An entry holds what is needed to go back over one operation;
// applying it yields the entry that goes forward again (and vice versa).
//
// Limits: at most `limit` undo entries, and at most `maxBytes` in both stacks together (as
// `size` measures an entry): the oldest undo entries go first, so one huge body cannot exhaust
// memory; the newest entry is always kept.

export interface Item<S> {
  label: string;
  state: S;
}

export interface HistoryLimits<S> {
  /** Undo entries kept at most. */
  limit?: number;
  /** Bytes kept at most over both stacks, measured by `size`. */
  maxBytes?: number;
  size?: (s: S) => number;
}

export class History<S> {
  private undoStack: Item<S>[] = [];
  private redoStack: Item<S>[] = [];
  private readonly limit: number;
  private readonly maxBytes: number;
  private readonly size: (s: S) => number;
  /** Bytes held by both stacks (as `size` measures them). */
  bytes = 0;

  constructor(limits: number | HistoryLimits<S> = 50) {
    const l = typeof limits === 'number' ? { limit: limits } : limits;
    this.limit = l.limit ?? 50;
    this.maxBytes = l.maxBytes ?? Infinity;
    this.size = l.size ?? (() => 0);
  }

  /** Record the entry that undoes a new operation. Clears redo. */
  push(label: string, before: S): void {
    for (const r of this.redoStack) this.bytes -= this.size(r.state);
    this.redoStack = [];
    this.putUndo({ label, state: before });
  }

  takeUndo(): Item<S> | null { return this.take(this.undoStack); }
  takeRedo(): Item<S> | null { return this.take(this.redoStack); }

  private take(stack: Item<S>[]): Item<S> | null {
    const item = stack.pop() ?? null;
    if (item) this.bytes -= this.size(item.state);
    return item;
  }

  putUndo(item: Item<S>): void {
    this.undoStack.push(item);
    this.bytes += this.size(item.state);
    this.trim();
  }
  putRedo(item: Item<S>): void {
    this.redoStack.push(item);
    this.bytes += this.size(item.state);
    this.trim();
  }

  /** Drop the oldest undo entries while over a limit (keeping the newest entry). */
  private trim(): void {
    while (this.undoStack.length > this.limit || (this.bytes > this.maxBytes && this.undoStack.length > 1)) {
      const old = this.undoStack.shift()!;
      this.bytes -= this.size(old.state);
    }
  }

  get canUndo(): boolean { return this.undoStack.length > 0; }
  get canRedo(): boolean { return this.redoStack.length > 0; }
  get undoLabel(): string | undefined { return this.undoStack.at(-1)?.label; }
  get redoLabel(): string | undefined { return this.redoStack.at(-1)?.label; }
  get sizes(): [number, number] { return [this.undoStack.length, this.redoStack.length]; }
  clear(): void { this.undoStack = []; this.redoStack = []; this.bytes = 0; }

  /**
   * The newest entries of both stacks (oldest first in each) that fit in `maxBytes` together,
   * the undo stack's first: what is kept across a reload.
   */
  newest(maxBytes: number): { undo: Item<S>[]; redo: Item<S>[] } {
    let left = maxBytes;
    const pick = (stack: Item<S>[]) => {
      const out: Item<S>[] = [];
      for (let i = stack.length - 1; i >= 0; i--) {
        const n = this.size(stack[i].state);
        if (n > left) break;
        left -= n;
        out.unshift(stack[i]);
      }
      return out;
    };
    const undo = pick(this.undoStack);
    return { undo, redo: pick(this.redoStack) };
  }

  /** Replace both stacks (entries oldest first), within the limits. */
  load(undo: Item<S>[], redo: Item<S>[]): void {
    this.clear();
    for (const r of redo) this.putRedo(r);
    for (const u of undo) this.putUndo(u);
  }
}

/** Undo (or redo) one step: `apply` performs an entry and returns its inverse. */
export function travel<S>(h: History<S>, dir: 'undo' | 'redo', apply: (s: S) => S): Item<S> | null {
  const item = dir === 'undo' ? h.takeUndo() : h.takeRedo();
  if (!item) return null;
  let inverse: Item<S>;
  try {
    inverse = { label: item.label, state: apply(item.state) };
  } catch (e) {
    // Not applied: the entry goes back where it was.
    if (dir === 'undo') h.putUndo(item); else h.putRedo(item);
    throw e;
  }
  if (dir === 'undo') h.putRedo(inverse); else h.putUndo(inverse);
  return item;
}
