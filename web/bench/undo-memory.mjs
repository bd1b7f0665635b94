// Undo memory of brush strokes: 100 inflate strokes on the 163,842-vertex icosphere (the
// standard workload at level 7), each recorded as the modeler records it — `ss_mark` at the
// stroke's start, `ss_delta(touched)` at its end — while the world steps between brush ticks.
// Prints the sum of the deltas' bytes (what the undo history holds) and how much wasm memory
// grew over the strokes (the mark and the result slot), and checks that undoing every stroke
// in reverse gives back the first rest lengths exactly.
//   node bench/undo-memory.mjs [strokes=100] [level=7]
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const strokes = Number(process.argv[2] ?? 100);
const level = Number(process.argv[3] ?? 7);
const wasm = readFileSync(fileURLToPath(new URL('../public/softsculpt.wasm', import.meta.url)));
const { instance } = await WebAssembly.instantiate(wasm, { env: { ss_now: () => performance.now(), ss_interrupted: () => 0 } });
const e = instance.exports;
const ok = (r) => {
  if (r < 0) throw new Error(new TextDecoder().decode(new Uint8Array(e.memory.buffer, e.ss_error_ptr(), e.ss_error_len())));
  return r;
};
const result = () => new Uint8Array(e.memory.buffer, e.ss_result_ptr(), e.ss_result_len()).slice();
const layout = (w) => new Uint32Array(e.memory.buffer, ok(e.ss_body_views(w, 0)), 17).slice();

const w = ok(e.ss_workload(level));
let L = layout(w);
const n = L[0], springs = L[2];
const rest0 = new Float64Array(e.memory.buffer, L[11], springs).slice();
const MB = 1024 * 1024;
const memBefore = e.memory.buffer.byteLength;

// Brush: radius 0.35 m on the unit sphere (about 3% of the vertices), a new centre per stroke.
let seed = 12345;
const random = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
const ticks = 6, stepsPerTick = 2, rate = 0.01; // rest lengths × (1 + rate) per tick under the brush centre
const deltas = [];
let bytes = 0;
const t0 = performance.now();
for (let s = 0; s < strokes; s++) {
  const z = 2 * random() - 1, phi = 2 * Math.PI * random(), r = Math.sqrt(1 - z * z);
  const c = [r * Math.cos(phi), r * Math.sin(phi), z];
  ok(e.ss_mark(w));
  for (let t = 0; t < ticks; t++) {
    L = layout(w);
    const x = new Float64Array(e.memory.buffer, L[4], 3 * n);
    const f = new Float64Array(e.memory.buffer, L[15], n);
    for (let i = 0; i < n; i++) {
      const d = Math.hypot(x[3 * i] - c[0], x[3 * i + 1] - c[1], x[3 * i + 2] - c[2]);
      f[i] = d < 0.35 ? 1 + rate * (1 - d / 0.35) : 1;
    }
    ok(e.ss_scale_rest(w, 0));
    ok(e.ss_step(w, stepsPerTick));
  }
  ok(e.ss_delta(w, 1));
  const d = result();
  deltas.push(d);
  bytes += d.length;
}
const ms = performance.now() - t0;
const memAfter = e.memory.buffer.byteLength;
// Undo every stroke, newest first: the rest lengths come back bit for bit.
for (const d of deltas.reverse()) {
  const p = e.ss_alloc(d.length);
  new Uint8Array(e.memory.buffer, p, d.length).set(d);
  ok(e.ss_apply_delta(w, p, d.length));
  e.ss_dealloc(p, d.length);
}
L = layout(w);
const rest = new Float64Array(e.memory.buffer, L[11], springs);
const same = rest.every((v, k) => Object.is(v, rest0[k]));
console.log(JSON.stringify({
  vertices: n,
  strokes,
  delta_bytes_total_mb: +(bytes / MB).toFixed(2),
  delta_bytes_mean_kb: +(bytes / strokes / 1024).toFixed(1),
  wasm_memory_before_mb: +(memBefore / MB).toFixed(1),
  wasm_memory_growth_mb: +((memAfter - memBefore) / MB).toFixed(1),
  undo_all_restores_rest_lengths: same,
  seconds: +(ms / 1000).toFixed(1),
}));
if (!same) process.exit(1);
