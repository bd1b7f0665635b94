// Undo/redo: two stacks of entries. An entry holds what is needed to go back over one operation;
// applying it yields the entry that goes forward again (and vice versa).

export interface Item<S> {
  label: string;
  state: S;
}

export class History<S> {
  private undoStack: Item<S>[] = [];
  private redoStack: Item<S>[] = [];
  constructor(private readonly limit = 50) {}

  /** Record the entry that undoes a new operation. Clears redo. */
  push(label: string, before: S): void {
    this.putUndo({ label, state: before });
    this.redoStack = [];
  }

  takeUndo(): Item<S> | null { return this.undoStack.pop() ?? null; }
  takeRedo(): Item<S> | null { return this.redoStack.pop() ?? null; }

  putUndo(item: Item<S>): void {
    this.undoStack.push(item);
    if (this.undoStack.length > this.limit) this.undoStack.shift();
  }
  putRedo(item: Item<S>): void { this.redoStack.push(item); }

  get canUndo(): boolean { return this.undoStack.length > 0; }
  get canRedo(): boolean { return this.redoStack.length > 0; }
  get undoLabel(): string | undefined { return this.undoStack.at(-1)?.label; }
  get redoLabel(): string | undefined { return this.redoStack.at(-1)?.label; }
  get sizes(): [number, number] { return [this.undoStack.length, this.redoStack.length]; }
  clear(): void { this.undoStack = []; this.redoStack = []; }
}

/** Undo (or redo) one step: `apply` performs an entry and returns its inverse. */
export function travel<S>(h: History<S>, dir: 'undo' | 'redo', apply: (s: S) => S): Item<S> | null {
  const item = dir === 'undo' ? h.takeUndo() : h.takeRedo();
  if (!item) return null;
  const inverse = { label: item.label, state: apply(item.state) };
  if (dir === 'undo') h.putRedo(inverse); else h.putUndo(inverse);
  return item;
}
