// The brush under the cursor: the ring (view/ring.ts) follows the pointer over the surface and
// shows the brush radius, the active tool's strength and the mirror images; and the brush's two
// sizes are set on keys or by dragging (as Blender's F and Shift+F):
//   [ / ]   radius smaller / larger (×1.2)      { / } (Shift+[ ])   strength smaller / larger
//   B       move the mouse to set the radius    Shift+B   … the strength; click or Enter sets it,
//           Esc or a right click puts it back. The value follows exp(Δx / 150 px): 150 px right
//           is ×e, left ÷e, so one gesture spans any range.

import * as THREE from 'three';
import type { Tool, ToolContext } from './tool';
import { reflect, reflectVector, reflections, type Symmetry } from './symmetry';
import { BrushRing } from '../view/ring';
import { brushUnit } from './scale';
import { bodyOf, pickBody } from './pick';

/** The brush radius's limits on keys and B (m) for a model of unit 1 m (tools/scale.ts). */
export const RADIUS_MIN = 0.02;
export const RADIUS_MAX = 3;
const ADJUST_PX = 150;

/** A brush radius within its limits at the current model's unit. */
export function clampRadius(r: number): number {
  const u = brushUnit.unit;
  return Math.min(RADIUS_MAX * u, Math.max(RADIUS_MIN * u, r));
}

/** Where a strength lies in its range, in [0, 1]: log scale for ranges over a decade (the grab's 1–3000 1/s). */
export function strengthFraction(t: Tool): number | null {
  const i = t.strengthInfo;
  if (!i) return null;
  if (i.min > 0 && i.max / i.min > 10) return Math.log(t.strength / i.min) / Math.log(i.max / i.min);
  return (t.strength - i.min) / (i.max - i.min);
}

export function clampStrength(t: Tool, v: number): number {
  const i = t.strengthInfo;
  return i ? Math.min(i.max, Math.max(i.min, v)) : v;
}

interface Adjusting { what: 'radius' | 'strength'; x0: number; start: number; tool: Tool }

export class BrushCursor {
  readonly ring = new BrushRing();
  private last: { clientX: number; clientY: number } | null = null;
  private moved = false;
  adjusting: Adjusting | null = null;

  constructor(private readonly ctx: ToolContext & { tools: { tool: Tool; isDragging: boolean } }, private readonly changed: (text: string | null) => void) {
    ctx.viewport.scene.add(this.ring.group);
    const canvas = ctx.viewport.canvas;
    canvas.addEventListener('pointermove', (ev) => { this.last = ev; this.moved = true; this.adjustTo(ev.clientX); });
    canvas.addEventListener('pointerleave', () => { this.last = null; this.moved = true; });
    // Capture phase on the window (before the tools' and the camera's listeners on the canvas):
    // a click while adjusting sets the value and is nobody else's.
    window.addEventListener('pointerdown', (ev) => {
      if (!this.adjusting || ev.target !== canvas) return;
      ev.stopImmediatePropagation();
      ev.preventDefault();
      this.finishAdjust(ev.button !== 2);
    }, { capture: true });
  }

  /** Start setting the radius or the strength with the mouse (B / Shift+B). */
  startAdjust(what: 'radius' | 'strength'): void {
    const tool = this.ctx.tools.tool;
    if (what === 'strength' && !tool.strengthInfo) { this.changed(`the ${tool.label.toLowerCase()} has no strength`); return; }
    const x0 = this.last?.clientX ?? this.ctx.viewport.canvas.clientWidth / 2;
    this.adjusting = { what, x0, start: what === 'radius' ? this.ctx.brush.radius : tool.strength, tool };
    this.describe();
  }

  private adjustTo(x: number): void {
    const a = this.adjusting;
    if (!a) return;
    const v = a.start * Math.exp((x - a.x0) / ADJUST_PX);
    if (a.what === 'radius') this.ctx.brush.radius = clampRadius(v);
    else a.tool.strength = clampStrength(a.tool, v);
    this.describe();
  }

  private describe(): void {
    const a = this.adjusting;
    if (!a) return;
    const value = a.what === 'radius' ? `brush radius ${this.ctx.brush.radius.toPrecision(3)} m` : `${a.tool.strengthInfo!.label} ${a.tool.strength.toPrecision(3)}`;
    this.changed(`${value} — move the mouse; click or Enter sets it, Esc puts it back`);
    this.moved = true;
  }

  /** Set (true) or put back (false) the value being adjusted. */
  finishAdjust(keep: boolean): void {
    const a = this.adjusting;
    if (!a) return;
    this.adjusting = null;
    if (!keep) {
      if (a.what === 'radius') this.ctx.brush.radius = a.start; else a.tool.strength = a.start;
    }
    this.changed(null);
    this.moved = true;
  }

  /** Redraw the ring if the pointer, the brush or the body moved (every animation frame). */
  update(bodyMoved: boolean): void {
    if (!this.moved && !bodyMoved) return;
    this.moved = false;
    const v = this.ctx.viewport;
    const hit = this.last && !this.ctx.tools.isDragging ? pickBody(v, this.last) : null;
    if (!hit || !hit.face) {
      if (this.ring.shown) { this.ring.hide(); v.invalidate(); }
      return;
    }
    const sym: Symmetry | undefined = this.ctx.symmetry(bodyOf(hit));
    const signs = sym ? reflections(sym.axes) : [[1, 1, 1] as [number, number, number]];
    const centre = sym?.centre ?? [0, 0, 0];
    const p = hit.point, n = hit.face.normal;
    const points = signs.map((s) => new THREE.Vector3(...reflect([p.x, p.y, p.z], s, centre as [number, number, number])));
    const normals = signs.map((s) => new THREE.Vector3(...reflectVector([n.x, n.y, n.z], s)));
    // A body is symmetric only up to about an edge (and less once deformed): a mirror image of
    // the point under the cursor can sit off the surface. Each copy goes onto the surface along
    // its normal (the nearest hit within a brush radius), as the stroke's copies act there.
    for (let i = 1; i < points.length; i++) onSurface(hit.object, points[i], normals[i], this.ctx.brush.radius);
    this.ring.show(points, normals, this.ctx.brush.radius, strengthFraction(this.ctx.tools.tool));
    v.invalidate();
  }

  /** The brush or strength changed from elsewhere (keys, panel). */
  poke(): void { this.moved = true; }
}

/** Scratch for `onSurface` (called as the pointer moves: no allocation). */
const ray = new THREE.Raycaster();
const along = new THREE.Vector3();
const from = new THREE.Vector3();

/**
 * Move `p` (with its normal `n`) onto `mesh`'s surface: the nearer of the hits of the line
 * through p along n within `reach` either way; unchanged if there is none.
 */
function onSurface(mesh: THREE.Object3D, p: THREE.Vector3, n: THREE.Vector3, reach: number): void {
  along.copy(n).normalize();
  from.copy(p).addScaledVector(along, reach);
  ray.set(from, along.negate());
  ray.far = 2 * reach;
  const hits = ray.intersectObject(mesh, false);
  let best: THREE.Intersection | null = null;
  for (const h of hits) if (!best || Math.abs(h.distance - reach) < Math.abs(best.distance - reach)) best = h;
  if (!best?.face) return;
  p.copy(best.point);
  n.copy(best.face.normal);
}
