// Every interaction tool has the same small lifecycle (as three.js controls): connect when it
// becomes the active tool, disconnect when another takes over, dispose at the end, update every
// frame; and start/move/end for a drag on the body (the camera is disabled while a tool drags).

import type * as THREE from 'three';
import type { SoftBody } from '../engine/softbody';
import type { Viewport } from '../view/viewport';

export interface Brush {
  /** Radius of the brush (m), shared by the tools. */
  radius: number;
}

/** What a tool's strength means: its unit and slider range. */
export interface Strength {
  label: string;
  min: number;
  max: number;
}

export interface ToolContext {
  body(): SoftBody;
  readonly viewport: Viewport;
  readonly brush: Brush;
  /** An operation that changes the model is about to begin: remember the state for undo. */
  beginEdit(label: string): void;
  /** The operation ended (pushes the undo entry and autosaves). */
  endEdit(): void;
  /** The tool changed what an overlay shows. */
  refreshOverlay(): void;
}

export interface Tool {
  readonly name: string;
  readonly label: string;
  readonly key: string;
  readonly tooltip: string;
  /** The tool's strength (unit in `strengthInfo`), or null if it has none. */
  strength: number;
  readonly strengthInfo: Strength | null;
  connect(ctx: ToolContext): void;
  disconnect(): void;
  dispose(): void;
  /** Every frame, before the simulation steps (dt: simulated seconds this frame). */
  update(dt: number): void;
  /** Pointer pressed on the body: return true to take the drag. */
  start(hit: THREE.Intersection, ev: PointerEvent): boolean;
  move(ev: PointerEvent): void;
  end(): void;
  /** Colour overlay while the tool is active, or null. */
  overlay?(colors: Float32Array, body: SoftBody): void;
}

/** Base with the shared plumbing; tools override what they need. */
export abstract class BaseTool implements Tool {
  abstract readonly name: string;
  abstract readonly label: string;
  abstract readonly key: string;
  abstract readonly tooltip: string;
  abstract strength: number;
  abstract readonly strengthInfo: Strength | null;
  protected ctx: ToolContext | null = null;
  protected dragging = false;
  /** Modifier (Shift) inverts the brush: deflate, lighter, unpin. */
  protected inverted = false;

  connect(ctx: ToolContext): void { this.ctx = ctx; }
  disconnect(): void { if (this.dragging) this.end(); this.ctx = null; }
  dispose(): void { this.disconnect(); }
  update(_dt: number): void {}
  start(_hit: THREE.Intersection, ev: PointerEvent): boolean { this.inverted = ev.shiftKey; this.dragging = true; return true; }
  move(_ev: PointerEvent): void {}
  end(): void { this.dragging = false; }
}

export function point(v: THREE.Vector3): [number, number, number] {
  return [v.x, v.y, v.z];
}
