// Issue #36 item 5, the first step: the engine built for threads (atomics, bulk memory, shared
// memory imported; `scripts/wasm_threads.sh` builds it into /tmp/wasm-mt) instantiates on a
// shared WebAssembly.Memory and steps as the one-thread build does. Threads themselves are not
// started: the core's team (`crates/softsculpt/src/par.rs`) runs one thread on wasm32, and
// std::thread cannot spawn on wasm32-unknown-unknown; a pool of Web Workers instantiating the
// same module on the same memory (each with its stack and `__wasm_init_tls`) is the next step.
//
//   node bench/threaded-build.mjs [THREADED_WASM]    (from web/, after `make wasm`)
import fs from 'node:fs';

const threaded = process.argv[2] ?? '/tmp/wasm-mt/wasm32-unknown-unknown/release/softsculpt_wasm.wasm';
async function load(path, shared) {
  const env = { ss_now: () => performance.now(), ss_interrupted: () => 0 };
  if (shared) env.memory = new WebAssembly.Memory({ initial: 1024, maximum: 16384, shared: true });
  const { instance } = await WebAssembly.instantiate(fs.readFileSync(path), { env });
  return instance.exports;
}
for (let round = 0; round < 3; round++) {
  for (const [name, path, shared] of [['one-thread build', 'public/softsculpt.wasm', false], ['threaded build, shared memory', threaded, true]]) {
    const e = await load(path, shared);
    const w = e.ss_workload(5);
    const t0 = performance.now();
    const rc = e.ss_step(w, 100);
    console.log(`${name}: status ${rc}, ${((performance.now() - t0) / 100).toFixed(3)} ms per explicit step at 10,242 vertices`);
  }
}
