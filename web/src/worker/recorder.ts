// Recording in the worker: while the simulation plays, every body's shape is kept at RECORD_FPS
// frames per simulated second; the recording is written as a GLB of morph targets by the core
// (the format of `softsculpt run --frames`: one mesh per body, one target per frame, the weights
// animated; Blender imports the targets as shape keys). Positions are written in the imported
// file's units and placement (Y-up, as glTF is).

import { animationGlb } from '../engine/world';
import { IDENTITY_FRAME, toFile } from '../io/import';
import type { Recording } from '../protocol';
import type { Document } from './document';

/** Frames per simulated second. */
export const RECORD_FPS = 30;
/** Most bytes of frames kept (f32 positions); recording stops there and says so. */
export const RECORD_MAX_BYTES = 256 * 1024 * 1024;

interface Take { times: number[]; triangles: Uint32Array[]; frames: Float32Array[][]; bytes: number; next: number }

export class Recorder {
  private take: Take | null = null;
  /** The last recording, stopped (kept for export until the next one starts). */
  private done: Take | null = null;

  constructor(private readonly say: (text: string, kind?: 'info' | 'warn' | 'error') => void) {}

  get recording(): boolean { return this.take !== null; }
  /** What is being recorded (for the frames), or undefined. */
  get status(): Recording | undefined {
    const t = this.take;
    return t ? { frames: t.times.length, seconds: t.times.length ? t.times[t.times.length - 1] - t.times[0] : 0 } : undefined;
  }

  start(doc: Document): void {
    const w = doc.world, triangles: Uint32Array[] = [];
    for (let i = 0; i < w.bodyCount; i++) triangles.push(w.body(i).triangles.slice());
    this.take = { times: [], triangles, frames: triangles.map(() => []), bytes: 0, next: -Infinity };
    this.done = null;
    this.sample(doc);
    this.say(`recording at ${RECORD_FPS} frames per simulated second${doc.settings.playing ? '' : ' (paused: play to record motion)'}`);
  }

  stop(): void {
    const t = this.take;
    if (!t) return;
    this.take = null;
    this.done = t;
    this.say(`recorded ${t.times.length} frames (${(t.times[t.times.length - 1] - t.times[0]).toFixed(2)} s): Files › Export recording writes them as GLB`);
  }

  /** After steps: keep a frame if a frame's time has passed; stop if the meshes changed. */
  sample(doc: Document): void {
    const t = this.take;
    if (!t) return;
    const w = doc.world;
    const same = w.bodyCount === t.triangles.length && t.triangles.every((tri, i) => w.body(i).triangles.length === tri.length && w.body(i).vertexCount * 3 === (t.frames[i][0]?.length ?? w.body(i).vertexCount * 3));
    if (!same) { this.say('recording stopped: the meshes changed (a new model, subdivide or undo)', 'warn'); this.stop(); return; }
    const time = doc.stats().time;
    if (time + 1e-9 < t.next) return;
    if (t.times.length && time <= t.times[t.times.length - 1]) return;
    const frame = doc.settings.frame ?? IDENTITY_FRAME;
    for (let i = 0; i < w.bodyCount; i++) {
      const f = Float32Array.from(toFile(w.body(i).positions, frame, true));
      t.frames[i].push(f);
      t.bytes += f.byteLength;
    }
    t.times.push(time);
    t.next = time + 1 / RECORD_FPS - 1e-9;
    if (t.bytes >= RECORD_MAX_BYTES) { this.say(`recording stopped at ${RECORD_MAX_BYTES >> 20} MB of frames`, 'warn'); this.stop(); }
  }

  /** The GLB of the last recording (stopping one under way), or null if there is none. */
  glb(): Uint8Array | null {
    if (this.take) this.stop();
    const t = this.done;
    if (!t || t.times.length === 0) return null;
    const t0 = t.times[0];
    return animationGlb(Float64Array.from(t.times, (x) => x - t0), t.triangles.map((triangles, i) => ({ triangles, frames: t.frames[i] })));
  }
}
