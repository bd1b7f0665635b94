// The painting brushes: they act every frame on the vertices under the cursor while the button is
// held, and Shift inverts them.
// - Inflate (I): lengthen the rest lengths (Shift: shorten); strength = rate (1/s).
// - Mass (M): make vertices heavier (Shift: lighter) to localise deformation; strength = rate (1/s).
// - Pin (N): pin vertices so they never move (Shift: unpin).

import type * as THREE from 'three';
import type { SoftBody } from '../engine/softbody';
import { BaseTool, point } from './tool';
import { inflateFactor, verticesAround } from './brush';

abstract class PaintTool extends BaseTool {
  private centre: [number, number, number] | null = null;
  protected abstract paint(body: SoftBody, indices: number[], weights: number[], dt: number): void;

  start(hit: THREE.Intersection, ev: PointerEvent): boolean {
    super.start(hit, ev);
    this.ctx!.beginEdit(this.name);
    this.centre = point(hit.point);
    this.apply(0);
    return true;
  }

  move(ev: PointerEvent): void {
    if (!this.dragging || !this.ctx) return;
    this.inverted = ev.shiftKey;
    const hit = this.ctx.viewport.pick(ev);
    this.centre = hit ? point(hit.point) : null;
  }

  update(dt: number): void {
    if (this.dragging) this.apply(dt);
  }

  private apply(dt: number): void {
    if (!this.ctx || !this.centre) return;
    const body = this.ctx.body();
    const w = verticesAround(body.positions(), this.centre, this.ctx.brush.radius);
    if (w.indices.length > 0) this.paint(body, w.indices, w.weights, dt);
    this.ctx.refreshOverlay();
  }

  end(): void {
    if (!this.dragging || !this.ctx) return;
    super.end();
    this.centre = null;
    this.ctx.endEdit();
  }
}

export class InflateTool extends PaintTool {
  readonly name = 'inflate';
  readonly label = 'Inflate';
  readonly key = 'i';
  readonly tooltip = 'Inflate (I): lengthen rest lengths under the brush; Shift deflates (strength = rate, 1/s)';
  strength = 0.3;
  readonly strengthInfo = { label: 'growth rate (1/s)', min: 0.01, max: 3 };
  private factors = new Float64Array(0);
  protected paint(body: SoftBody, indices: number[], weights: number[], dt: number): void {
    if (dt <= 0) return;
    if (this.factors.length !== body.vertexCount) this.factors = new Float64Array(body.vertexCount);
    const factors = this.factors.fill(1);
    indices.forEach((i, k) => (factors[i] = inflateFactor(weights[k], this.strength, dt, this.inverted)));
    body.scaleRestByVertex(factors);
  }
}

export class MassTool extends PaintTool {
  readonly name = 'mass';
  readonly label = 'Mass';
  readonly key = 'm';
  readonly tooltip = 'Mass (M): paint vertices heavier so they move less; Shift paints lighter (strength = rate, 1/s)';
  strength = 2;
  readonly strengthInfo = { label: 'mass rate (1/s)', min: 0.1, max: 20 };
  protected paint(body: SoftBody, indices: number[], weights: number[], dt: number): void {
    if (dt <= 0) return;
    const m = body.masses().slice();
    indices.forEach((i, k) => {
      const f = inflateFactor(weights[k], this.strength, dt, this.inverted);
      m[i] = Math.min(Math.max(m[i] * f, 1e-9), 1e9);
    });
    body.setMasses(m);
  }
  overlay(colors: Float32Array, body: SoftBody): void {
    const m = body.masses();
    const mean = m.reduce((a, b) => a + b, 0) / m.length;
    for (let i = 0; i < m.length; i++) {
      // log2(m / mean) in [−3, 3] → blue (light) .. white .. red (heavy).
      const t = Math.max(-1, Math.min(1, Math.log2(m[i] / mean) / 3));
      colors.set(t >= 0 ? [1, 1 - t, 1 - t] : [1 + t, 1 + t, 1], 3 * i);
    }
  }
}

export class PinTool extends PaintTool {
  readonly name = 'pin';
  readonly label = 'Pin';
  readonly key = 'n';
  readonly tooltip = 'Pin (N): pin the vertices under the brush so they never move; Shift unpins';
  strength = 0;
  readonly strengthInfo = null;
  protected paint(body: SoftBody, indices: number[]): void {
    const pinned = body.pinned();
    for (const i of indices) if ((pinned[i] === 1) === this.inverted) body.setPinned(i, !this.inverted);
  }
  overlay(colors: Float32Array, body: SoftBody): void {
    const p = body.pinned();
    for (let i = 0; i < p.length; i++) colors.set(p[i] ? [0.9, 0.15, 0.15] : [0.85, 0.85, 0.85], 3 * i);
  }
}
