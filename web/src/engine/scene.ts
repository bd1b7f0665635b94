// Scene: one small class over one engine scene (crates/softsculpt/src/scene): a world of bodies,
// rigid obstacles and timed events, opened from a TOML scene file and saved back to one.

import { message, raw, view, withArrays, withBytes } from './wasm';
import { EngineError, SoftBody } from './softbody';

/** A rigid obstacle as the engine describes it (m). */
export type Obstacle =
  | { kind: 'sphere'; center: number[]; radius: number }
  | { kind: 'box'; center: number[]; half: number[]; axes: number[][] }
  | { kind: 'capsule'; a: number[]; b: number[]; radius: number }
  | { kind: 'mesh'; positions: Float64Array; indices: Uint32Array };

export class Scene {
  private handle: number;
  /** The scene's bodies, in file order; each is an ordinary SoftBody. */
  readonly bodies: SoftBody[];
  readonly names: string[];

  private constructor(handle: number) {
    this.handle = handle;
    const n = raw().ss_scene_body_count(handle);
    this.bodies = Array.from({ length: n }, (_, i) => SoftBody.adopt(raw().ss_scene_body(handle, i)));
    raw().ss_scene_names(handle);
    this.names = message().split('\n');
  }

  /**
   * Open scene text; `files` holds the mesh files it names (by file name). Throws EngineError
   * with the scene's line and key on a bad file.
   */
  static open(text: string, files: Map<string, Uint8Array> = new Map()): Scene {
    const e = raw();
    for (const [name, bytes] of files) {
      const nameBytes = new TextEncoder().encode(name);
      withBytes(nameBytes, (np, nl) => withBytes(bytes, (p, l) => e.ss_scene_add_file(np, nl, p, l)));
    }
    const h = withBytes(new TextEncoder().encode(text), (p, n) => e.ss_scene_open(p, n));
    if (h === 0) throw new EngineError(`scene: ${message()}`);
    return new Scene(h);
  }

  /** Scene text (TOML) for `bodies` as they are now, with `scene`'s obstacles and events. */
  static save(bodies: SoftBody[], dt: number, duration: number, scene: Scene | null = null): string {
    const ids = new Uint32Array(bodies.map((b) => b.id));
    const status = withArrays([ids], (p) => raw().ss_scene_save(scene ? scene.handle : 0, p, ids.length, dt, duration));
    if (status !== 0) throw new EngineError(`save scene: ${message()}`);
    return message();
  }

  get time(): number { return raw().ss_scene_time(this.handle); }
  get duration(): number { return raw().ss_scene_duration(this.handle); }
  /** The scene file's time step (s). */
  get dt(): number { return raw().ss_scene_dt(this.handle); }

  /** Step the whole world (contacts, events) `substeps` times by `dt` (s); rolls back on failure. */
  step(dt: number, substeps = 1): void {
    if (raw().ss_scene_step(this.handle, dt, substeps) !== 0) throw new EngineError(message());
  }

  /** Body `i` was replaced (undo, subdivide); returns a note if its pending events were dropped. */
  replaceBody(i: number, body: SoftBody): string {
    if (raw().ss_scene_set_body(this.handle, i, body.id) !== 0) throw new EngineError(message());
    (this.bodies as SoftBody[])[i] = body;
    return message();
  }

  obstacles(): Obstacle[] {
    const n = raw().ss_scene_obstacles_len(this.handle);
    const a = view.f64(raw().ss_scene_obstacles(this.handle), n).slice();
    const out: Obstacle[] = [];
    for (let k = 0; k < n;) {
      const kind = a[k];
      const v = (i: number) => [a[i], a[i + 1], a[i + 2]];
      if (kind === 0) { out.push({ kind: 'sphere', center: v(k + 2), radius: a[k + 5] }); k += 6; }
      else if (kind === 1) { out.push({ kind: 'box', center: v(k + 2), half: v(k + 5), axes: [v(k + 8), v(k + 11), v(k + 14)] }); k += 17; }
      else if (kind === 2) { out.push({ kind: 'capsule', a: v(k + 2), b: v(k + 5), radius: a[k + 8] }); k += 9; }
      else {
        const nv = a[k + 2], nt = a[k + 3];
        const positions = a.slice(k + 4, k + 4 + 3 * nv);
        const indices = Uint32Array.from(a.slice(k + 4 + 3 * nv, k + 4 + 3 * nv + 3 * nt));
        out.push({ kind: 'mesh', positions, indices });
        k += 4 + 3 * nv + 3 * nt;
      }
    }
    return out;
  }

  /** Forget the scene; its bodies stay alive (free them separately). */
  free(): void {
    if (this.handle !== 0) raw().ss_scene_free(this.handle);
    this.handle = 0;
  }
}
