// The only module that touches the WebAssembly engine (crates/softsculpt-wasm). It loads the
// module, types its raw exports, and makes typed-array views over wasm memory.

export interface RawEngine {
  memory: WebAssembly.Memory;
  ss_alloc(len: number): number;
  ss_dealloc(ptr: number, len: number): void;
  ss_message_ptr(): number;
  ss_message_len(): number;
  ss_create_builtin(name: number, len: number, mass: number): number;
  ss_create_obj(ptr: number, len: number, mass: number): number;
  ss_create_mesh(pos: number, nVertices: number, idx: number, nIndices: number, mass: number, weld: number): number;
  ss_free(h: number): void;
  ss_vertex_count(h: number): number;
  ss_face_count(h: number): number;
  ss_spring_count(h: number): number;
  ss_sync(h: number): number;
  ss_render_positions(h: number): number;
  ss_triangles(h: number): number;
  ss_springs(h: number): number;
  ss_positions(h: number): number;
  ss_velocities(h: number): number;
  ss_masses(h: number): number;
  ss_rest_lengths(h: number): number;
  ss_frozen_positions(h: number): number;
  ss_bending_count(h: number): number;
  ss_bending_rest_lengths(h: number): number;
  ss_frozen_bending_rest_lengths(h: number): number;
  ss_set_bending_rest(h: number, now: number, frozen: number): number;
  ss_frozen_rest_lengths(h: number): number;
  ss_pinned(h: number): number;
  ss_user_forces(h: number): number;
  ss_face_pressures(h: number): number;
  ss_vertex_scratch(h: number): number;
  ss_vector_scratch(h: number): number;
  ss_get(h: number, id: number): number;
  ss_set(h: number, id: number, value: number): number;
  ss_step(h: number, dt: number, substeps: number): number;
  ss_stats(h: number): number;
  ss_freeze(h: number): number;
  ss_reset(h: number): number;
  ss_freeze_under_load(h: number): number;
  ss_prestress(h: number): number;
  ss_frozen_prestress(h: number): number;
  ss_set_prestress(h: number, now: number, frozen: number): number;
  ss_subdivide(h: number): number;
  ss_scale_rest(h: number, factor: number): number;
  ss_scale_rest_by_vertex(h: number): number;
  ss_set_rest_lengths(h: number, ptr: number): number;
  ss_set_masses(h: number): number;
  ss_set_pinned(h: number, vertex: number, pinned: number): number;
  ss_apply_user_forces(h: number): number;
  ss_apply_face_pressures(h: number): number;
  ss_set_state(h: number, ptr: number): number;
  ss_set_frozen(h: number, pos: number, rest: number, ambient: number, volume: number): number;
  ss_scene_add_file(name: number, nameLen: number, ptr: number, len: number): void;
  ss_scene_open(ptr: number, len: number): number;
  ss_scene_free(s: number): void;
  ss_scene_body_count(s: number): number;
  ss_scene_body(s: number, i: number): number;
  ss_scene_names(s: number): number;
  ss_scene_set_body(s: number, i: number, h: number): number;
  ss_scene_step(s: number, dt: number, substeps: number): number;
  ss_scene_time(s: number): number;
  ss_scene_duration(s: number): number;
  ss_scene_dt(s: number): number;
  ss_scene_obstacles(s: number): number;
  ss_scene_obstacles_len(s: number): number;
  ss_scene_save(s: number, hs: number, n: number, dt: number, duration: number): number;
}

let engine: RawEngine | null = null;

/** Load the engine from the wasm bytes or a URL (browser). Safe to call more than once. */
export async function initEngine(source: BufferSource | string): Promise<RawEngine> {
  if (engine) return engine;
  const bytes = typeof source === 'string' ? await (await fetch(source)).arrayBuffer() : source;
  const { instance } = await WebAssembly.instantiate(bytes, {});
  engine = instance.exports as unknown as RawEngine;
  return engine;
}

export function raw(): RawEngine {
  if (!engine) throw new Error('the engine is not loaded yet (initEngine first)');
  return engine;
}

/** Views over wasm memory; made anew on each call, so a memory growth never leaves a stale one. */
export const view = {
  f64: (ptr: number, len: number) => new Float64Array(raw().memory.buffer, ptr, len),
  f32: (ptr: number, len: number) => new Float32Array(raw().memory.buffer, ptr, len),
  u32: (ptr: number, len: number) => new Uint32Array(raw().memory.buffer, ptr, len),
  u8: (ptr: number, len: number) => new Uint8Array(raw().memory.buffer, ptr, len),
};

/** The engine's last message (an error, or a load's warnings). */
export function message(): string {
  const e = raw();
  return new TextDecoder().decode(new Uint8Array(e.memory.buffer, e.ss_message_ptr(), e.ss_message_len()));
}

/** Copy bytes into a temporary wasm buffer for the duration of `f`. */
export function withBytes<T>(bytes: Uint8Array, f: (ptr: number, len: number) => T): T {
  const e = raw();
  const ptr = e.ss_alloc(bytes.length);
  try {
    new Uint8Array(e.memory.buffer, ptr, bytes.length).set(bytes);
    return f(ptr, bytes.length);
  } finally {
    e.ss_dealloc(ptr, bytes.length);
  }
}

/** Copy typed arrays into temporary wasm buffers for the duration of `f`. */
export function withArrays<T>(arrays: (Float64Array | Uint32Array)[], f: (...ptrs: number[]) => T): T {
  const e = raw();
  const blocks = arrays.map((a) => ({ a, len: a.byteLength, ptr: e.ss_alloc(a.byteLength) }));
  try {
    for (const b of blocks) new Uint8Array(e.memory.buffer, b.ptr, b.len).set(new Uint8Array(b.a.buffer, b.a.byteOffset, b.len));
    return f(...blocks.map((b) => b.ptr));
  } finally {
    for (const b of blocks) e.ss_dealloc(b.ptr, b.len);
  }
}
