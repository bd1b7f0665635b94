// SoftBody: one small class over one engine body (a handle). Arrays are views over wasm memory.

import { message, raw, view, withArrays, withBytes } from './wasm';
import { Param, type ParamName } from './params';

export class EngineError extends Error {}

function check(status: number, what: string): void {
  if (status !== 0) throw new EngineError(`${what}: ${message()}`);
}

function created(h: number, what: string): number {
  if (h === 0) throw new EngineError(`${what}: ${message()}`);
  return h;
}

export interface Stats {
  step: number; time: number; volume: number; pressure: number;
  kinetic: number; elastic: number; gas: number; gravity: number; total: number;
  momentum: [number, number, number]; centerOfMass: [number, number, number]; maxSpeed: number;
}

export class SoftBody {
  private handle: number;
  /** Warnings from loading (welded seams, dropped faces…), one per line; '' if none. */
  readonly warnings: string;

  private constructor(handle: number) {
    this.handle = handle;
    this.warnings = message();
  }

  static builtin(name: string, mass = 1): SoftBody {
    const bytes = new TextEncoder().encode(name);
    return new SoftBody(created(withBytes(bytes, (p, n) => raw().ss_create_builtin(p, n, mass)), `model '${name}'`));
  }

  static fromObj(bytes: Uint8Array, mass = 1): SoftBody {
    return new SoftBody(created(withBytes(bytes, (p, n) => raw().ss_create_obj(p, n, mass)), 'OBJ'));
  }

  /** From an indexed triangle mesh; `weld` prepares it like a file (weld, orient, reorder). */
  static fromMesh(positions: Float64Array, indices: Uint32Array, mass = 1, weld = true): SoftBody {
    const h = withArrays([positions, indices], (p, i) =>
      raw().ss_create_mesh(p, positions.length / 3, i, indices.length, mass, weld ? 1 : 0));
    return new SoftBody(created(h, 'mesh'));
  }

  /** A body the engine already holds (a scene's body, see `Scene`). */
  static adopt(handle: number): SoftBody { return new SoftBody(created(handle, 'body')); }
  /** The engine's handle, for calls that take several bodies (`Scene`). */
  get id(): number { return this.handle; }

  get alive(): boolean { return this.handle !== 0; }
  free(): void {
    if (this.handle !== 0) raw().ss_free(this.handle);
    this.handle = 0;
  }

  get vertexCount(): number { return raw().ss_vertex_count(this.handle); }
  get faceCount(): number { return raw().ss_face_count(this.handle); }
  get springCount(): number { return raw().ss_spring_count(this.handle); }

  /** Positions as f32 for rendering, refreshed from the engine (a view: copy to keep). */
  syncRender(): Float32Array { return view.f32(raw().ss_sync(this.handle), 3 * this.vertexCount); }
  positions(): Float64Array { return view.f64(raw().ss_positions(this.handle), 3 * this.vertexCount); }
  velocities(): Float64Array { return view.f64(raw().ss_velocities(this.handle), 3 * this.vertexCount); }
  masses(): Float64Array { return view.f64(raw().ss_masses(this.handle), this.vertexCount); }
  restLengths(): Float64Array { return view.f64(raw().ss_rest_lengths(this.handle), this.springCount); }
  get bendingCount(): number { return raw().ss_bending_count(this.handle); }
  bendingRestLengths(): Float64Array { return view.f64(raw().ss_bending_rest_lengths(this.handle), this.bendingCount); }
  frozenBendingRestLengths(): Float64Array { return view.f64(raw().ss_frozen_bending_rest_lengths(this.handle), this.bendingCount); }
  setBendingRest(now: Float64Array, frozen: Float64Array): void {
    withArrays([now, frozen], (a, b) => check(raw().ss_set_bending_rest(this.handle, a, b), 'bending rest lengths'));
  }
  frozenPositions(): Float64Array { return view.f64(raw().ss_frozen_positions(this.handle), 3 * this.vertexCount); }
  frozenRestLengths(): Float64Array { return view.f64(raw().ss_frozen_rest_lengths(this.handle), this.springCount); }
  triangles(): Uint32Array { return view.u32(raw().ss_triangles(this.handle), 3 * this.faceCount); }
  springs(): Uint32Array { return view.u32(raw().ss_springs(this.handle), 2 * this.springCount); }
  pinned(): Uint8Array { return view.u8(raw().ss_pinned(this.handle), this.vertexCount); }

  get(p: ParamName): number { return raw().ss_get(this.handle, Param[p]); }
  set(p: ParamName, value: number): void { check(raw().ss_set(this.handle, Param[p], value), p); }

  /** `substeps` steps of `dt` s; on a blow-up the engine rolls back and this throws. */
  step(dt: number, substeps = 1): void { check(raw().ss_step(this.handle, dt, substeps), 'step'); }

  stats(): Stats {
    const s = view.f64(raw().ss_stats(this.handle), 16);
    return {
      step: s[0], time: s[1], volume: s[2], pressure: s[3], kinetic: s[4], elastic: s[5], gas: s[6],
      gravity: s[7], total: s[8], momentum: [s[9], s[10], s[11]], centerOfMass: [s[12], s[13], s[14]], maxSpeed: s[15],
    };
  }

  freeze(): void { check(raw().ss_freeze(this.handle), 'freeze'); }
  /** Freeze but keep carrying the current loads (a body resting under gravity does not sag). */
  freezeUnderLoad(): void { check(raw().ss_freeze_under_load(this.handle), 'freeze'); }
  prestress(): Float64Array { return view.f64(raw().ss_prestress(this.handle), 3 * this.vertexCount); }
  frozenPrestress(): Float64Array { return view.f64(raw().ss_frozen_prestress(this.handle), 3 * this.vertexCount); }
  setPrestress(now: Float64Array, frozen: Float64Array): void {
    withArrays([now, frozen], (a, b) => check(raw().ss_set_prestress(this.handle, a, b), 'prestress'));
  }
  reset(): void { check(raw().ss_reset(this.handle), 'reset'); }
  /** Loop subdivision (the body becomes the subdivided, frozen one; all views change). */
  subdivide(): void { check(raw().ss_subdivide(this.handle), 'subdivide'); }
  scaleRest(factor: number): void { check(raw().ss_scale_rest(this.handle, factor), 'inflate'); }

  /** Multiply rest lengths by per-vertex factors (a spring takes the mean of its ends). */
  scaleRestByVertex(factors: ArrayLike<number>): void {
    view.f64(raw().ss_vertex_scratch(this.handle), this.vertexCount).set(factors);
    check(raw().ss_scale_rest_by_vertex(this.handle), 'inflate');
  }
  setMasses(masses: ArrayLike<number>): void {
    view.f64(raw().ss_vertex_scratch(this.handle), this.vertexCount).set(masses);
    check(raw().ss_set_masses(this.handle), 'masses');
  }
  setPinned(vertex: number, pinned: boolean): void {
    check(raw().ss_set_pinned(this.handle, vertex, pinned ? 1 : 0), 'pin');
  }
  /** The staging array of user forces (N, 3 per vertex); call applyUserForces after writing. */
  userForces(): Float64Array { return view.f64(raw().ss_user_forces(this.handle), 3 * this.vertexCount); }
  applyUserForces(): void { check(raw().ss_apply_user_forces(this.handle), 'forces'); }
  /** The staging array of face pressures (Pa, 1 per face); call applyFacePressures after. */
  facePressures(): Float64Array { return view.f64(raw().ss_face_pressures(this.handle), this.faceCount); }
  applyFacePressures(): void { check(raw().ss_apply_face_pressures(this.handle), 'pressure'); }

  setRestLengths(rest: Float64Array): void {
    withArrays([rest], (p) => check(raw().ss_set_rest_lengths(this.handle, p), 'rest lengths'));
  }
  setState(positions: Float64Array, velocities: Float64Array): void {
    view.f64(raw().ss_vector_scratch(this.handle), 3 * this.vertexCount).set(velocities);
    withArrays([positions], (p) => check(raw().ss_set_state(this.handle, p), 'state'));
  }
  setFrozen(positions: Float64Array, rest: Float64Array, ambient: number, volume: number): void {
    withArrays([positions, rest], (p, r) => check(raw().ss_set_frozen(this.handle, p, r, ambient, volume), 'frozen state'));
  }
}
