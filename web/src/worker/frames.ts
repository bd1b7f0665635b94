// Frames for the page: the positions in a recycled Float32Array (two per mesh size: one being
// drawn by the page, one being filled here), the statistics every time, and what else changed
// since the last frame (topology, masses and pins, parameters, settings, history sizes); the
// engine's parameter table with the first frame (and after a resync).

import type { Frame } from '../protocol';
import type { Document } from './document';
import { engineThreads } from '../engine/wasm';

export class FramePublisher {
  private free: Float32Array[] = [];
  /** Buffers of the current length in existence (free here or out with the page). */
  private owned = 0;
  private length = -1;
  private sent = { topology: -1, body: -1, params: '', settings: '', history: '', table: false };

  constructor(private readonly buffers = 2) {}

  /** A buffer the page has drawn and handed back; one of an old mesh size is dropped. */
  giveBack(buffer: ArrayBuffer): void {
    const a = new Float32Array(buffer);
    if (a.length === this.length && this.free.length + 1 <= this.owned) this.free.push(a);
  }

  /** Send everything again with the next frame. */
  resync(): void {
    this.sent = { topology: -1, body: -1, params: '', settings: '', history: '', table: false };
  }

  /** Send the parameters again with the next frame (a refused value: the page shows the old one again). */
  resendParams(): void { this.sent.params = ''; }

  /** How many buffers exist for the current mesh size (for tests). */
  get allocated(): number { return this.owned; }

  /**
   * The next frame, or null if nothing is new (`moved`: the simulation stepped or a stroke is
   * acting) or no buffer is free (the page has not drawn the last frame yet).
   */
  next(doc: Document, moved: boolean, sim: { simMs: number; slowMotion: boolean; realTimeFraction: number; accuracy: number }): Frame | null {
    const params = doc.params();
    const paramsKey = JSON.stringify(params);
    const settingsKey = JSON.stringify(doc.settings);
    const historyKey = doc.history.sizes.join(',');
    const news = doc.topologyVersion !== this.sent.topology || doc.bodyVersion !== this.sent.body ||
      paramsKey !== this.sent.params || settingsKey !== this.sent.settings || historyKey !== this.sent.history;
    if (!moved && !news) return null;
    const len = doc.renderLength;
    if (len !== this.length) { this.length = len; this.free = []; this.owned = 0; }
    let positions = this.free.pop();
    if (!positions) {
      if (this.owned >= this.buffers) return null;
      positions = new Float32Array(len);
      this.owned++;
    }
    doc.renderInto(positions);
    const frame: Frame = { positions, stats: doc.stats(), ...sim, scene: doc.sceneInfo };
    if (doc.topologyVersion !== this.sent.topology) { frame.topology = doc.topology(); this.sent.topology = doc.topologyVersion; }
    if (doc.bodyVersion !== this.sent.body) { frame.body = doc.bodyData(); this.sent.body = doc.bodyVersion; }
    if (paramsKey !== this.sent.params) { frame.params = params; this.sent.params = paramsKey; }
    if (!this.sent.table) { frame.table = doc.paramTable(); frame.presets = doc.world.materialPresets(); frame.threads = engineThreads(); this.sent.table = true; }
    if (settingsKey !== this.sent.settings) { frame.settings = { ...doc.settings }; this.sent.settings = settingsKey; }
    if (historyKey !== this.sent.history) { frame.history = doc.history.sizes; this.sent.history = historyKey; }
    if (doc.settings.strain) frame.strain = doc.strain();
    return frame;
  }
}
