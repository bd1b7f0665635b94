import { beforeAll, describe, expect, it } from 'vitest';
import { loadEngine } from './setup';
import { falloff, inflateFactor, targetSpring, vertexNormals, verticesAround } from '../src/tools/brush';
import { placeOnGround, MODELS } from '../src/models';
import { addModel, useDefaults } from '../src/engine/models';
import { World } from '../src/engine/world';

beforeAll(loadEngine);

describe('brush maths', () => {
  it('falls off smoothly from 1 at the centre to 0 at the rim', () => {
    expect(falloff(0, 1)).toBe(1);
    expect(falloff(1, 1)).toBe(0);
    expect(falloff(2, 1)).toBe(0);
    expect(falloff(0.5, 1)).toBeCloseTo(0.5625, 15); // (1 − 0.25)²
    // Zero slope at the rim: the difference quotient vanishes as h → 0 (≈ 8h for h ≪ 1).
    const h = 1e-4;
    expect(falloff(1 - h, 1) / h).toBeLessThan(1e-3);
    expect(falloff(0.5, 0)).toBe(0);
  });

  it('selects the vertices inside the brush, weighted', () => {
    const x = [0, 0, 0, 0.5, 0, 0, 2, 0, 0];
    const w = verticesAround(x, [0, 0, 0], 1);
    expect(w.indices).toEqual([0, 1]);
    expect(w.weights[0]).toBe(1);
  });

  it('gives a target spring of stiffness m w ω² and critical damping 2 m w ω', () => {
    // m = 2 kg, w = 0.5, ω = 10 1/s: k = 100 N/m, c = 20 N·s/m (c² = 4 m w k: critical).
    const t = targetSpring(2, 0.5, 10);
    expect(t.stiffness).toBeCloseTo(100, 12);
    expect(t.damping).toBeCloseTo(20, 12);
  });

  it('points vertex normals out of a closed mesh', () => {
    // A tetrahedron wound outward: each vertex normal points away from the centroid.
    const x = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1];
    const n = vertexNormals(x, [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]);
    for (let i = 0; i < 4; i++) {
      const out = [0, 1, 2].map((d) => x[3 * i + d] - 0.25);
      expect(out.reduce((s, o, d) => s + o * n[3 * i + d], 0)).toBeGreaterThan(0);
      expect(Math.hypot(n[3 * i], n[3 * i + 1], n[3 * i + 2])).toBeCloseTo(1, 12);
    }
  });

  it('inflates and deflates by inverse factors', () => {
    const up = inflateFactor(1, 0.5, 0.1, false);
    expect(up).toBeCloseTo(1.05, 15);
    expect(up * inflateFactor(1, 0.5, 0.1, true)).toBeCloseTo(1, 15);
  });
});

describe('models', () => {
  it('every model loads closed, standing on y = 0, with a stable step', () => {
    for (const name of MODELS) {
      const w = World.create();
      const b = addModel(w, name);
      const dt = useDefaults(w, b);
      const x = w.body(b).positions;
      let lo = Infinity;
      for (let i = 1; i < x.length; i += 3) lo = Math.min(lo, x[i]);
      expect(lo).toBeCloseTo(0, 12);
      // A second of simulated time at the chosen dt stays finite (no blow-up; a blow-up throws).
      w.step(Math.round(1 / dt));
      w.sync();
      expect(w.body(b).positions.every(Number.isFinite)).toBe(true);
      expect(w.body(b).stats.volume).toBeGreaterThan(0);
      w.free();
    }
  });

  it('the bunny is the Stanford bunny: 1,839 vertices, closed, scaled to fit', () => {
    const w = World.create();
    const b = addModel(w, 'bunny');
    expect(w.body(b).vertexCount).toBe(1839);
    expect(w.body(b).faceCount).toBe(3674);
    w.setParam(b, 'gas.amount', 0.01); // accepted only on a closed surface
    w.free();
  });

  it('placing fits the bounding-box diagonal and centres x and z', () => {
    const { positions, scale } = placeOnGround(new Float64Array([0, 5, 0, 3, 9, 4]), 10);
    expect(scale).toBeCloseTo(10 / Math.hypot(3, 4, 4), 14);
    expect(positions[1]).toBe(0);
    expect(positions[0]).toBeCloseTo(-positions[3], 14);
  });

  it('the stable step shrinks with lighter vertices and stiffer springs', () => {
    const w = World.create();
    addModel(w, 'sphere');
    const dt1 = useDefaults(w, 0);
    expect(w.params(0).dt).toBe(dt1);
    w.setParam(0, 'stiffness', 1e5);
    expect(w.stableDt('symplectic')).toBeLessThan(dt1);
    w.free();
  });
});
