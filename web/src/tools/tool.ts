// Every interaction tool has the same small lifecycle (as three.js controls): connect when it
// becomes the active tool, disconnect when another takes over, dispose at the end; and
// start/move/end for a drag on the body (the camera is disabled while a tool drags).
// The tools run on the page: they pick and follow the pointer and send the stroke to the
// simulation worker (`strokeStart`, `strokeMove`, `strokeEnd`), which acts on the body every
// tick (worker/strokes.ts).

import type * as THREE from 'three';
import type { Command, StrokeTool, Vec3 } from '../protocol';
import type { Viewport } from '../view/viewport';
import type { Symmetry } from './symmetry';
import { sig3 } from '../format';
import { bodyOf, pickBody } from './pick';

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

/** The body as last drawn, for picking and overlays. */
export interface BodyView {
  /** xyz per vertex (m). */
  positions: Float32Array;
  masses: Float64Array;
  pinned: Uint8Array;
}

export interface ToolContext {
  readonly viewport: Viewport;
  readonly brush: Brush;
  body(): BodyView;
  /** Send a stroke command to the simulation. */
  send(cmd: Command): void;
  /** Mirror symmetry for a stroke starting now on body `k` (undefined: off). */
  symmetry(k?: number): Symmetry | undefined;
  /** Body `k`'s positions as drawn (the pieces of an import, a scene's bodies). */
  positionsOf?(k: number): ArrayLike<number>;
  /** Tell the user something (why a tool did nothing). */
  message(text: string, kind?: 'info' | 'warn' | 'error'): void;
}

/** A pen's pressure in (0, 1] (it scales the tool's strength); a mouse or a finger: undefined (full). */
export function penPressure(ev: PointerEvent): number | undefined {
  return ev.pointerType === 'pen' && ev.pressure > 0 ? ev.pressure : undefined;
}

export interface Tool {
  readonly name: StrokeTool | 'sketch';
  readonly label: string;
  readonly key: string;
  readonly tooltip: string;
  /** The tool's strength (unit in `strengthInfo`), or null if it has none. */
  strength: number;
  readonly strengthInfo: Strength | null;
  /** The strength is a length (m): it follows the model's size (tools/scale.ts). */
  readonly isLength?: boolean;
  connect(ctx: ToolContext): void;
  disconnect(): void;
  dispose(): void;
  /** The tool's drag may start off the body (`start` then gets no hit). */
  readonly anywhere?: boolean;
  /**
   * Why a press at `hit` can do nothing (no vertex under the brush), or null. The press is then
   * the tool's all the same (the view does not turn), the reason is shown and nothing is sent.
   */
  refusal?(hit: THREE.Intersection): string | null;
  /** Pointer pressed on the body (or anywhere, for `anywhere` tools): return true to take the drag. */
  start(hit: THREE.Intersection | null, ev: PointerEvent): boolean;
  move(ev: PointerEvent): void;
  end(): void;
  /** Colour overlay while the tool is active, or null. */
  overlay?(colors: Float32Array, body: BodyView): void;
}

/**
 * Base with the shared plumbing: a stroke starts at the picked point and, by default, follows the
 * surface point under the pointer (press and the brushes); tools override what they need.
 */
export abstract class BaseTool implements Tool {
  abstract readonly name: StrokeTool;
  abstract readonly label: string;
  abstract readonly key: string;
  abstract readonly tooltip: string;
  abstract strength: number;
  abstract readonly strengthInfo: Strength | null;
  protected ctx: ToolContext | null = null;
  protected dragging = false;
  /** Modifier (Shift) inverts the brush: deflate, lighter, unpin. */
  protected inverted = false;
  /** The body the stroke acts on: the one picked when it began (tools/pick.ts). */
  protected body = 0;

  connect(ctx: ToolContext): void { this.ctx = ctx; }
  disconnect(): void { if (this.dragging) this.end(); this.ctx = null; }
  dispose(): void { this.disconnect(); }

  /**
   * A brush with no vertex within its radius of the pressed point would act on nothing and leave
   * an empty undo step (a small brush on a coarse mesh): say so, with the distance to enlarge it to.
   */
  refusal(hit: THREE.Intersection): string | null {
    const ctx = this.ctx!;
    const x = ctx.positionsOf?.(bodyOf(hit)) ?? ctx.body().positions, p = hit.point, r = ctx.brush.radius;
    let nearest = Infinity;
    for (let i = 0; i < x.length; i += 3) nearest = Math.min(nearest, Math.hypot(x[i] - p.x, x[i + 1] - p.y, x[i + 2] - p.z));
    if (nearest < r) return null;
    return `no vertex under the brush (radius ${sig3(r)} m, the nearest is ${sig3(nearest)} m away) — enlarge it with ] or B, or Subdivide (U)`;
  }

  start(hit: THREE.Intersection | null, ev: PointerEvent): boolean {
    const ctx = this.ctx!;
    if (!hit) return false;
    this.inverted = ev.shiftKey;
    this.dragging = true;
    this.body = bodyOf(hit);
    ctx.send({ type: 'strokeStart', tool: this.name, point: point(hit.point), radius: ctx.brush.radius, strength: this.strength, inverted: this.inverted,
      mirror: ctx.symmetry(this.body), pressure: penPressure(ev), body: this.body });
    return true;
  }

  move(ev: PointerEvent): void {
    if (!this.dragging || !this.ctx) return;
    this.inverted = ev.shiftKey;
    const hit = pickBody(this.ctx.viewport, ev, this.body);
    this.ctx.send({ type: 'strokeMove', point: hit ? point(hit.point) : null, inverted: this.inverted, pressure: penPressure(ev) });
  }

  end(): void {
    if (!this.dragging) return;
    this.dragging = false;
    this.ctx?.send({ type: 'strokeEnd' });
  }
}

export function point(v: THREE.Vector3): Vec3 {
  return [v.x, v.y, v.z];
}
