// The grab's anchors along the cursor's path (src/worker/anchorpath.ts), on model worlds whose
// Newton counts follow what was measured natively on the page's stiff-rubber sphere
// (BENCHMARKS.md): a step of h takes more Newton iterations the larger (h / dt)², and an anchor
// jump beyond what one step can take does not converge. Then the document's frames on the real
// engine (`World::advance`: the core splits a refused step, crates/softsculpt/src/world/advance.rs).
import { beforeAll, describe, expect, it } from 'vitest';
import { AnchorPath, TRAVEL_MAX } from '../src/worker/anchorpath';
import { SPLITS } from '../src/worker/document';
import { loadEngine, openedDocument, topVertex, vertexAt } from './setup';
import type { Vec3 } from '../src/protocol';
import { makeStroke, type Anchors, type StrokeBody } from '../src/worker/strokes';

const DT = 1 / 60;
const unconverged = () => Object.assign(new Error('not converged'), { kind: 'step', fields: { converged: false } });

/**
 * A model world: a step of h takes `base + stiff (h/DT)²` Newton iterations (the mass term
 * m / h² against the skin's non-convexity: 4× smaller per halving), and does not converge if
 * that is over 100 or if the anchors moved more than `jump` (m) in it. Tracks simulated time.
 */
function world(stiff: number, base = 2, jump = Infinity) {
  const w = { time: 0, steps: [] as number[], anchor: 0, moved: 0, fails: 0 };
  const step = (h: number) => {
    const n = Math.round(base + stiff * (h / DT) ** 2);
    if (n > 100 || w.moved > jump) { w.fails++; w.moved = 0; throw unconverged(); }
    w.time += h;
    w.steps.push(h);
    w.moved = 0;
    return n;
  };
  return { w, step };
}

/**
 * A frame of one step of `h` as the document takes it (`Document.advance` over the core's
 * `World::advance`): the anchors aimed at the frame's end, a refused step halved up to
 * SPLITS times (the anchors where they are), then the path moved on. Returns the splits.
 */
function frame(anchors: Anchors | null, step: (h: number) => number, h: number): number {
  anchors?.aim(h);
  let newton = 0;
  const take = (k: number, depth: number): number => {
    try { newton = step(k); return 0; } catch (e) { if (depth <= 0) throw e; }
    return 1 + take(k / 2, depth - 1) + take(k / 2, depth - 1);
  };
  const splits = take(h, SPLITS);
  anchors?.took(h);
  anchors?.stepped(newton, splits > 0);
  return splits;
}

/** The grab's path on a line (x only), wired to a model world's anchor. */
function along(path: AnchorPath, w: { anchor: number; moved: number }): Anchors {
  return {
    aim: (h) => { const x = path.next(h)[0]; w.moved += Math.abs(x - w.anchor); w.anchor = x; },
    took: (h) => path.took(h),
    stepped: (newton, split) => path.stepped(newton, split),
  };
}

describe('the grab’s anchors', () => {
  const R = 0.35;

  it('travel at most `travel` a step towards the cursor and arrive on it', () => {
    // A model world where no step converges with the anchors moved more than 5 cm in it and
    // 30 Newton iterations a step at dt (so the substeps double once).
    const { w, step } = world(28, 2, 0.05);
    const path = new AnchorPath([0, 0, 0], R);
    const cursor: Vec3 = [0.56, 0, 0];
    let last = 0, over = 0;
    for (let i = 0; i < 40; i++) {
      const most = path.travel;
      path.aim(cursor, DT, DT);
      frame(along(path, w), step, DT);
      if (path.point[0] - last > most + 1e-12) over++;
      last = path.point[0];
    }
    expect(over).toBe(0);
    expect(path.point[0]).toBeCloseTo(0.56, 12);
    // The travel grows while the steps are quick and halves when one is refused: at most a few
    // refusals on the way.
    expect(w.fails).toBeLessThanOrEqual(3);
    // The whole 56 cm in one step is refused (the split halves take it, the anchors moved once).
    const jump = world(28, 2, 0.05);
    expect(frame({ aim: () => { jump.w.moved = 0.56; }, took: () => {}, stepped: () => {} }, jump.step, DT)).toBe(1);
    expect(jump.w.fails).toBe(1);
  });

  it('on a soft body soon follow the cursor within the step', () => {
    const { w, step } = world(2, 1);
    const path = new AnchorPath([0, 0, 0], R);
    let x = 0, lagged = 0;
    for (let i = 0; i < 60; i++) {
      x += 0.1; // 6 m/s: 10 cm a frame, more than the first travel (4.4 cm)
      path.aim([x, 0, 0], DT, DT);
      frame(along(path, w), step, DT);
      if (path.point[0] < x - 1e-12) lagged++;
    }
    // The travel doubles every step that held the anchors back (4.4, 8.8, 17.5 cm): two frames
    // of lag, then none.
    expect(path.travel).toBeGreaterThanOrEqual(0.1);
    expect(path.travel).toBeLessThanOrEqual(TRAVEL_MAX * R);
    expect(lagged).toBeLessThanOrEqual(3);
  });
});

describe('a grab after a rewind', () => {
  it('starts again from where its vertices were put back, their offsets kept', () => {
    const positions = new Float64Array([0, 0, 0, 0.1, 0, 0, 5, 0, 0]);
    let targets = new Float64Array(0);
    const body = { view: { positions, masses: new Float64Array([1, 1, 1]) }, setTargets: (r: Float64Array) => { targets = r.slice(); } } as unknown as StrokeBody;
    const grab = makeStroke({ tool: 'grab', point: [0, 0, 0], radius: 0.5, strength: 600, inverted: false });
    grab.start(body);
    grab.move([1, 0, 0], false, body);
    grab.update(body, DT, DT);
    // A step along the path (the anchors 1/8 of the brush on), then the world is put back
    // elsewhere: its grabbed vertices 0.3 m along z.
    grab.path(body)!.aim(DT);
    positions[2] += 0.3;
    positions[5] += 0.3;
    grab.rebase(body);
    expect(targets.length).toBe(12); // vertices 0 and 1 under the brush, not 2
    for (let k = 0; k < 2; k++) {
      const i = targets[6 * k];
      for (let d = 0; d < 3; d++) expect(targets[6 * k + 1 + d]).toBeCloseTo(positions[3 * i + d], 15);
    }
  });
});

/**
 * The e2e test's first grab, before its strongest: 2 s at rest, then the default pull
 * (ω = 600 1/s) of the top vertex 0.4 m up and aside for 2 s, let go for 3 s; every step taken.
 */
function afterTheDefaultPull(doc: ReturnType<typeof openedDocument>['doc'], mirror?: { axes: [boolean, boolean, boolean]; centre: Vec3 }): void {
  const dt = doc.settings.dt;
  for (let i = 0; i < 120; i++) expect(doc.advance(dt, 1)).toBe(true);
  const x = doc.world.body(0).positions;
  const p = vertexAt(x, topVertex(x));
  doc.strokeStart({ tool: 'grab', point: p, radius: 0.35, strength: 600, inverted: false, mirror });
  for (let i = 0; i < 120; i++) {
    const s = Math.min(1, i / 15);
    doc.strokeMove([p[0] + 0.23 * s, p[1] + 0.33 * s, p[2]], false);
    doc.updateStroke(dt);
    expect(doc.advance(dt, 1)).toBe(true);
  }
  doc.strokeEnd();
  for (let i = 0; i < 180; i++) expect(doc.advance(dt, 1)).toBe(true);
}

describe('the document’s substeps (real engine)', () => {
  beforeAll(loadEngine);

  const opened = openedDocument;

  it('a frame of n steps is n engine steps of dt covering n dt, the world’s dt as set', () => {
    const { doc } = opened();
    const dt = doc.settings.dt, w = doc.world;
    expect(w.params(0).integrator).toBe('implicit');
    w.sync();
    const t0 = w.body(0).stats.time;
    expect(doc.advance(dt, 3)).toBe(true);
    w.sync();
    const a = doc.lastAdvance!;
    expect([a.steps, a.splits]).toEqual([3, 0]);
    // Three steps of dt, to the rounding of the clock's additions.
    expect(a.simulated).toBeCloseTo(3 * dt, 14);
    expect(w.body(0).stats.time - t0).toBeCloseTo(3 * dt, 12);
    expect(w.params(0).dt).toBe(dt);
  });

  it('a grab on the default model follows the cursor, unannounced', () => {
    const { doc, messages } = opened();
    const dt = doc.settings.dt;
    for (let i = 0; i < 30; i++) doc.advance(dt, 1);
    const x = doc.world.body(0).positions;
    const top = topVertex(x);
    const p = vertexAt(x, top);
    doc.strokeStart({ tool: 'grab', point: p, radius: 0.35, strength: 600, inverted: false });
    doc.strokeMove([p[0], p[1] + 0.4, p[2]], false);
    const ys: number[] = [];
    for (let i = 0; i < 60; i++) { doc.updateStroke(dt); doc.advance(dt, 1); ys.push(doc.world.body(0).positions[3 * top + 1]); }
    doc.strokeEnd();
    // The first step's travel is 1/8 of the brush (4.4 cm): the top cannot have gone further.
    expect(ys[0] - p[1]).toBeLessThan(0.35 / 8 + 1e-3);
    // Then it follows: within 2 cm of the 0.4 m lift (the target spring's sag under the body).
    expect(Math.abs(ys[59] - (p[1] + 0.4))).toBeLessThan(0.02);
    expect(doc.splitFrames).toBe(0);
    expect(messages.filter((m) => /did not converge|shorter steps/.test(m))).toEqual([]);
  });

  it('a mirrored grab on the mushroom subdivided twice follows the cursor and the shape comes back', () => {
    // 5,762 vertices: where the 12th session's trial found frames frozen for seconds (a
    // buckling step ran to the Newton cap three times before the split; now it is given up
    // after a few iterations: `GiveUp`). Every step succeeds (the splits are the worker's).
    const { doc } = opened();
    const dt = doc.settings.dt;
    doc.subdivide(); doc.subdivide();
    expect(doc.world.body(0).vertexCount).toBe(5762);
    for (let i = 0; i < 60; i++) expect(doc.advance(dt, 1)).toBe(true);
    doc.world.sync();
    const v0 = doc.world.body(0).stats.volume;
    const x = doc.world.body(0).positions;
    const top = topVertex(x);
    const p = vertexAt(x, top);
    const aim: Vec3 = [p[0] + 0.3, p[1] + 0.45, p[2]];
    doc.strokeStart({ tool: 'grab', point: p, radius: 0.35, strength: 600, inverted: false, mirror: { axes: [true, false, false], centre: [0, 0, 0] } });
    for (let i = 0; i < 60; i++) {
      doc.strokeMove(aim, false);
      doc.updateStroke(dt);
      expect(doc.advance(dt, 1)).toBe(true);
    }
    const y = doc.world.body(0).positions;
    // After 1 s the grabbed vertex is at the cursor: within 1 cm (measured 1–2 mm: the target
    // springs, k_t = m ω² each, hold the cap's pull-back over the brush's vertices).
    expect(Math.hypot(y[3 * top] - aim[0], y[3 * top + 1] - aim[1], y[3 * top + 2] - aim[2])).toBeLessThan(0.01);
    doc.strokeEnd();
    for (let i = 0; i < 180; i++) expect(doc.advance(dt, 1)).toBe(true);
    doc.world.sync();
    // Released, the gas and the frozen rest shape bring the volume back: within 1e-3 after 3 s
    // (measured: −7 % while pulled, 2e-4 after 3 s; the modeler's damping e-folds the volume's
    // swing in ~0.4 s, so the bound has a margin of ~5).
    expect(Math.abs(doc.world.body(0).stats.volume / v0 - 1)).toBeLessThan(1e-3);
    // No fold was crushed: every step was the model's own (no relaxed retry stood in for a split).
    expect(doc.relaxedSteps).toBe(0);
  }, 300_000);

  it('the strongest mirrored grab pulling the mushroom’s cap up and aside keeps stepping, the top on the cursor', () => {
    // Where the page paused (the 19th session's CI, `e2e/implicit.test.mjs`): the cap pulled
    // this hard crushes faces at its rim to 1e-3 of their height under hinges bent by ~2 rad, and
    // no Newton solve finished even at dt/64. A crushed face now fades its hinges' force
    // (`hinges::bend`); this drag paused the document before that. (Dragged 0.9 or 1.1 m aside
    // instead, the same pull paused it until the relaxed retry: BENCHMARKS.md.)
    const dx = -0.6;
    const { doc, messages } = opened();
    const dt = doc.settings.dt;
    const mirror = { axes: [true, false, false] as [boolean, boolean, boolean], centre: [0, 0, 0] as Vec3 };
    const top = (): number => topVertex(doc.world.body(0).positions);
    const at = (i: number): Vec3 => vertexAt(doc.world.body(0).positions, i);
    // First the default pull, as the e2e test does.
    afterTheDefaultPull(doc, mirror);
    // Then the strongest (ω = 3000 1/s), dragged 0.6 m up and dx aside in 1/3 s and held 1 s.
    const t = top(), p = at(t);
    const aim: Vec3 = [p[0] + dx, p[1] + 0.6, p[2]];
    doc.strokeStart({ tool: 'grab', point: p, radius: 0.35, strength: 3000, inverted: false, mirror });
    for (let i = 0; i < 80; i++) {
      const s = Math.min(1, (i + 1) / 20);
      doc.strokeMove([p[0] + dx * s, p[1] + 0.6 * s, p[2]], false);
      doc.updateStroke(dt);
      const ok = doc.advance(dt, 1);
      if (!ok) throw new Error(`dx = ${dx}: paused at step ${i} of the pull: ${messages.join(' | ')}`);
    }
    // The top is on the cursor: within 2 cm (the target springs at ω = 3000 hold it to mm).
    const y = at(t);
    expect(Math.hypot(y[0] - aim[0], y[1] - aim[1], y[2] - aim[2])).toBeLessThan(0.02);
    doc.strokeEnd();
    for (let i = 0; i < 120; i++) expect(doc.advance(dt, 1)).toBe(true);
    expect(Array.from(doc.world.body(0).positions).every(Number.isFinite)).toBe(true);
  }, 300_000);

  it('the strongest grab crushing the bunny’s back keeps stepping, the top on the cursor, and says once that it let go of crushed bending', () => {
    // The bunny's top dragged 1.1 m aside and 0.4 m up in 5 frames at ω = 3000 1/s, no mirror
    // (`web/bench/repro/fuzz-grab.ts`, GRID=1 MODEL=bunny MIRROR=0, case 12): the drag crushes
    // faces flat under bent hinges, and no solve of the model finished a step there even at
    // dt/64, so the document paused at the 4th frame (8 of that grid's 18 drags did). The
    // engine now takes such a step with the crushed faces' hinges let go (`Relaxed`).
    const { doc, messages } = opened();
    doc.loadBuiltin('bunny', false);
    const dt = doc.settings.dt;
    const at = (i: number): Vec3 => vertexAt(doc.world.body(0).positions, i);
    // The e2e test's default pull first.
    afterTheDefaultPull(doc);
    expect(doc.relaxedSteps).toBe(0);
    const t = topVertex(doc.world.body(0).positions), p = at(t);
    const aim: Vec3 = [p[0] - 1.1, p[1] + 0.4, p[2]];
    doc.strokeStart({ tool: 'grab', point: p, radius: 0.35, strength: 3000, inverted: false });
    for (let f = 1; f <= 90; f++) {
      const s = Math.min(1, f / 5);
      doc.strokeMove([p[0] - 1.1 * s, p[1] + 0.4 * s, p[2]], false);
      doc.updateStroke(dt);
      if (!doc.advance(dt, 1)) throw new Error(`paused at frame ${f} of the drag: ${messages.join(' | ')}`);
    }
    // Held 1.4 s on the aim: the top within 2 cm of it (the target springs at ω = 3000 hold it
    // to mm where the body lets them; the mushroom's drag above meets the same bound).
    const y = at(t);
    expect(Math.hypot(y[0] - aim[0], y[1] - aim[1], y[2] - aim[2])).toBeLessThan(0.02);
    expect(doc.relaxedSteps).toBeGreaterThan(0);
    expect(messages.filter((m) => m.includes('bending let go')).length).toBe(1);
    doc.strokeEnd();
    for (let i = 0; i < 120; i++) expect(doc.advance(dt, 1)).toBe(true);
    expect(Array.from(doc.world.body(0).positions).every(Number.isFinite)).toBe(true);
  }, 300_000);
});
