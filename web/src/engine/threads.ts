// The engine on more than one core (issue #36 item 5): the threaded build
// (`softsculpt-threads.wasm`, scripts/wasm_threads.sh: atomics, bulk memory, its memory imported
// and shared) instantiated on a shared WebAssembly.Memory, plus helper Web Workers
// (./helper.ts) that instantiate the same module on the same memory, each with a stack and a
// thread-local block of its own, and serve the core's team of threads
// (crates/softsculpt/src/par/host.rs). Used only where memory can be shared (the page
// cross-origin isolated: COOP + COEP, vite.config.ts); otherwise, or if anything here fails,
// the page runs the one-thread build and says nothing (the results are the same bits).

/** Pages of 64 KiB: the shared memory's start and most (4 GiB, wasm32's whole address space; the
 * build's `--max-memory` must match). */
const INITIAL_PAGES = 256;
const MAXIMUM_PAGES = 65536;
/** Each helper's stack (the build's default stack for the first thread is 1 MiB too). */
const STACK_BYTES = 1 << 20;
/** How long the helpers may take to start before the page runs on one thread. */
const START_MS = 10_000;

/** The exports the helpers need beyond the engine's calls. */
interface ThreadExports {
  memory?: WebAssembly.Memory;
  __tls_size: WebAssembly.Global;
  __tls_align: WebAssembly.Global;
  ss_alloc(len: number): number;
  ss_use_threads(n: number): number;
}

/** What a helper is sent: the module, the memory, its stack's top and its thread-local block. */
export interface HelperStart {
  module: WebAssembly.Module;
  memory: WebAssembly.Memory;
  stackTop: number;
  tls: number;
}

/** Whether this context can share wasm memory with workers (a browser: when cross-origin isolated; Node: always). */
export function canShareMemory(): boolean {
  return (globalThis as { crossOriginIsolated?: boolean }).crossOriginIsolated !== false && typeof SharedArrayBuffer !== 'undefined';
}

/** Threads worth asking for here: the cores the browser reports, at most 4 (the passes' chunks
 * of ~4,096 vertices leave little for more at the modeler's sizes). */
export function threadsWanted(): number {
  return Math.max(1, Math.min(4, (globalThis.navigator?.hardwareConcurrency ?? 1)));
}

/** Start helper `i` on `start` (a Web Worker running ./helper.ts; tests pass Node's threads):
 * `ready` resolves once it serves, `stop` ends it (when another helper failed). */
export type HelperSpawner = (start: HelperStart, i: number) => { ready: Promise<void>; stop(): void };

/**
 * Instantiate the threaded build (its bytes or URL) with `threads` threads (the caller and
 * threads − 1 helpers). Returns the instance, its memory and the count in use, or null (then
 * the caller loads the one-thread build): no shared memory, the file missing, a helper that
 * failed to start.
 */
export async function loadThreaded(
  source: BufferSource | string,
  threads: number,
  imports: { env: Record<string, unknown> },
  spawn: HelperSpawner = webHelper,
): Promise<{ instance: WebAssembly.Instance; memory: WebAssembly.Memory; threads: number } | null> {
  if (threads <= 1 || !canShareMemory()) return null;
  let module: WebAssembly.Module;
  try {
    let bytes: BufferSource;
    if (typeof source === 'string') {
      const res = await fetch(source);
      if (!res.ok) return null;
      bytes = await res.arrayBuffer();
    } else bytes = source;
    module = await WebAssembly.compile(bytes);
  } catch {
    return null;
  }
  const memory = new WebAssembly.Memory({ initial: INITIAL_PAGES, maximum: MAXIMUM_PAGES, shared: true });
  const instance = await WebAssembly.instantiate(module, { env: { ...imports.env, memory } });
  const e = instance.exports as unknown as ThreadExports;
  const helpers: ReturnType<HelperSpawner>[] = [];
  const stop = (why: string) => {
    for (const h of helpers) h.stop();
    console.warn(`SoftSculpt: the engine runs on one thread (${why})`);
    return null;
  };
  let timer: ReturnType<typeof setTimeout> | undefined;
  try {
    for (let i = 1; i < threads; i++) helpers.push(spawn(helperStart(module, memory, e), i));
    await Promise.race([Promise.all(helpers.map((h) => h.ready)), new Promise((_, fail) => { timer = setTimeout(() => fail(new Error(`no helper thread started within ${START_MS / 1000} s`)), START_MS); })]);
    // A helper counts once it waits for work (just after its `ready`): ask until all of them do.
    for (let tries = 0; tries < 200; tries++) {
      const n = e.ss_use_threads(threads);
      if (n === threads) return { instance, memory, threads };
      await new Promise((r) => setTimeout(r, 5));
    }
    return stop('the helper threads did not start serving');
  } catch (err) {
    return stop(err instanceof Error ? err.message : String(err));
  } finally {
    clearTimeout(timer);
  }
}

/** A helper's stack and thread-local block, allocated in the shared memory. */
function helperStart(module: WebAssembly.Module, memory: WebAssembly.Memory, e: ThreadExports): HelperStart {
  const tlsSize = e.__tls_size.value as number;
  const tlsAlign = Math.max(16, e.__tls_align.value as number);
  const stack = e.ss_alloc(STACK_BYTES) >>> 0;
  const tlsRaw = e.ss_alloc(tlsSize + tlsAlign) >>> 0;
  // The stack grows down from its top, 16-byte aligned as the C ABI wants.
  const stackTop = (stack + STACK_BYTES) - ((stack + STACK_BYTES) % 16);
  const tls = Math.ceil(tlsRaw / tlsAlign) * tlsAlign;
  return { module, memory, stackTop, tls };
}

/** A helper as a Web Worker (./helper.ts). */
function webHelper(start: HelperStart, i: number): ReturnType<HelperSpawner> {
  const worker = new Worker(new URL('./helper.ts', import.meta.url), { type: 'module', name: `softsculpt-helper-${i}` });
  const ready = new Promise<void>((resolve, reject) => {
    worker.onmessage = (ev: MessageEvent<string>) => (ev.data === 'ready' ? resolve() : reject(new Error(String(ev.data))));
    worker.onerror = (ev) => { ev.preventDefault(); reject(new Error(ev.message)); };
    worker.postMessage(start);
  });
  return { ready, stop: () => worker.terminate() };
}
