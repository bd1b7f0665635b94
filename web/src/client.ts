// The page's end of the simulation worker: starts it (a module worker bundled by Vite), sends
// commands, hands replies on, and notices when it fails. A worker that dies (an uncaught error,
// a crash) is replaced by a new one that opens the last autosave; the page says so plainly.

import type { Command, Reply } from './protocol';
import { interrupts } from './protocol';

export interface ClientEvents {
  reply(r: Reply): void;
  /** The worker failed and is being restarted from the autosave (or cannot be: `final`). */
  failed(text: string, final: boolean): void;
}

/** Restarts allowed within a minute before giving up (a worker that dies at once, every time). */
const MAX_RESTARTS = 3;

export class SimulationClient {
  private worker: Worker | null = null;
  private restarts: number[] = [];
  /** Interrupting commands sent [0] and taken by the worker [1] (`interrupts` in protocol.ts); null where memory cannot be shared (not cross-origin isolated). */
  private counters: Int32Array | null = null;

  constructor(private readonly wasmUrl: string, private readonly events: ClientEvents) {}

  /** Start the worker; `restore`: open the autosave if there is one. */
  start(restore = true): void {
    const w = new Worker(new URL('./worker/main.ts', import.meta.url), { type: 'module', name: 'softsculpt-simulation' });
    w.onmessage = (ev: MessageEvent<Reply>) => { if (w === this.worker) this.events.reply(ev.data); };
    w.onerror = (ev: ErrorEvent) => {
      ev.preventDefault();
      if (w === this.worker) this.restart(`the simulation stopped because of an error (${ev.message || 'in its worker'})`);
    };
    // A reply that could not be read: ask for everything again rather than draw half a state.
    w.onmessageerror = () => this.send({ type: 'resync' });
    this.worker = w;
    const shared = (globalThis as { crossOriginIsolated?: boolean }).crossOriginIsolated && typeof SharedArrayBuffer !== 'undefined' ? new SharedArrayBuffer(8) : undefined;
    this.counters = shared ? new Int32Array(shared) : null;
    // `?threads=N` in the page's address: the engine on N threads (1: the one-thread build).
    const asked = Number(new URLSearchParams(globalThis.location?.search ?? '').get('threads'));
    const threads = Number.isInteger(asked) && asked >= 1 ? { threads: asked } : {};
    this.send({ type: 'init', wasmUrl: this.wasmUrl, restore, ...threads, ...(shared ? { interrupts: shared } : {}) });
  }

  send(cmd: Command, transfer: Transferable[] = []): void {
    if (!this.worker) return;
    if (this.counters && interrupts(cmd)) Atomics.add(this.counters, 0, 1);
    this.worker.postMessage(cmd, transfer);
  }

  /** Replace a failed worker by a new one that opens the last autosave. */
  restart(reason: string): void {
    this.worker?.terminate();
    this.worker = null;
    const now = performance.now();
    this.restarts = this.restarts.filter((t) => now - t < 60_000);
    if (this.restarts.length >= MAX_RESTARTS) {
      this.events.failed(`${reason}. It failed again after restarting; please reload the page.`, true);
      return;
    }
    this.restarts.push(now);
    this.events.failed(`${reason}. Restarting it from your last autosave…`, false);
    this.start(true);
  }
}
