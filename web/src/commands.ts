// The page's operations, each a command to the worker (src/protocol.ts): what the panel, the
// keys and the inspector call. A modeling operation waits while a long one is under way (it says
// so); settings change in the mirror at once. The page (app.ts `App`) is the one subclass: it
// brings the link to the worker, the mirror, the view, the tools and the messages.

import type { Command, MessageKind, ParamValue, Settings, UiState } from './protocol';
import type { Mirror } from './mirror';
import type { Viewport } from './view/viewport';
import type { ToolManager } from './tools/manager';
import { download, exportShape, type ExportFormat } from './io/export';
import { rememberedUp, rememberUp } from './io/upaxis';
import { baseName } from './project';
import { sig3 } from './format';
import { acrossView, alongView } from './tools/wind';
import type { ParamId } from './engine/params';

export abstract class Commands {
  abstract readonly mirror: Mirror;
  abstract readonly viewport: Viewport;
  abstract readonly tools: ToolManager;
  /** The long operation under way in the worker ("subdividing"…), or null. */
  abstract get busy(): string | null;
  abstract send(cmd: Command, transfer?: Transferable[]): void;
  abstract message(text: string, kind?: MessageKind, sticky?: boolean): void;
  /** The page's tool state (kept in project files and the autosave). */
  abstract ui(): UiState;

  /** Send a modeling operation, unless a long one is still running (then say so). */
  protected operate(cmd: Command, transfer: Transferable[] = []): void {
    if (this.busy) { this.message(`still ${this.busy}… try again when it is done`, 'warn'); return; }
    this.send(cmd, transfer);
  }

  // ----- models, files and scenes ---------------------------------------------------------------

  loadBuiltin(name: string): void { this.operate({ type: 'loadBuiltin', name }); }
  importFile(name: string, data: ArrayBuffer): void { this.operate({ type: 'import', name, data, upAnswers: rememberedUp() }, [data]); }
  /** Turn the imported model to another up axis (a wrong guess fixed), remembered for its file. */
  setUpAxis(up: 'y' | 'z'): void {
    const frame = this.mirror.settings.frame;
    rememberUp(frame?.file, frame?.format, up);
    this.operate({ type: 'setUp', up });
  }
  openProjectFile(name: string, text: string): void { this.operate({ type: 'openProject', name, text }); }
  openScene(name: string, text: string, files: Map<string, Uint8Array>): void { this.operate({ type: 'openScene', name, text, files }); }
  restartScene(): void { this.operate({ type: 'restartScene' }); }
  saveScene(): void { this.send({ type: 'saveScene' }); }
  saveProject(): void { this.send({ type: 'saveProject', ui: this.ui() }); }

  /** Download the shapes as drawn (every body), in the imported file's units and frame. */
  async export(format: ExportFormat): Promise<void> {
    const shapes = this.mirror.shapes();
    const blob = await exportShape(format, shapes, undefined, this.mirror.settings.frame);
    const name = `${baseName(this.mirror.settings.model)}.${format}`;
    download(blob, name);
    // What the file holds: every body (a new-user trial saw one body's counts for a file of two).
    const vertices = shapes.reduce((n, s) => n + s.positions.length / 3, 0);
    const faces = shapes.reduce((n, s) => n + s.triangles.length / 3, 0);
    const bodies = shapes.length > 1 ? ` in ${shapes.length} bodies` : '';
    this.message(`exported ${name}: ${vertices} vertices, ${faces} faces${bodies} (${sig3(blob.size / 1024)} KB, in your downloads)`);
  }
  /** Start or stop recording (io: worker/recorder.ts); export the recording as GLB morph targets. */
  record(on = !this.mirror.recording): void { this.send({ type: 'record', on }); }
  exportRecording(): void { this.send({ type: 'exportRecording' }); }

  // ----- modeling -------------------------------------------------------------------------------

  freeze(): void { this.operate({ type: 'freeze' }); }
  reset(): void { this.operate({ type: 'reset' }); }
  subdivide(): void { this.operate({ type: 'subdivide' }); }
  remesh(): void { this.operate({ type: 'remesh' }); }
  undo(): void { if (!this.tools.isDragging) this.operate({ type: 'undo' }); }
  redo(): void { if (!this.tools.isDragging) this.operate({ type: 'redo' }); }

  // ----- the simulation -------------------------------------------------------------------------

  step(): void { this.send({ type: 'step' }); }
  /** Set a parameter by its table id (see `mirror.table`). */
  setParam(name: ParamId, value: ParamValue): void { this.send({ type: 'setParam', name, value }); }
  setMass(total: number): void { this.send({ type: 'setMass', total }); }
  /** Change settings (play, dt, real time, steps per frame); the mirror follows at once. */
  setSettings(patch: Partial<Settings>): void {
    Object.assign(this.mirror.settings, patch);
    this.send({ type: 'settings', patch });
  }
  togglePlaying(): void {
    this.setSettings({ playing: !this.mirror.settings.playing });
    this.message(this.mirror.settings.playing ? 'playing' : 'paused');
  }

  /** Wind blowing along the current view direction at `strength` m/s (0: calm); undoable. */
  windFromView(strength: number): void {
    this.send({ type: 'wind', direction: alongView(this.viewport.camera), strength });
  }
  /**
   * Wind blowing across the view, level, from the screen's left to its right (tools/wind.ts
   * `acrossView`) at `strength` m/s (0: calm); undoable. What W does: the lean shows.
   */
  windAcrossView(strength: number): void {
    this.send({ type: 'wind', direction: acrossView(this.viewport.camera), strength });
  }
  /** The wind at `strength` m/s, blowing where it blows now (from calm: across the view). */
  setWindStrength(strength: number): void {
    const w = this.wind, s = Math.hypot(...w);
    if (s > 0) this.send({ type: 'wind', direction: [w[0] / s, w[1] / s, w[2] / s], strength });
    else this.windAcrossView(strength);
  }
  get windStrength(): number {
    return Math.hypot(...this.wind);
  }
  /** The wind velocity (m/s). */
  get wind(): [number, number, number] {
    const w = this.mirror.params.wind;
    return Array.isArray(w) ? w : [0, 0, 0];
  }
}
