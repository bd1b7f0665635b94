// The standard workload in WebAssembly (Node's V8, the engine Chromium runs), next to the native
// `softsculpt bench`, in one run: prints ms per step for both and the ratio.
//   node bench/wasm-bench.mjs [levels=4,5,6] [steps=300] [implicit[:TOL]]
// `implicit`: the issue-9 workload instead — backward Euler at dt = 1/60 s, k = 1000 N/m
// (tolerance TOL, default the parameter table's), native on one thread.
import { readFileSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const levels = (process.argv[2] ?? '4,5,6').split(',').map(Number);
const steps = Number(process.argv[3] ?? 300);
const [mode, tolText] = (process.argv[4] ?? 'explicit').split(':');
const implicit = mode === 'implicit';
const wasm = readFileSync(fileURLToPath(new URL('../public/softsculpt.wasm', import.meta.url)));
const { instance } = await WebAssembly.instantiate(wasm, { env: { ss_now: () => performance.now(), ss_interrupted: () => 0 } });
const e = instance.exports;
const native = fileURLToPath(new URL('../../target/release/softsculpt', import.meta.url));
const fail = () => {
  const m = e.memory.buffer;
  throw new Error(new TextDecoder().decode(new Uint8Array(m, e.ss_error_ptr(), e.ss_error_len())));
};
/** `ss_set_param` on body 0 with a JSON value. */
const setParam = (w, id, value) => {
  const put = (s) => {
    const b = new TextEncoder().encode(s), p = e.ss_alloc(b.length);
    new Uint8Array(e.memory.buffer, p, b.length).set(b);
    return [p, b.length];
  };
  const [ip, il] = put(id), [jp, jl] = put(JSON.stringify(value));
  const r = e.ss_set_param(w, 0, ip, il, jp, jl);
  e.ss_dealloc(ip, il);
  e.ss_dealloc(jp, jl);
  if (r !== 0) fail();
};
const DT = 1 / 60;

console.log(`${implicit ? `implicit dt=1/60 s k=1000 N/m tolerance=${tolText ?? 'default'}` : 'explicit standard workload'}`);
console.log('vertices  wasm ms/step  native ms/step  wasm/native');
for (const level of levels) {
  let best = Infinity, nv = 0;
  for (let rep = 0; rep < 3; rep++) {
    const w = e.ss_workload(level); // a world handle: the workload's one-body world (dt 1e-4 s)
    if (w < 0) fail();
    if (implicit) {
      setParam(w, 'integrator', 'implicit');
      setParam(w, 'dt', DT);
      setParam(w, 'stiffness', 1000);
      if (tolText) setParam(w, 'tolerance', Number(tolText));
    }
    nv = new Uint32Array(e.memory.buffer, e.ss_body_views(w, 0), 1)[0];
    if (e.ss_step(w, implicit ? 2 : 10) !== 0) fail(); // warm up
    const t0 = performance.now();
    if (e.ss_step(w, steps) !== 0) fail();
    best = Math.min(best, (performance.now() - t0) / steps);
    e.ss_world_free(w);
  }
  const extra = implicit ? ['--integrator', 'implicit', '--dt', String(DT), '--stiffness', '1000', '--threads', '1', ...(tolText ? ['--tolerance', tolText] : [])] : [];
  const out = execFileSync(native, ['bench', '--levels', String(level), '--steps', String(steps), '--reps', '3', '--json', ...extra]).toString();
  const nat = JSON.parse(out.trim().split('\n').pop()).ms_per_step;
  console.log(`${String(nv).padStart(8)}  ${best.toFixed(4).padStart(12)}  ${nat.toFixed(4).padStart(14)}  ${(best / nat).toFixed(2).padStart(11)}`);
}
