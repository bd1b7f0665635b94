// The page's side of the WebAssembly binding, written from its one table: do not edit. The
// raw exports' types (the `exports!` blocks of crates/softsculpt-wasm/src, abi.rs), the
// layout table's slots and the stats block's order (views.rs), the delta scope codes
// (history.rs), the JSON reports' interfaces (the `reports!` blocks, report.rs). After
// changing one of those, `UPDATE_ABI=1 cargo test -p softsculpt-wasm
// --test abi` rewrites this file (crates/softsculpt-wasm/tests/abi.rs). The calls'
// conventions (status and index, error and result slots, memory): the crate documentation
// of crates/softsculpt-wasm/src/lib.rs.

/**
 * The engine's raw exports, with wasm-level types: 32-bit integers, pointers and floats are
 * `number` (a u32 above 2^31 arrives negative: `>>> 0`), 64-bit integers `bigint`. Each
 * comment ends with the Rust signature.
 */
export interface RawEngine {
  memory: WebAssembly.Memory;
  /**
   * Allocate `len` bytes in wasm memory for the page to fill.
   *
   * `ss_alloc(len: usize) -> *mut u8`
   */
  ss_alloc(len: number): number;
  /**
   * Free memory from [`ss_alloc`].
   *
   * # Safety
   * `ptr` and `len` must come from one call of `ss_alloc`.
   *
   * `unsafe ss_dealloc(ptr: *mut u8, len: usize)`
   */
  ss_dealloc(ptr: number, len: number): void;
  /**
   * The last error, JSON (see the crate documentation).
   *
   * `ss_error_ptr() -> *const u8`
   */
  ss_error_ptr(): number;
  /** `ss_error_len() -> usize` */
  ss_error_len(): number;
  /**
   * The last result's bytes.
   *
   * `ss_result_ptr() -> *const u8`
   */
  ss_result_ptr(): number;
  /** `ss_result_len() -> usize` */
  ss_result_len(): number;
  /**
   * The material presets as JSON (`softsculpt::params::material_presets_json`: name, help) in the
   * result slot.
   *
   * `ss_material_presets() -> i32`
   */
  ss_material_presets(): number;
  /**
   * The parameter table as JSON (`softsculpt::params::table_json`) in the result slot.
   *
   * `ss_param_table() -> i32`
   */
  ss_param_table(): number;
  /**
   * An empty world with the parameter table's defaults.
   *
   * `ss_world_new() -> i32`
   */
  ss_world_new(): number;
  /** `ss_world_free(w: u32)` */
  ss_world_free(w: number): void;
  /**
   * Step every world on `n` threads: the caller and n − 1 of the helper threads the page started
   * (`ss_thread_serve`; 0: all of them). Returns the count in use; −1 (error) when the build has
   * no threads (n > 1 without atomics) or too few helpers serve. 1 goes back to one thread.
   *
   * `ss_use_threads(n: u32) -> i32`
   */
  ss_use_threads(n: number): number;
  /**
   * A helper thread's life (a Web Worker on the same module and shared memory, its stack and
   * thread-local block set up: `web/src/engine/threads.ts`): serve the pool's passes; never
   * returns. Threaded builds only; elsewhere it returns at once.
   *
   * `ss_thread_serve()`
   */
  ss_thread_serve(): void;
  /**
   * Passes a helper thread took part in so far (`softsculpt::par::passes_helped`), as f64.
   *
   * `ss_thread_passes() -> f64`
   */
  ss_thread_passes(): number;
  /**
   * The address of the flag a helper's JavaScript sets (`Atomics.store`, u32) when its
   * `ss_thread_serve` traps, so a pass waiting for it fails instead of waiting forever
   * (`softsculpt::par::host`). 0 in builds without threads.
   *
   * `ss_thread_trapped_flag() -> usize`
   */
  ss_thread_trapped_flag(): number;
  /**
   * Threads the worlds step on (1 until `ss_use_threads`).
   *
   * `ss_threads() -> u32`
   */
  ss_threads(): number;
  /**
   * The standard benchmark workload at an icosphere level (see `softsculpt::workload`).
   *
   * `ss_workload(level: u32) -> i32`
   */
  ss_workload(level: number): number;
  /**
   * A built-in model by name, of total mass `mass` (kg), with the default material.
   *
   * # Safety
   * `name` must point to `len` readable bytes.
   *
   * `unsafe ss_add_builtin(w: u32, name: *const u8, len: usize, mass: f64) -> i32`
   */
  ss_add_builtin(w: number, name: number, len: number, mass: number): number;
  /**
   * A body from OBJ bytes (welded, checked, oriented, reordered); warnings in the result.
   *
   * # Safety
   * `ptr` must point to `len` readable bytes.
   *
   * `unsafe ss_add_obj(w: u32, ptr: *const u8, len: usize, mass: f64) -> i32`
   */
  ss_add_obj(w: number, ptr: number, len: number, mass: number): number;
  /**
   * A body sketched from a closed outline of `n` points (`2 n` f64: x y, m): the pillow inflated
   * to rest (`softsculpt::sketch`); `edge` ≤ 0 takes the default edge length.
   *
   * # Safety
   * `xy` must point to `2 n` f64.
   *
   * `unsafe ss_add_sketch(w: u32, xy: *const f64, n: usize, edge: f64, mass: f64) -> i32`
   */
  ss_add_sketch(w: number, xy: number, n: number, edge: number, mass: number): number;
  /**
   * A body from an indexed triangle mesh (f64 xyz, u32 indices): `prepare` = 1 prepares it like
   * a file (weld, check, orient, reorder), 0 takes it exactly as given.
   *
   * # Safety
   * `pos` must point to `3 n_vertices` f64 and `idx` to `n_indices` u32.
   *
   * `unsafe ss_add_mesh(w: u32, pos: *const f64, n_vertices: usize, idx: *const u32, n_indices: usize, mass: f64, prepare: u32) -> i32`
   */
  ss_add_mesh(w: number, pos: number, nVertices: number, idx: number, nIndices: number, mass: number, prepare: number): number;
  /**
   * Drop every body, the events and loads, and forget the open scene (names, file); keep the
   * settings (obstacles included). The clock starts again at 0.
   *
   * `ss_clear(w: u32) -> i32`
   */
  ss_clear(w: number): number;
  /**
   * `n` steps (`World::step_n`), or none: on failure the whole world is as before the call and
   * the error (kind `step`) has `time` (s), `step`, `rolled_back_to` (s) and an event's `line`.
   *
   * `ss_step(w: u32, n: u32) -> i32`
   */
  ss_step(w: number, n: number): number;
  /**
   * `World::advance`: `frame_dt` simulated seconds; under a real-time budget of `seconds` of
   * wall-clock time (> 0; ≤ 0: converge every step) accepting a step past its deadline at a
   * relative residual of `min_accuracy` (≤ 0: the core's `MIN_ACCURACY`); a refused implicit
   * step halved up to `splits` times; `relax` 1: the relaxed retry; `rewind` 1: a failed frame
   * goes back to the last sound state (`world/rewind.rs`; the error's `rewound_to`, s). Result
   * `{"steps", "splits", "simulated", "residual", "early", "wall"}`; on failure the error is a
   * step error as `ss_step`'s (the world as after the last step taken, or rewound); under a
   * real-time budget a step is also abandoned when the page has a command waiting (cause
   * `interrupted`; never rewound).
   *
   * `ss_advance(w: u32, frame_dt: f64, seconds: f64, min_accuracy: f64, splits: u32, relax: u32, rewind: u32) -> i32`
   */
  ss_advance(w: number, frameDt: number, seconds: number, minAccuracy: number, splits: number, relax: number, rewind: number): number;
  /**
   * `World::forget_rewind`: the page changed the model; the rewind points before it go.
   *
   * `ss_forget_rewind(w: u32) -> i32`
   */
  ss_forget_rewind(w: number): number;
  /**
   * `World::stable_dt`: the largest stable step (s) of the explicit integrator `name` for every
   * body of the world; 0 for `implicit` (stable at any step); −1 on error (set).
   *
   * # Safety
   * `name` must point to `len` bytes.
   *
   * `unsafe ss_stable_dt(w: u32, name: *const u8, len: usize) -> f64`
   */
  ss_stable_dt(w: number, name: number, len: number): number;
  /**
   * Refresh every body's render positions, pins and stats.
   *
   * `ss_sync(w: u32) -> i32`
   */
  ss_sync(w: number): number;
  /**
   * Number of bodies, or −1 for a bad handle.
   *
   * `ss_body_count(w: u32) -> i32`
   */
  ss_body_count(w: number): number;
  /**
   * Newton iterations of body `b`'s last step (0 after an explicit one), or −1 (error set).
   *
   * `ss_body_newton_iterations(w: u32, b: u32) -> i32`
   */
  ss_body_newton_iterations(w: number, b: number): number;
  /**
   * The relative residual ‖r‖/‖r_0‖ body `b`'s last implicit step was accepted at when its
   * deadline stopped it short of the tolerance (the anytime step); 0 for a step that converged
   * (or an explicit one); −1 (error set).
   *
   * `ss_body_accuracy(w: u32, b: u32) -> f64`
   */
  ss_body_accuracy(w: number, b: number): number;
  /**
   * What of the hinges body `b`'s last step let go of to finish (`Relaxed`: 0 nothing, 1 the
   * crushed faces' hinges, 2 every hinge), or −1 (error set).
   *
   * `ss_body_relaxed(w: u32, b: u32) -> i32`
   */
  ss_body_relaxed(w: number, b: number): number;
  /**
   * Body `b`'s layout table (see the module documentation), or 0 (error set).
   *
   * `ss_body_views(w: u32, b: u32) -> *const u32`
   */
  ss_body_views(w: number, b: number): number;
  /**
   * `World::let_overlapping_bodies_be`: contacts off between the bodies that overlap or touch
   * now, until they part (an import's pieces); result `{"pairs": [[a, b], …]}`.
   *
   * `ss_let_overlapping_be(w: u32) -> i32`
   */
  ss_let_overlapping_be(w: number): number;
  /**
   * The whole world as snapshot bytes (`docs/snapshot.md`) in the result.
   *
   * `ss_snapshot(w: u32) -> i32`
   */
  ss_snapshot(w: number): number;
  /**
   * The world from snapshot bytes; on error (kind `snapshot`, the core's message) the world is
   * untouched. Every body's views change.
   *
   * # Safety
   * `ptr` must point to `len` readable bytes.
   *
   * `unsafe ss_restore(w: u32, ptr: *const u8, len: usize) -> i32`
   */
  ss_restore(w: number, ptr: number, len: number): number;
  /**
   * Every body and world parameter of body `b` and its world, as a JSON object in the result
   * (`null` for the ground's when there is no ground).
   *
   * `ss_params(w: u32, b: u32) -> i32`
   */
  ss_params(w: number, b: number): number;
  /**
   * Apply preset `name` (`softsculpt::params::presets`): its body parameters on body `b`, its
   * world parameters on the world; all or nothing.
   *
   * # Safety
   * `name` must point to `len` bytes.
   *
   * `unsafe ss_apply_preset(w: u32, b: u32, name: *const u8, len: usize) -> i32`
   */
  ss_apply_preset(w: number, b: number, name: number, len: number): number;
  /**
   * Set parameter `id` (body parameters on body `b`, world parameters on the world) from a JSON
   * value; refused with an error naming the parameter and its unit.
   *
   * # Safety
   * `id` must point to `id_len` bytes and `json` to `json_len` bytes.
   *
   * `unsafe ss_set_param(w: u32, b: u32, id: *const u8, id_len: usize, json: *const u8, json_len: usize) -> i32`
   */
  ss_set_param(w: number, b: number, id: number, idLen: number, json: number, jsonLen: number): number;
  /**
   * `World::move_ground`: the ground to `height` m, carrying the bodies standing on it; result
   * `{"moved": n}` (bodies moved). Refused like `ss_set_param("ground.height")`.
   *
   * `ss_move_ground(w: u32, height: f64) -> i32`
   */
  ss_move_ground(w: number, height: number): number;
  /**
   * Rest shape := current shape; `under_load` = 1 keeps carrying the weight, `keep_tension` = 1
   * keeps the gas pressing (rest lengths solved); result `{"residual": N, "load": N,
   * "iterations": n, "clamped": n}`.
   *
   * `ss_freeze(w: u32, b: u32, under_load: u32, keep_tension: u32) -> i32`
   */
  ss_freeze(w: number, b: number, underLoad: number, keepTension: number): number;
  /**
   * Back to the last frozen shape.
   *
   * `ss_reset(w: u32, b: u32) -> i32`
   */
  ss_reset(w: number, b: number): number;
  /**
   * Replace body `b` by its isotropic remeshing to edge length `edge` (m)
   * (`World::remesh_reporting`; `under_load` ≠ 0: frozen under load); result
   * `{"dropped_events": n, "edge": m, "requested": m, "crease_deg": deg | null, "tries": n,
   * "distance": m, "volume_change": fraction}`: the edge length used (shorter than asked when the
   * shape needed it), keeping creases or not, and how far the surface moved. A remesh that would
   * change the shape is an error and changes nothing. Its views change.
   *
   * `ss_remesh(w: u32, b: u32, edge: f64, under_load: u32) -> i32`
   */
  ss_remesh(w: number, b: number, edge: number, underLoad: number): number;
  /**
   * Body `b`'s triangle quality (`World::quality`); result: JSON with the smallest angle and the
   * share of angles below 25° (degrees, fraction), the shortest and mean edge (m), the edges'
   * spread (σ/mean) and `poor` (`Quality::is_poor`).
   *
   * `ss_quality(w: u32, b: u32) -> i32`
   */
  ss_quality(w: number, b: number): number;
  /**
   * Replace body `b` by its Loop subdivision (frozen plainly, its resting vertices kept on their
   * support: `World::subdivide`); result `{"dropped_events": n}` (its pending scene events no
   * longer fit). Its views change.
   *
   * `ss_subdivide(w: u32, b: u32) -> i32`
   */
  ss_subdivide(w: number, b: number): number;
  /**
   * Multiply rest lengths by the per-vertex factors in the vertex scratch (a spring takes the
   * mean of its ends).
   *
   * `ss_scale_rest(w: u32, b: u32) -> i32`
   */
  ss_scale_rest(w: number, b: number): number;
  /**
   * Vertex masses (kg) from the vertex scratch.
   *
   * `ss_set_masses(w: u32, b: u32) -> i32`
   */
  ss_set_masses(w: number, b: number): number;
  /**
   * Pins from the pinned view (1 pinned, 0 free); only vertices that change are touched.
   *
   * `ss_set_pins(w: u32, b: u32) -> i32`
   */
  ss_set_pins(w: number, b: number): number;
  /**
   * User forces (N, 3 per vertex) and face pressures (Pa, 1 per face) from the staging views.
   *
   * `ss_apply_loads(w: u32, b: u32) -> i32`
   */
  ss_apply_loads(w: number, b: number): number;
  /**
   * Target springs of body `b` (`SoftBody::set_targets`), replacing any it had: `count` records
   * of 6 f64 at `ptr`, (vertex, anchor x, y, z (m), stiffness (N/m), damping (N·s/m)); 0 clears.
   *
   * # Safety
   * `ptr` must point to `6 count` f64 (or be null with `count` 0).
   *
   * `unsafe ss_set_targets(w: u32, b: u32, ptr: *const f64, count: usize) -> i32`
   */
  ss_set_targets(w: number, b: number, ptr: number, count: number): number;
  /**
   * A mesh file (`name`'s extension says its format, else its first bytes) read like the CLI
   * reads it (`softsculpt::mesh::load`: weld, checks, orientation, pieces): one body of `mass` kg,
   * or with `split` = 1 one body per piece, largest area first, each of `mass` kg. Returns the
   * first body's index; result: `{format, up_axis, pieces: [{vertices, faces, area, closed,
   * boundary_edges}], boundary_edges, non_manifold_edges, warnings}`. Nothing is rotated: the
   * page asks the up axis.
   *
   * # Safety
   * `name` must point to `name_len` bytes and `ptr` to `len` bytes.
   *
   * `unsafe ss_add_file(w: u32, name: *const u8, name_len: usize, ptr: *const u8, len: usize, split: u32, mass: f64) -> i32`
   */
  ss_add_file(w: number, name: number, nameLen: number, ptr: number, len: number, split: number, mass: number): number;
  /**
   * `World::apply_preset_scaled`: preset `name` for a model `size` times as large as the one it was
   * tuned for (similarity, `softsculpt::params::similarity`); result: the gas parameters skipped
   * because the body is open (JSON array).
   *
   * # Safety
   * `name` must point to `len` bytes.
   *
   * `unsafe ss_apply_preset_scaled(w: u32, b: u32, name: *const u8, len: usize, size: f64) -> i32`
   */
  ss_apply_preset_scaled(w: number, b: number, name: number, len: number, size: number): number;
  /**
   * The GLB of a recording (`softsculpt::mesh::animation`, the format of `softsculpt run
   * --frames`): `n_frames` times (s); per track `counts` holds (vertices, triangles); `tris` the
   * tracks' triangles one after the other (u32, 3 per triangle, per track's vertices); `frames`
   * per track its `n_frames` frames of xyz (f32), one track after the other. Result: the bytes.
   *
   * # Safety
   * The pointers must hold the counts they are said to hold.
   *
   * `unsafe ss_animation_glb(times: *const f64, n_frames: usize, counts: *const u32, n_tracks: usize, tris: *const u32, frames: *const f32) -> i32`
   */
  ss_animation_glb(times: number, nFrames: number, counts: number, nTracks: number, tris: number, frames: number): number;
  /**
   * Make a file (`name`, bytes) available to the next `ss_open_scene`.
   *
   * # Safety
   * The pointers must point to `name_len` and `len` readable bytes.
   *
   * `unsafe ss_scene_file(name: *const u8, name_len: usize, ptr: *const u8, len: usize) -> i32`
   */
  ss_scene_file(name: number, nameLen: number, ptr: number, len: number): number;
  /**
   * The world becomes the scene's (bodies, settings, events, clock at 0); result
   * `{"names": […], "dt": s, "duration": s}`. On error (kind `scene`, with `line` and `key`
   * when known) the world is untouched.
   *
   * # Safety
   * `ptr` must point to `len` readable bytes.
   *
   * `unsafe ss_open_scene(w: u32, ptr: *const u8, len: usize) -> i32`
   */
  ss_open_scene(w: number, ptr: number, len: number): number;
  /**
   * The world as a scene file (TOML) in the result: bodies as they are now (named as in the
   * open scene, `body1`, … otherwise), the world's settings, the open scene's obstacles and
   * events and its length (the table's default duration otherwise).
   *
   * `ss_save_scene(w: u32) -> i32`
   */
  ss_save_scene(w: number): number;
  /**
   * The world's obstacles as JSON in the result (see the module documentation).
   *
   * `ss_obstacles(w: u32) -> i32`
   */
  ss_obstacles(w: number): number;
  /**
   * Remember the world as it is now, for `ss_delta`.
   *
   * `ss_mark(w: u32) -> i32`
   */
  ss_mark(w: number): number;
  /**
   * The bytes of the delta that takes the world back to the mark, in the result (scope 0 none:
   * positions and velocities are not kept, 1 touched: of the vertices whose state changed, 2 all,
   * 3 whole: the world as it was at the mark, whatever happens after — `Delta::whole`).
   *
   * `ss_delta(w: u32, scope: u32) -> i32`
   */
  ss_delta(w: number, scope: number): number;
  /**
   * Apply delta bytes; the result holds the inverse delta's bytes. On error (kind `delta`) the
   * world is untouched. Every body's views change.
   *
   * # Safety
   * `ptr` must point to `len` readable bytes.
   *
   * `unsafe ss_apply_delta(w: u32, ptr: *const u8, len: usize) -> i32`
   */
  ss_apply_delta(w: number, ptr: number, len: number): number;
  /**
   * A version-1 project file becomes the world; result `{name, ui}`.
   *
   * # Safety
   * `ptr` must point to `len` readable bytes.
   *
   * `unsafe ss_open_project_v1(w: u32, ptr: *const u8, len: usize) -> i32`
   */
  ss_open_project_v1(w: number, ptr: number, len: number): number;
}

/** Every raw export and its number of arguments (what `Function.length` says of it), in the table's order. */
export const EXPORTS: { readonly [name in Exclude<keyof RawEngine, 'memory'>]: number } = {
  ss_alloc: 1,
  ss_dealloc: 2,
  ss_error_ptr: 0,
  ss_error_len: 0,
  ss_result_ptr: 0,
  ss_result_len: 0,
  ss_material_presets: 0,
  ss_param_table: 0,
  ss_world_new: 0,
  ss_world_free: 1,
  ss_use_threads: 1,
  ss_thread_serve: 0,
  ss_thread_passes: 0,
  ss_thread_trapped_flag: 0,
  ss_threads: 0,
  ss_workload: 1,
  ss_add_builtin: 4,
  ss_add_obj: 4,
  ss_add_sketch: 5,
  ss_add_mesh: 7,
  ss_clear: 1,
  ss_step: 2,
  ss_advance: 7,
  ss_forget_rewind: 1,
  ss_stable_dt: 3,
  ss_sync: 1,
  ss_body_count: 1,
  ss_body_newton_iterations: 2,
  ss_body_accuracy: 2,
  ss_body_relaxed: 2,
  ss_body_views: 2,
  ss_let_overlapping_be: 1,
  ss_snapshot: 1,
  ss_restore: 3,
  ss_params: 2,
  ss_apply_preset: 4,
  ss_set_param: 6,
  ss_move_ground: 2,
  ss_freeze: 4,
  ss_reset: 2,
  ss_remesh: 4,
  ss_quality: 2,
  ss_subdivide: 2,
  ss_scale_rest: 2,
  ss_set_masses: 2,
  ss_set_pins: 2,
  ss_apply_loads: 2,
  ss_set_targets: 4,
  ss_add_file: 7,
  ss_apply_preset_scaled: 5,
  ss_animation_glb: 6,
  ss_scene_file: 4,
  ss_open_scene: 3,
  ss_save_scene: 1,
  ss_obstacles: 1,
  ss_mark: 1,
  ss_delta: 2,
  ss_apply_delta: 3,
  ss_open_project_v1: 3,
};

/** The slots of a body's layout table (`ss_body_views`; crates/softsculpt-wasm/src/views.rs). */
export const SLOT = {
  /** Vertex count n. */
  n: 0,
  /** Face count f. */
  f: 1,
  /** Spring count s. */
  s: 2,
  /** Bending-spring count k. */
  k: 3,
  /** Positions (m), the engine's: f64, 3n. */
  positions: 4,
  /** Velocities (m/s), the engine's: f64, 3n. */
  velocities: 5,
  /** Render positions (refreshed by `ss_sync`): f32, 3n. */
  render: 6,
  /** Triangles: u32, 3f. */
  triangles: 7,
  /** Springs (ends): u32, 2s. */
  springs: 8,
  /** Vertex masses (kg), the engine's: f64, n. */
  masses: 9,
  /** Pinned (1/0; refreshed by `ss_sync`, read by `ss_set_pins`): u8, n. */
  pinned: 10,
  /** Spring rest lengths (m), the engine's: f64, s. */
  rest: 11,
  /** Bending-spring rest lengths (m), the engine's: f64, k. */
  bendingRest: 12,
  /** Staging: user forces (N), read by `ss_apply_loads`: f64, 3n. */
  userForces: 13,
  /** Staging: face pressures (Pa), read by `ss_apply_loads`: f64, f. */
  facePressures: 14,
  /** Staging: vertex scratch, read by `ss_scale_rest`, `ss_set_masses`: f64, n. */
  scratch: 15,
  /** Stats (refreshed by `ss_sync`): f64, `STATS_LEN` (the stats block, `STATS`). */
  stats: 16,
} as const;
/** Length of the layout table (u32). */
export const LAYOUT_LEN = 17;

/** A body's statistics as of the last `ss_sync` (the stats block, views.rs). */
export interface Stats {
  /** Steps taken. */
  step: number;
  /** Simulated time (s). */
  time: number;
  /** The volume the pressure uses (m³). */
  volume: number;
  /** Gas pressure (Pa). */
  pressure: number;
  /** Kinetic energy (J). */
  kinetic: number;
  /** Elastic energy (J). */
  elastic: number;
  /** Gas energy (J). */
  gas: number;
  /** Gravitational energy (J). */
  gravity: number;
  /** The sum of the four energies (J). */
  total: number;
  /** Momentum (kg·m/s). */
  momentum: [number, number, number];
  /** Centre of mass (m). */
  centerOfMass: [number, number, number];
  /** Largest speed (m/s). */
  maxSpeed: number;
}
/** Length of the stats block (f64). */
export const STATS_LEN = 16;

/** The stats block (`STATS_LEN` f64, the layout table's `stats` slot) as `Stats`. */
export function readStats(s: ArrayLike<number>): Stats {
  return {
    step: s[0],
    time: s[1],
    volume: s[2],
    pressure: s[3],
    kinetic: s[4],
    elastic: s[5],
    gas: s[6],
    gravity: s[7],
    total: s[8],
    momentum: [s[9], s[10], s[11]],
    centerOfMass: [s[12], s[13], s[14]],
    maxSpeed: s[15],
  };
}

/** `ss_delta`'s scope codes (crates/softsculpt-wasm/src/history.rs): what an undo delta keeps. */
export const SCOPE = {
  /** Positions and velocities are not kept. */
  none: 0,
  /** The state of the vertices whose state changed. */
  touched: 1,
  /** The state of every vertex. */
  all: 2,
  /** The world as it was at the mark, whatever the steps since did. */
  whole: 3,
} as const;
export type DeltaScope = keyof typeof SCOPE;

/** What a freeze leaves unbalanced (`softsculpt::body::FreezeReport`): forces in N. */
export interface FreezeReport {
  /** Largest net force on a free vertex at rest right after the freeze. */
  residual: number;
  /** Largest load the springs were asked to balance on a vertex: the residual's scale. */
  load: number;
  /** Conjugate-gradient iterations of the tension solve. */
  iterations: number;
  /** Springs whose solved rest length came out negative and was set to 0. */
  clamped: number;
}

/**
 * What `ss_remesh` reports (lengths in m; `volume_change` relative, before the remesher's
 * correction).
 */
export interface RemeshReport {
  /** The body's pending scene events that no longer fit and were dropped. */
  dropped_events: number;
  /** The edge length used. */
  edge: number;
  /** The edge length asked for. */
  requested: number;
  /** The crease angle kept (degrees), or null. */
  crease_deg: number | null;
  /** 1: remeshed as asked; more: the shape needed a shorter edge or its sharp edges kept. */
  tries: number;
  /** The largest distance between the old and the new surface. */
  distance: number;
  volume_change: number;
}

/** What a mesh file held (`ss_add_file`): its format, the up axis it declares, its pieces. */
export interface FileReport {
  /** The format read (`OBJ`, `PLY`, `STL`, `glTF`, `GLB`), or null. */
  format: string | null;
  /** 'y' (glTF says so) or 'unknown' (OBJ, PLY, STL). */
  up_axis: 'y' | 'z' | 'unknown';
  /** Its pieces (one body each when split), largest area first. */
  pieces: PieceReport[];
  boundary_edges: number;
  non_manifold_edges: number;
  /** What the reader mended or doubts, a line each. */
  warnings: string[];
}

/**
 * One piece of a mesh file (`FileReport.pieces`): its size (area in m²) and whether it is
 * closed.
 */
export interface PieceReport {
  vertices: number;
  faces: number;
  area: number;
  closed: boolean;
  boundary_edges: number;
}

/** What a frame did (`World.advance`, the core's `Advance`). */
export interface Advance {
  /** Steps taken (a split step counts its pieces). */
  steps: number;
  /** Steps that had to be split. */
  splits: number;
  /** Simulated seconds advanced. */
  simulated: number;
  /** The largest relative residual a step was accepted at. */
  residual: number;
  /** Implicit steps stopped at their deadline, short of the tolerance. */
  early: number;
  /** Wall-clock seconds the frame took (real-time budgets). */
  wall: number;
}
