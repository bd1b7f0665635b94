// The threaded engine (public/softsculpt-threads.wasm) on 1 and 2+ threads, alternated in one
// process (V8, the engine Chromium runs; helpers on Node's worker_threads as the page starts
// them on Web Workers, src/engine/threads.ts): ms per implicit step of the issue-9 workload
// (backward Euler at dt = 1/60 s, k = 1000 N/m, the table's tolerance) and per explicit step of
// the standard workload, best of `reps`, and the speed-up; beside them the one-thread build
// (public/softsculpt.wasm, what the page runs when it is not cross-origin isolated).
//   node bench/threads.mjs [levels=5,6] [threads=2] [reps=3]      (from web/, after `make web`)
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { Worker } from 'node:worker_threads';

const levels = (process.argv[2] ?? '5,6').split(',').map(Number);
const most = Number(process.argv[3] ?? 2);
const reps = Number(process.argv[4] ?? 3);
const module = new WebAssembly.Module(readFileSync(fileURLToPath(new URL('../public/softsculpt-threads.wasm', import.meta.url))));
const memory = new WebAssembly.Memory({ initial: 256, maximum: 65536, shared: true });
const env = { memory, ss_now: () => performance.now(), ss_interrupted: () => 0 };
const e = new WebAssembly.Instance(module, { env }).exports;
const plain = new WebAssembly.Instance(new WebAssembly.Module(readFileSync(fileURLToPath(new URL('../public/softsculpt.wasm', import.meta.url)))), { env: { ss_now: env.ss_now, ss_interrupted: env.ss_interrupted } }).exports;

// Helpers as in src/engine/threads.ts and src/engine/helper.ts.
const HELPER = `
const { parentPort, workerData } = require('node:worker_threads');
const { module, memory, stackTop, tls } = workerData;
const e = new WebAssembly.Instance(module, { env: { memory, ss_now: () => performance.now(), ss_interrupted: () => 0 } }).exports;
e.__stack_pointer.value = stackTop;
e.__wasm_init_tls(tls);
parentPort.postMessage('ready');
e.ss_thread_serve();`;
const ready = [];
for (let i = 1; i < most; i++) {
  const stack = e.ss_alloc(1 << 20) >>> 0, tls = e.ss_alloc(e.__tls_size.value + 16) >>> 0;
  const w = new Worker(HELPER, { eval: true, workerData: { module, memory, stackTop: stack + (1 << 20) - ((stack + (1 << 20)) % 16), tls: Math.ceil(tls / 16) * 16 } });
  w.unref();
  ready.push(new Promise((r) => w.once('message', r)));
}
await Promise.all(ready);
const useThreads = async (n) => {
  for (let k = 0; k < 200; k++) {
    if (e.ss_use_threads(n) === n) return;
    await new Promise((r) => setTimeout(r, 5));
  }
  throw new Error(`cannot use ${n} threads`);
};
const setParam = (e, w, id, value) => {
  const mem = e.memory ?? memory;
  const put = (s) => { const b = new TextEncoder().encode(s), p = e.ss_alloc(b.length); new Uint8Array(mem.buffer, p, b.length).set(b); return [p, b.length]; };
  const [ip, il] = put(id), [jp, jl] = put(JSON.stringify(value));
  if (e.ss_set_param(w, 0, ip, il, jp, jl) !== 0) throw new Error(`set ${id}`);
};
const time = (e, level, implicit) => {
  const w = e.ss_workload(level);
  if (implicit) { setParam(e, w, 'integrator', 'implicit'); setParam(e, w, 'dt', 1 / 60); setParam(e, w, 'stiffness', 1000); }
  const steps = implicit ? 4 : 200;
  if (e.ss_step(w, implicit ? 1 : 20) !== 0) throw new Error('step');
  const t0 = performance.now();
  if (e.ss_step(w, steps) !== 0) throw new Error('step');
  const ms = (performance.now() - t0) / steps;
  e.ss_world_free(w);
  return ms;
};
console.log('workload        vertices  one-thread build ms  1 thread ms  ' + `${most} threads ms  speed-up`);
for (const implicit of [true, false]) {
  for (const level of levels) {
    const best = { 1: Infinity, [most]: Infinity, plain: Infinity };
    for (let r = 0; r < reps; r++) {
      best.plain = Math.min(best.plain, time(plain, level, implicit));
      for (const n of [1, most]) {
        await useThreads(n);
        best[n] = Math.min(best[n], time(e, level, implicit));
      }
    }
    const nv = 10 * 4 ** level + 2;
    console.log(`${implicit ? 'implicit 1/60 s' : 'explicit 1e-4 s'}  ${String(nv).padStart(8)}  ${best.plain.toFixed(3).padStart(19)}  ${best[1].toFixed(3).padStart(11)}  ${best[most].toFixed(3).padStart(12)}  ${(best[1] / best[most]).toFixed(2).padStart(8)}`);
  }
}
process.exit(0);
