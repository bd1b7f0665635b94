// The simulation worker's entry (a module worker, started by src/client.ts): the service over
// the document, fed by the page's messages, ticking on its own clock, autosaving in IndexedDB.

import type { Command, Reply } from '../protocol';
import { Service } from './service';
import { loadAutosave, saveAutosave } from '../storage';
import { settleInterrupts } from '../engine/wasm';

/** The worker's global scope, as far as it is used here. */
const scope = self as unknown as {
  postMessage(message: Reply, transfer: Transferable[]): void;
  onmessage: ((ev: MessageEvent<Command>) => void) | null;
  onmessageerror: (() => void) | null;
};

const service = new Service({
  post: (r: Reply, transfer: Transferable[]) => scope.postMessage(r, transfer),
  now: () => performance.now(),
  storage: { load: loadAutosave, save: saveAutosave },
  later: (f, ms) => setTimeout(f, ms),
  cancel: (t) => clearTimeout(t as ReturnType<typeof setTimeout>),
});

scope.onmessage = (ev: MessageEvent<Command>) => { void service.handle(ev.data); };
scope.onmessageerror = () => { settleInterrupts(); service.message('a command to the simulation was lost (it could not be read); please try again', 'error'); };

// About 60 ticks a second; a tick that takes longer (slow motion) is followed at once by the next.
const FRAME_MS = 16;
function loop(): void {
  const t0 = performance.now();
  service.tick();
  setTimeout(loop, Math.max(0, FRAME_MS - (performance.now() - t0)));
}
loop();
