// The simulation service: the worker's side of the protocol. It turns commands into document
// operations, runs the real-time stepping tick, publishes frames, reports progress and messages,
// and autosaves. A plain class: the worker (worker/main.ts) feeds it messages and ticks; the
// tests do the same in Node.

import type { Command, MessageKind, Reply, Settings, UiState } from '../protocol';
import { interrupts, transferables } from '../protocol';
import { tookInterrupt, useInterrupts } from '../engine/wasm';
import { Document, errorText, loadEngine } from './document';
import { baseName } from '../project';
import type { Autosave, AutosaveRecord } from '../storage';
import { FramePublisher } from './frames';
import { Stepper } from './stepper';
import { Recorder } from './recorder';

export interface ServiceHost {
  post(reply: Reply, transfer: Transferable[]): void;
  now(): number;
  /** Where the autosave lives (IndexedDB in the browser; absent: no autosave). */
  storage?: { load(): Promise<Autosave | null>; save(record: AutosaveRecord): Promise<void> };
  /** Defer `f` by `ms` (the autosave's debounce). */
  later?(f: () => void, ms: number): unknown;
  cancel?(timer: unknown): void;
}

/** While the simulation runs, the autosave is written at least this often (ms of wall-clock time). */
export const AUTOSAVE_RUNNING_MS = 10000;

export class Service {
  readonly doc: Document;
  readonly frames = new FramePublisher();
  readonly stepper: Stepper;
  readonly recorder: Recorder;
  private progressLabel: string | null = null;
  private progressAt = 0;
  private saveTimer: unknown = null;
  /** When the autosave was last written (host clock, ms) and what writing it took (ms). */
  private savedAt = 0;
  private saveCost = 0;
  private lastTickError = '';
  /** A command may have changed what the page shows: publish a frame on the next tick. */
  private poked = false;

  constructor(private readonly host: ServiceHost) {
    this.stepper = new Stepper(() => host.now());
    this.doc = new Document({
      message: (text, kind) => this.message(text, kind),
      progress: (label, fraction) => this.progress(label, fraction),
      changed: () => this.autosave(),
      ui: (ui) => this.post({ type: 'ui', ui }),
      ask: (question) => this.post({ type: 'importQuestion', question }),
    });
    this.recorder = new Recorder((text, kind) => this.message(text, kind));
  }

  private post(r: Reply): void { this.host.post(r, transferables(r)); }
  message(text: string, kind: MessageKind = 'info'): void { this.post({ type: 'message', text, kind }); }

  /** Progress of a long operation, at most ten times a second (and always its start and end). */
  private progress(label: string | null, fraction?: number): void {
    const now = this.host.now();
    if (label === this.progressLabel && (label === null || now - this.progressAt < 100)) return;
    this.progressLabel = label;
    this.progressAt = now;
    this.post(fraction === undefined ? { type: 'progress', label } : { type: 'progress', label, fraction });
  }

  /** Handle one command. Whatever fails is reported; the document stays as it was. */
  async handle(cmd: Command): Promise<void> {
    if (cmd.type !== 'returnBuffer') this.poked = true;
    if (interrupts(cmd)) tookInterrupt();
    try {
      await this.dispatch(cmd);
    } catch (e) {
      this.progress(null);
      this.message(`${describe(cmd)} failed: ${errorText(e)} — the model is as it was before`, 'error');
    }
  }

  private async dispatch(cmd: Command): Promise<void> {
    const doc = this.doc;
    if (cmd.type === 'init') { if (cmd.interrupts) useInterrupts(cmd.interrupts); return this.init(cmd.wasmUrl, cmd.restore, cmd.threads); }
    if (cmd.type === 'returnBuffer') return this.frames.giveBack(cmd.buffer);
    if (cmd.type === 'resync') return this.frames.resync();
    if (cmd.type === 'ui') { doc.ui = cmd.ui; return; }
    if (!doc.loaded) { this.message('the engine is still starting; try again in a moment', 'warn'); return; }
    switch (cmd.type) {
      case 'loadBuiltin': return doc.loadBuiltin(cmd.name);
      case 'import': return doc.importFile(cmd.name, cmd.data, cmd.upAnswers);
      case 'setUp': return doc.setUp(cmd.up);
      case 'importAnswer': return doc.importAnswer(cmd.answer);
      case 'record': if (cmd.on) this.recorder.start(doc); else this.recorder.stop(); return;
      case 'exportRecording': return this.exportRecording();
      case 'openProject': return doc.openProject(cmd.name, cmd.text);
      case 'openScene': doc.openScene(cmd.name, cmd.text, cmd.files); return;
      case 'restartScene': return doc.restartScene();
      case 'saveProject': return this.saveProject(cmd.ui);
      case 'saveScene': return this.saveScene();
      case 'freeze': return doc.freeze();
      case 'reset': return doc.reset();
      case 'subdivide': return doc.subdivide();
      case 'remesh': return doc.remesh();
      case 'undo': return doc.undo();
      case 'redo': return doc.redo();
      case 'step': doc.updateStroke(doc.settings.dt * doc.settings.substeps); this.stepper.run(doc, doc.settings.dt, doc.settings.substeps); this.recorder.sample(doc); return;
      case 'setParam': if (!doc.setParam(cmd.name, cmd.value)) this.frames.resendParams(); return;
      case 'setMass': return doc.setMass(cmd.total);
      case 'preset': return doc.materialPreset(cmd.name);
      case 'wind': return doc.wind(cmd.direction, cmd.strength);
      case 'settings': return this.settings(cmd.patch);
      case 'strokeStart': return doc.strokeStart(cmd);
      case 'strokeMove': return doc.strokeMove(cmd.point, cmd.inverted, cmd.pressure);
      case 'strokeEnd': return doc.strokeEnd();
      case 'sketch': return doc.sketch(cmd);
    }
  }

  private async init(wasmUrl: string, restore: boolean, threads?: number): Promise<void> {
    try {
      await loadEngine(wasmUrl, threads);
    } catch (e) {
      this.post({ type: 'fatal', text: `SoftSculpt could not start its engine: ${errorText(e)}` });
      return;
    }
    let saved: Autosave | null = null;
    if (restore && this.host.storage) {
      try {
        saved = await this.host.storage.load();
      } catch (e) {
        this.message(`could not read the autosave: ${errorText(e)}; opened the default model instead`, 'warn');
      }
    }
    this.doc.open(saved);
  }

  private settings(patch: Partial<Settings>): void {
    const s = this.doc.settings;
    if (typeof patch.dt === 'number' && Number.isFinite(patch.dt) && patch.dt > 0) this.doc.setDt(patch.dt);
    if (typeof patch.substeps === 'number' && patch.substeps >= 1) s.substeps = Math.round(patch.substeps);
    if (typeof patch.realTime === 'boolean') s.realTime = patch.realTime;
    if (typeof patch.playing === 'boolean') { s.playing = patch.playing; this.doc.pausedByError = false; }
    if (typeof patch.strain === 'boolean') s.strain = patch.strain;
    if (typeof patch.keepTension === 'boolean') s.keepTension = patch.keepTension;
    this.autosave();
  }

  private saveProject(ui: UiState): void {
    this.doc.ui = ui;
    const filename = `${baseName(this.doc.settings.model)}.softsculpt.json`;
    const text = this.doc.projectText();
    this.post({ type: 'download', filename, mime: 'application/json', text });
    // Said, as exports are (a new-user trial saw nothing happen on Ctrl+S).
    this.message(`saved the project ${filename} (${(text.length / 1024).toPrecision(3)} KB, in your downloads): Open project (Ctrl+O) continues from here`);
  }

  private exportRecording(): void {
    const bytes = this.recorder.glb();
    if (!bytes) { this.message('nothing recorded yet: Record, play, then export', 'warn'); return; }
    this.post({ type: 'download', filename: `${baseName(this.doc.settings.model)}-recording.glb`, mime: 'model/gltf-binary', text: '', bytes });
  }

  private saveScene(): void {
    try {
      const text = this.doc.sceneText();
      this.post({ type: 'download', filename: `${baseName(this.doc.settings.model)}.toml`, mime: 'application/toml', text });
      this.message('saved the scene: the shapes as they are now, opening at rest');
    } catch (e) {
      this.message(`could not save the scene: ${errorText(e)}`, 'error');
    }
  }

  /** Write the world's snapshot (and the page's state) to the autosave a moment after the last change. */
  autosave(): void {
    const { storage, later, cancel } = this.host;
    if (!storage || !later) return;
    if (this.saveTimer !== null) cancel?.(this.saveTimer);
    this.saveTimer = later(() => {
      this.saveTimer = null;
      this.saveNow();
    }, 250);
  }

  /** Write the autosave now (its snapshot and the undo steps kept), timing what it takes here. */
  private saveNow(): void {
    const storage = this.host.storage;
    if (!storage || !this.doc.loaded) return;
    const t0 = this.host.now();
    storage.save(this.doc.autosaveRecord(Date.now())).catch((e) => this.message(`autosave failed: ${errorText(e)}`, 'warn'));
    this.savedAt = this.host.now();
    this.saveCost = this.savedAt - t0;
  }

  /**
   * While the simulation runs the shape keeps changing after the last operation (a body
   * collapsing, settling, blown by the wind): a reload must bring back what was on screen, not
   * the moment of the last edit. So the autosave is also written every AUTOSAVE_RUNNING_MS of
   * running, or less often if writing it is slow: at most 2 % of the time (a 40,962-vertex
   * snapshot takes ~33 ms: every 1.7 s would do; 10 s is the floor).
   */
  private saveWhileRunning(): void {
    if (this.saveTimer !== null) return; // one is coming
    if (this.host.now() - this.savedAt >= Math.max(AUTOSAVE_RUNNING_MS, 50 * this.saveCost)) this.saveNow();
  }

  /** One tick: step as the clock allows, then publish a frame if there is something to show. */
  tick(): void {
    if (!this.doc.loaded) return;
    try {
      const stepped = this.stepper.tick(this.doc);
      if (stepped) {
        this.recorder.sample(this.doc);
        this.saveWhileRunning();
      }
      const sim = { simMs: 0, slowMotion: this.stepper.slowMotion, realTimeFraction: this.stepper.realTimeFraction, accuracy: 0 };
      const frame = this.frames.next(this.doc, stepped || this.doc.stroking || this.poked, sim);
      if (frame) {
        this.poked = false;
        frame.simMs = this.stepper.take();
        frame.accuracy = this.doc.takeAccuracy();
        const rec = this.recorder.status;
        if (rec) frame.recording = rec;
        this.post({ type: 'frame', frame });
      }
      this.lastTickError = '';
    } catch (e) {
      // Say it once, not every tick.
      const text = `the simulation stopped: ${errorText(e)}`;
      if (text !== this.lastTickError) this.message(text, 'error');
      this.lastTickError = text;
      this.doc.settings.playing = false;
    }
  }
}

function describe(cmd: Command): string {
  return cmd.type.replace(/[A-Z]/g, (c) => ` ${c.toLowerCase()}`);
}
