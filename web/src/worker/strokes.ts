// What a tool stroke does to the body, in the worker. The page's tools (src/tools/) pick the
// point and follow the pointer; these act on the engine every tick while the button is held:
// - grab: a target spring (SoftBody::set_targets, exact in the implicit step) from each vertex
//   under the brush to the cursor's point plus the vertex's offset, re-aimed every tick from the
//   latest cursor; strength: the pull's angular frequency ω (1/s), stiffness m w ω²;
// - press: a target spring on each vertex the brush passes over, to where it was when first
//   touched moved inward along its normal by the depth (the strength, m) × the brush weight
//   (Shift: outward); released with the button, so the dent springs back;
// - inflate / mass: rest lengths / masses grow (Shift: shrink) at a rate (1/s) under the brush;
// - pin: vertices under the brush are pinned (Shift: unpinned).

import type { StrokeTool, Vec3 } from '../protocol';
import type { BodyView } from '../engine/world';
import { inflateFactor, targetSpring, vertexNormals, verticesAround, type Weighted } from '../tools/brush';
import { reflect, reflections, type Symmetry } from '../tools/symmetry';
import { AnchorPath } from './anchorpath';

/** Pen pressure as a strength scale: (0, 1], 1 when not given (a mouse). */
function clampPressure(p: number | undefined): number {
  return p === undefined || !Number.isFinite(p) || p <= 0 ? 1 : Math.min(1, Math.max(0.05, p));
}

/** The anchors of a stroke moving within the tick (the grab's: `anchorpath.ts`), bound to its body. */
export interface Anchors {
  /** Before steps of `h` s: the anchors where the path is at their end. */
  aim(h: number): void;
  /** Steps of `h` s were taken (the path moves on). */
  took(h: number): void;
  /** Steps were taken: `newton` Newton iterations in the last (the most over the bodies); `split`: one had to be split. */
  stepped(newton: number, split: boolean): void;
}

/** What a stroke needs from the body (the document hands over its active body). */
export interface StrokeBody {
  /** The body's arrays (engine/world.ts): positions, masses, pins, the staging arrays. */
  readonly view: BodyView;
  /** User forces and face pressures from the staging arrays. */
  applyLoads(): void;
  /** Rest lengths × per-vertex factors. */
  scaleRest(factors: ArrayLike<number>): void;
  setMasses(masses: ArrayLike<number>): void;
  /** Pins from the `pinned` view as written. */
  setPins(): void;
  /** Target springs: records (vertex, anchor xyz, stiffness, damping); empty clears them. */
  setTargets(records: Float64Array): void;
}

export interface StrokeStart {
  tool: StrokeTool; point: Vec3; radius: number; strength: number; inverted: boolean;
  /** Mirror symmetry: the stroke also acts at the point's mirror images (tools/symmetry.ts). */
  mirror?: Symmetry;
  /** Pen pressure in (0, 1] scaling the strength (1: a mouse). */
  pressure?: number;
  /** The body it acts on (the one under the cursor; 0 if not given). */
  body?: number;
}

export abstract class Stroke {
  protected point: Vec3 | null;
  protected inverted: boolean;
  /** The strength scale from pen pressure, in (0, 1]. */
  protected pressure: number;
  /** Sign triples of the reflections the stroke acts through (the identity first). */
  protected readonly signs: Vec3[];
  protected readonly centre: Vec3;
  constructor(protected readonly s: StrokeStart) {
    this.point = s.point;
    this.inverted = s.inverted;
    this.pressure = clampPressure(s.pressure);
    this.signs = s.mirror ? reflections(s.mirror.axes) : [[1, 1, 1]];
    this.centre = s.mirror?.centre ?? [0, 0, 0];
  }
  /** The strength as the pen presses now. */
  protected get strength(): number { return this.s.strength * this.pressure; }
  /** The pen pressure changed (a move). */
  press(pressure: number | undefined): void { if (pressure !== undefined) this.pressure = clampPressure(pressure); }
  /**
   * The vertices within the brush of `point` and of its mirror images, with their falloff
   * weights (a vertex under two images keeps the larger weight), and for each the reflection
   * (index into `signs`) it was taken through.
   */
  protected around(x: ArrayLike<number>, point: Vec3, signs = this.signs): Weighted & { image: number[] } {
    const best = new Map<number, { w: number; image: number }>();
    signs.forEach((sg, image) => {
      const under = verticesAround(x, reflect(point, sg, this.centre), this.s.radius);
      under.indices.forEach((i, k) => {
        const had = best.get(i);
        if (!had || under.weights[k] > had.w) best.set(i, { w: under.weights[k], image });
      });
    });
    const out = { indices: [] as number[], weights: [] as number[], image: [] as number[] };
    for (const [i, { w, image }] of best) { out.indices.push(i); out.weights.push(w); out.image.push(image); }
    return out;
  }
  /** The undo step's name. */
  get label(): string { return this.s.tool; }
  /** The stroke begins (the document has remembered the state for undo). */
  abstract start(body: StrokeBody): void;
  move(point: Vec3 | null, inverted: boolean, _body: StrokeBody): void { this.point = point; this.inverted = inverted; }
  /** Every tick before the steps (dt: simulated seconds this tick, 0 when paused; step: the world's dt). */
  update(_body: StrokeBody, _dt: number, _step?: number): void {}
  /** Anchors that move along a path within the tick (the grab), as the document steps them (`Document.advance`). */
  path(_body: StrokeBody): Anchors | null { return null; }
  /** The body was put back (a rewind after a failed step): start again from where it is. */
  rebase(_body: StrokeBody): void {}
  abstract end(body: StrokeBody): void;
  /** Whether it changes masses or pins (which the page then needs again). */
  get paintsBodyData(): boolean { return false; }
}

class Grab extends Stroke {
  private picked: Weighted & { image: number[] } = { indices: [], weights: [], image: [] };
  /** Each picked vertex's offset from the (mirrored) grab point. */
  private offsets: number[] = [];
  private records = new Float64Array(0);
  /** Where the anchors are and where they head this tick (set at `start`). */
  private anchors = new AnchorPath([0, 0, 0], 1);
  /** The reflections this grab acts through: an image whose brush overlaps the grab's own is left out. */
  private images: Vec3[] = [[1, 1, 1]];
  start(body: StrokeBody): void {
    const x = body.view.positions, p = this.s.point;
    // A grab on (or within a brush radius of) the mirror plane would pull the same vertices
    // towards the cursor and towards its mirror image at once: it acts once, as without mirror.
    this.images = this.signs.filter((sg, k) => {
      const q = reflect(p, sg, this.centre);
      return k === 0 || Math.hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]) >= 2 * this.s.radius;
    });
    this.picked = this.around(x, p, this.images);
    this.offsets = this.picked.indices.flatMap((i, k) => {
      const q = reflect(p, this.images[this.picked.image[k]], this.centre);
      return [x[3 * i] - q[0], x[3 * i + 1] - q[1], x[3 * i + 2] - q[2]];
    });
    this.records = new Float64Array(6 * this.picked.indices.length);
    this.anchors = new AnchorPath(p, this.s.radius);
    this.set(body, p);
  }
  /** The cursor moved: `point` is its point on the grab plane (null keeps the last one). */
  move(point: Vec3 | null): void { if (point) this.point = point; }
  /** The anchors head for the cursor over this tick (`anchorpath.ts`); set where they are now. */
  update(body: StrokeBody, dt: number, step = dt): void {
    this.anchors.aim(this.point ?? this.s.point, dt, step);
    this.set(body, this.anchors.point);
  }
  path(body: StrokeBody): Anchors {
    const a = this.anchors;
    return { aim: (h) => this.set(body, a.next(h)), took: (h) => a.took(h), stepped: (newton, split) => a.stepped(newton, split) };
  }
  /** The grab point where the grabbed vertices are (those taken without a reflection: x − offset). */
  rebase(body: StrokeBody): void {
    const x = body.view.positions, c = [0, 0, 0];
    let n = 0;
    this.picked.indices.forEach((i, k) => {
      if (this.picked.image[k] !== 0) return;
      for (let d = 0; d < 3; d++) c[d] += x[3 * i + d] - this.offsets[3 * k + d];
      n++;
    });
    if (n === 0) return;
    this.anchors.rebase([c[0] / n, c[1] / n, c[2] / n]);
    this.set(body, this.anchors.point);
  }
  /** The target springs with the grab point at `cursor`. */
  private set(body: StrokeBody, cursor: Vec3): void {
    const m = body.view.masses, r = this.records;
    // Each image of the cursor pulls the vertices taken through that image (mirrored drags).
    const images = this.images.map((sg) => reflect(cursor, sg, this.centre));
    this.picked.indices.forEach((i, k) => {
      const c = images[this.picked.image[k]];
      const t = targetSpring(m[i], this.picked.weights[k], this.strength);
      r.set([i, c[0] + this.offsets[3 * k], c[1] + this.offsets[3 * k + 1], c[2] + this.offsets[3 * k + 2], t.stiffness, t.damping], 6 * k);
    });
    body.setTargets(r);
  }
  end(body: StrokeBody): void { body.setTargets(new Float64Array(0)); }
}

/** Stiffness of the press's springs as an angular frequency (1/s): the dent forms in ~1/ω s. */
export const PRESS_OMEGA = 200;

class Press extends Stroke {
  /** Anchor and weight of every vertex the brush has touched, by vertex. */
  private anchors = new Map<number, { a: Vec3; w: number }>();
  start(body: StrokeBody): void { this.apply(body); }
  move(point: Vec3 | null, inverted: boolean, body: StrokeBody): void {
    if (!point) return;
    super.move(point, inverted, body);
    this.apply(body);
  }
  private apply(body: StrokeBody): void {
    const x = body.view.positions;
    const under = this.around(x, this.point!);
    const fresh = under.indices.filter((i) => !this.anchors.has(i));
    if (fresh.length === 0 && this.anchors.size > 0) return;
    const n = vertexNormals(x, body.view.triangles);
    const depth = this.inverted ? -this.strength : this.strength;
    under.indices.forEach((i, k) => {
      if (this.anchors.has(i)) return;
      const w = under.weights[k];
      this.anchors.set(i, { a: [0, 1, 2].map((d) => x[3 * i + d] - depth * w * n[3 * i + d]) as Vec3, w });
    });
    const m = body.view.masses, r = new Float64Array(6 * this.anchors.size);
    let k = 0;
    for (const [i, { a, w }] of this.anchors) {
      const t = targetSpring(m[i], w, PRESS_OMEGA);
      r.set([i, a[0], a[1], a[2], t.stiffness, t.damping], 6 * k++);
    }
    body.setTargets(r);
  }
  end(body: StrokeBody): void { body.setTargets(new Float64Array(0)); }
}

/** The brushes act every tick on the vertices under the centre while the button is held. */
abstract class Paint extends Stroke {
  protected abstract paint(body: StrokeBody, w: Weighted, dt: number): void;
  start(body: StrokeBody): void { this.update(body, 0); }
  update(body: StrokeBody, dt: number): void {
    if (!this.point) return;
    const w = this.around(body.view.positions, this.point);
    if (w.indices.length > 0) this.paint(body, w, dt);
  }
  end(): void {}
}

class Inflate extends Paint {
  private factors = new Float64Array(0);
  protected paint(body: StrokeBody, w: Weighted, dt: number): void {
    if (dt <= 0) return;
    if (this.factors.length !== body.view.vertexCount) this.factors = new Float64Array(body.view.vertexCount);
    const factors = this.factors.fill(1);
    w.indices.forEach((i, k) => (factors[i] = inflateFactor(w.weights[k], this.strength, dt, this.inverted)));
    body.scaleRest(factors);
  }
}

class Mass extends Paint {
  get paintsBodyData(): boolean { return true; }
  protected paint(body: StrokeBody, w: Weighted, dt: number): void {
    if (dt <= 0) return;
    const m = body.view.masses.slice();
    w.indices.forEach((i, k) => {
      const f = inflateFactor(w.weights[k], this.strength, dt, this.inverted);
      m[i] = Math.min(Math.max(m[i] * f, 1e-9), 1e9);
    });
    body.setMasses(m);
  }
}

class Pin extends Paint {
  get paintsBodyData(): boolean { return true; }
  protected paint(body: StrokeBody, w: Weighted): void {
    const pinned = body.view.pinned;
    let changed = false;
    for (const i of w.indices) {
      if ((pinned[i] === 1) === this.inverted) { pinned[i] = this.inverted ? 0 : 1; changed = true; }
    }
    if (changed) body.setPins();
  }
}

const KINDS: Record<StrokeTool, new (s: StrokeStart) => Stroke> = { grab: Grab, press: Press, inflate: Inflate, mass: Mass, pin: Pin };

export function makeStroke(s: StrokeStart): Stroke {
  return new KINDS[s.tool](s);
}
