// One helper thread of the threaded engine (./threads.ts): a Web Worker that instantiates the
// engine's module on the page's shared memory, moves its stack pointer to the stack allocated
// for it and sets up its thread-local block, says `ready`, and then serves the core's team of
// threads for as long as the page lives (`ss_thread_serve` never returns; it waits on the
// memory, burning no CPU, while no pass runs). If it traps (a panic in a pass), the helper sets
// the engine's trap flag in the shared memory, so the pass waiting for it fails (the engine's
// call throws, the page restarts the simulation from the autosave) instead of waiting forever.

import type { HelperStart } from './threads';

interface HelperExports {
  __stack_pointer: WebAssembly.Global;
  __wasm_init_tls(tls: number): void;
  ss_thread_serve(): void;
  ss_thread_trapped_flag(): number;
}

const scope = self as unknown as { onmessage: ((ev: MessageEvent<HelperStart>) => void) | null; postMessage(m: string): void };

scope.onmessage = async (ev: MessageEvent<HelperStart>) => {
  scope.onmessage = null;
  const { module, memory, stackTop, tls } = ev.data;
  let e: HelperExports;
  try {
    // The engine's imports: a helper never reads the clock or the page's commands (only the
    // first thread runs the step's control), but the module imports them.
    const env = { memory, ss_now: () => performance.now(), ss_interrupted: () => 0 };
    const instance = await WebAssembly.instantiate(module, { env });
    e = instance.exports as unknown as HelperExports;
    e.__stack_pointer.value = stackTop;
    e.__wasm_init_tls(tls);
    scope.postMessage('ready');
  } catch (err) {
    scope.postMessage(`the helper thread could not start: ${err instanceof Error ? err.message : String(err)}`);
    return;
  }
  const flag = e.ss_thread_trapped_flag() >>> 0;
  try {
    e.ss_thread_serve();
  } catch (err) {
    if (flag) Atomics.store(new Uint32Array(memory.buffer, flag, 1), 0, 1);
    throw err;
  }
};
