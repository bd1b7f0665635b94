// One helper thread of the threaded engine (./threads.ts): a Web Worker that instantiates the
// engine's module on the page's shared memory, moves its stack pointer to the stack allocated
// for it and sets up its thread-local block, says `ready`, and then serves the core's team of
// threads for as long as the page lives (`ss_thread_serve` never returns; it waits on the
// memory, burning no CPU, while no pass runs).

import type { HelperStart } from './threads';

interface HelperExports {
  __stack_pointer: WebAssembly.Global;
  __wasm_init_tls(tls: number): void;
  ss_thread_serve(): void;
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
  e.ss_thread_serve();
};
