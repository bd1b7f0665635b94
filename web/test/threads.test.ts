// The engine on two threads (issue #36 item 5): the threaded build (public/softsculpt-threads.wasm,
// scripts/wasm_threads.sh) with a helper started as the page starts one (src/engine/threads.ts),
// here on Node's worker_threads instead of a Web Worker. The core's passes split their work
// into chunks of a size that does not depend on the thread count and sum reductions in chunk
// order (crates/softsculpt/src/par.rs), so the implicit solve gives the same bits on one thread
// and on two; the explicit stages on one thread take plain passes in another summation order,
// so they agree with two threads to rounding only.
import { existsSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { Worker } from 'node:worker_threads';
import { describe, expect, it } from 'vitest';
import { loadThreaded, type HelperSpawner } from '../src/engine/threads';

const path = fileURLToPath(new URL('../public/softsculpt-threads.wasm', import.meta.url));
const built = existsSync(path);

/** What src/engine/helper.ts does in a Web Worker, on a Node thread. */
const HELPER = `
const { parentPort, workerData } = require('node:worker_threads');
const { module, memory, stackTop, tls } = workerData;
const env = { memory, ss_now: () => performance.now(), ss_interrupted: () => 0 };
const e = new WebAssembly.Instance(module, { env }).exports;
e.__stack_pointer.value = stackTop;
e.__wasm_init_tls(tls);
parentPort.postMessage('ready');
e.ss_thread_serve();
`;
const nodeHelper: HelperSpawner = (start) => {
  const w = new Worker(HELPER, { eval: true, workerData: start });
  w.unref();
  return { ready: new Promise((resolve) => w.once('message', () => resolve())), stop: () => void w.terminate() };
};

interface E {
  ss_alloc(n: number): number;
  ss_dealloc(p: number, n: number): void;
  ss_workload(level: number): number;
  ss_world_free(w: number): void;
  ss_set_param(w: number, b: number, ip: number, il: number, jp: number, jl: number): number;
  ss_step(w: number, n: number): number;
  ss_body_views(w: number, b: number): number;
  ss_use_threads(n: number): number;
  ss_threads(): number;
  ss_thread_passes(): number;
}

describe.skipIf(!built)('the threaded engine', () => {
  it('steps the implicit solve to the same bits on one thread and on two, with the helper taking part', async () => {
    const env = { ss_now: () => performance.now(), ss_interrupted: () => 0 };
    const t = await loadThreaded(readFileSync(path), 2, { env }, nodeHelper);
    expect(t, 'the threaded build started with one helper').not.toBeNull();
    const e = t!.instance.exports as unknown as E;
    const memory = t!.memory;
    expect(e.ss_threads()).toBe(2);
    const setParam = (w: number, id: string, value: unknown) => {
      const put = (s: string): [number, number] => {
        const b = new TextEncoder().encode(s), p = e.ss_alloc(b.length);
        new Uint8Array(memory.buffer, p, b.length).set(b);
        return [p, b.length];
      };
      const [ip, il] = put(id), [jp, jl] = put(JSON.stringify(value));
      expect(e.ss_set_param(w, 0, ip, il, jp, jl)).toBe(0);
    };
    /** The standard workload at 10,242 vertices (three chunks of 4,096), `steps` steps, on `threads`. */
    const run = (threads: number, implicit: boolean, steps: number): Float64Array => {
      expect(e.ss_use_threads(threads)).toBe(threads);
      const w = e.ss_workload(5);
      if (implicit) {
        setParam(w, 'integrator', 'implicit');
        setParam(w, 'dt', 1 / 60);
        setParam(w, 'stiffness', 1000);
      }
      expect(e.ss_step(w, steps)).toBe(0);
      const layout = new Uint32Array(memory.buffer, e.ss_body_views(w, 0), 17).slice();
      const x = new Float64Array(memory.buffer, layout[4], 3 * layout[0]).slice();
      e.ss_world_free(w);
      return x;
    };
    const helped = e.ss_thread_passes();
    const one = run(1, true, 3);
    expect(e.ss_thread_passes()).toBe(helped); // one thread: the helper idles
    const two = run(2, true, 3);
    expect(two.length).toBe(3 * 10242);
    expect(Array.from(two)).toEqual(Array.from(one));
    // The implicit solve ran on the pool (a pass a worker joined, at least one per step).
    expect(e.ss_thread_passes()).toBeGreaterThan(helped);

    // Explicit: the standard workload's 200 steps of 1e-4 s. One thread sums each vertex's
    // springs in another order, so the two differ by rounding, growing over the steps: bounded
    // here by 1e-9 m against positions of ~1 m (200 steps × a few ulps of 2e-16 m per step,
    // with margin for the amplification of a stiff mass-spring system over 0.02 s).
    const a = run(1, false, 200), b = run(2, false, 200);
    let worst = 0;
    for (let i = 0; i < a.length; i++) worst = Math.max(worst, Math.abs(a[i] - b[i]));
    expect(worst).toBeLessThan(1e-9);
    expect(e.ss_use_threads(1)).toBe(1);
  }, 120_000);
});
