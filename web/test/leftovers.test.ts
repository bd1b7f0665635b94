// The page leftovers of issue 10 that are maths, not clicks: the default wind's speed, the brush's
// length unit, the material list's names through undo, and the gas energy plotted from 0.

import { describe, expect, it } from 'vitest';
import { PerspectiveCamera, Vector3 } from 'three';
import { acrossView, defaultWindSpeed, windwardArea, WIND_WEIGHT_FRACTION } from '../src/tools/wind';
import { BrushUnit, lengthUnit, rescaleBrush } from '../src/tools/scale';
import { CUSTOM, materialKey, MaterialTracker, MODELER } from '../src/panel-material';
import { Plots } from '../src/view/plots';

/** A latitude-longitude sphere of radius r (outward triangles). */
function uvSphere(r: number, nu = 96, nv = 48): { positions: number[]; triangles: number[] } {
  const positions: number[] = [], triangles: number[] = [];
  for (let j = 0; j <= nv; j++) for (let i = 0; i < nu; i++) {
    const th = (Math.PI * j) / nv, ph = (2 * Math.PI * i) / nu;
    positions.push(r * Math.sin(th) * Math.cos(ph), r * Math.cos(th), r * Math.sin(th) * Math.sin(ph));
  }
  const at = (i: number, j: number) => j * nu + (i % nu);
  for (let j = 0; j < nv; j++) for (let i = 0; i < nu; i++) {
    // Outward: (a, c, b) with y up, φ growing towards +z.
    triangles.push(at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  }
  return { positions, triangles };
}

describe('the default wind', () => {
  it('sees a sphere\'s windward Σ area (d·n)² as 2πR²/3', () => {
    // ∫ cos²θ dA over a hemisphere = 2πR² ∫₀^{π/2} cos²θ sinθ dθ = 2πR²/3; the lat-long mesh's
    // inscribed facets are within O(h²) ≈ 0.1 % of it at 96 × 48.
    const { positions, triangles } = uvSphere(1.5);
    for (const d of [[1, 0, 0], [0, -1, 0], [0.6, 0, 0.8]] as [number, number, number][]) {
      expect(windwardArea(positions, triangles, d) / ((2 * Math.PI * 1.5 * 1.5) / 3)).toBeCloseTo(1, 2);
    }
  });

  it('blows at the speed whose drag at rest is a fifth of the weight', () => {
    const { positions, triangles } = uvSphere(1);
    const d: [number, number, number] = [1, 0, 0];
    const s = defaultWindSpeed(positions, triangles, 2, d, 1, 9.81);
    // F = cw s Σ area (d·n)² (docs/model.md, at rest) = φ m g.
    expect(s * windwardArea(positions, triangles, d)).toBeCloseTo(WIND_WEIGHT_FRACTION * 2 * 9.81, 9);
    // Twice as heavy: twice the speed; half the drag coefficient: twice the speed.
    expect(defaultWindSpeed(positions, triangles, 4, d, 1, 9.81) / s).toBeCloseTo(2, 12);
    expect(defaultWindSpeed(positions, triangles, 2, d, 0.5, 9.81) / s).toBeCloseTo(2, 12);
    // Gravity off: standard gravity sets the scale; no drag: the old 5 m/s (the wind does nothing).
    expect(defaultWindSpeed(positions, triangles, 2, d, 1, 0)).toBeCloseTo(s, 12);
    expect(defaultWindSpeed(positions, triangles, 2, d, 0, 9.81)).toBe(5);
  });
});

describe('W\'s wind across the view', () => {
  const looking = (from: [number, number, number], up: [number, number, number] = [0, 1, 0]) => {
    const c = new PerspectiveCamera();
    c.up.set(...up);
    c.position.set(...from);
    c.lookAt(0, 0, 0);
    return c;
  };
  it('blows level from the screen\'s left to its right, whatever the tilt', () => {
    // The default front view (camera on +z): the screen's right is +x.
    const f = acrossView(looking([0, 0.5, 3]));
    expect(f[0]).toBeCloseTo(1, 12); expect(f[1]).toBe(0); expect(f[2]).toBeCloseTo(0, 12);
    // Looking down steeply from the side (+x): right is −z, still level.
    const d = acrossView(looking([3, 5, 0]));
    expect(d[0]).toBeCloseTo(0, 12); expect(d[1]).toBe(0); expect(d[2]).toBeCloseTo(-1, 12);
  });
  it('stays level and across the view when the camera is rolled', () => {
    // A trackball rolled a quarter round: the camera's right points up; the wind stays level, across the line of sight.
    const c = looking([0, 0, 3], [-1, 0, 0]);
    const d = acrossView(c);
    const look = c.getWorldDirection(new Vector3());
    expect(d[1]).toBe(0);
    expect(Math.hypot(...d)).toBeCloseTo(1, 12);
    expect(d[0] * look.x + d[2] * look.z).toBeCloseTo(0, 12);
  });
});

describe('the brush\'s length unit', () => {
  it('is a power of ten near the model\'s size, 1 m for the built-in models', () => {
    expect(lengthUnit(1.1)).toBe(1); // the mushroom
    expect(lengthUnit(0.05)).toBeCloseTo(0.1, 15); // a 5 cm ball
    expect(lengthUnit(20)).toBe(10);
    expect(lengthUnit(0)).toBe(1);
  });

  it('rescales the radius and the press depth when a model of another size comes, not what was restored with it', () => {
    const u = new BrushUnit(), brush = { radius: 0.35 }, tools = [{ strength: 0.15, isLength: true }, { strength: 600 }];
    rescaleBrush(brush, tools, u.model(1.1)); // the first model: as it is
    expect([brush.radius, tools[0].strength]).toEqual([0.35, 0.15]);
    u.tookUi({ radius: true, strengths: false }); // an import's fitted radius
    brush.radius = 0.012;
    rescaleBrush(brush, tools, u.model(0.05));
    expect(brush.radius).toBe(0.012);
    expect(tools[0].strength).toBeCloseTo(0.015, 15);
    expect(tools[1].strength).toBe(600); // not a length
    rescaleBrush(brush, tools, u.model(1)); // back to a built-in model
    expect(brush.radius).toBeCloseTo(0.12, 12);
    expect(tools[0].strength).toBeCloseTo(0.15, 12);
  });
});

describe('the material list', () => {
  const store = () => { const m = new Map<string, string>(); return { getItem: (k: string) => m.get(k) ?? null, setItem: (k: string, v: string) => void m.set(k, v) }; };
  const modeler = { stiffness: 100, spring_damping: 0.1, bending: 100, rigidity: 0, damping: 1.5, yield: 0, flow: 0, 'gas.amount': 0.012, 'gas.temperature': 300 };
  const clay = { ...modeler, stiffness: 300, spring_damping: 0.5, bending: 0, damping: 4, yield: 0.005, flow: 5, 'gas.amount': 0.008 };

  it('names the modeler\'s, a chosen preset once its step lands, custom after an edit, and follows undo', () => {
    const t = new MaterialTracker(store());
    expect(t.name(modeler, [0, 0], true)).toBe(MODELER);
    t.expect('clay', [0, 0]);
    // A frame before the preset's step arrives: still the modeler's.
    expect(t.name(modeler, [0, 0], false)).toBe(MODELER);
    expect(t.name(clay, [1, 0], false)).toBe('clay');
    expect(t.name({ ...clay, stiffness: 250 }, [2, 0], false)).toBe(CUSTOM);
    expect(t.name({ ...clay, rigidity: 0.05 }, [2, 0], false)).toBe(CUSTOM); // the rigidity is part of the material
    expect(t.name(clay, [1, 1], false)).toBe('clay'); // undo the edit
    expect(t.name(modeler, [0, 2], false)).toBe(MODELER); // undo the preset
  });

  it('remembers what it learned in the browser (a restored session names its material)', () => {
    const s = store();
    const a = new MaterialTracker(s);
    a.name(modeler, [0, 0], true);
    a.expect('clay', [0, 0]);
    a.name(clay, [1, 0], false);
    expect(new MaterialTracker(s).name(clay, [0, 0], true)).toBe('clay');
  });

  it('names the material an opened project gives, in a browser that has never seen it', () => {
    // A new-user trial: clay on an imported model, saved, opened in a fresh browser — the list
    // said "modeler's own" (the values were learned as the modeler's on arrival).
    const t = new MaterialTracker(store());
    expect(t.name(clay, [0, 0], true, 'clay')).toBe('clay');
    expect(t.name(clay, [0, 0], false)).toBe('clay'); // learned: later frames keep the name
    expect(t.name({ ...clay, stiffness: 250 }, [1, 0], false)).toBe(CUSTOM); // an edit after it
    expect(t.name({ ...clay, stiffness: 251 }, [0, 0], true, CUSTOM)).toBe(CUSTOM); // custom values stay unnamed
    expect(t.name({ ...clay, stiffness: 251 }, [0, 0], false)).toBe(CUSTOM);
    expect(t.name(modeler, [0, 0], true)).toBe(MODELER); // a model loaded without a name: the modeler's
  });

  it('still names a material learned before the rigidity existed (rigidity 0 is left out of the key)', () => {
    const s = store();
    const { rigidity: _, ...before } = clay; // what a page without the rigidity had
    const old = new MaterialTracker(s);
    old.name(modeler, [0, 0], true);
    old.expect('clay', [0, 0]);
    old.name(before, [1, 0], false);
    expect(materialKey(before)).toBe(materialKey(clay));
    expect(new MaterialTracker(s).name(clay, [0, 0], true)).toBe('clay');
    expect(materialKey({ ...clay, rigidity: 0.05 })).not.toBe(materialKey(clay));
  });
});

describe('the gas energy plot', () => {
  it('starts at 0 on a new model and again after a clear', () => {
    const p = new Plots({ getContext: () => null } as unknown as HTMLCanvasElement);
    for (let i = 0; i < 10; i++) p.push(i / 60, [2.5, 12, 0, 1.7, -5.9 + 0.1 * i]);
    const gas = p.series[4];
    expect(gas.values[0]).toBe(0);
    expect(gas.values[9]).toBeCloseTo(0.9, 12);
    p.clear();
    p.push(0, [2.5, 12, 0, 1.7, 3]);
    expect(gas.values).toEqual([0]);
  });

  it('draws every series and its value from a single point (plots restarted while paused, e.g. after a rewind)', () => {
    const texts: string[] = [];
    let lines = 0;
    const ctx = new Proxy({}, {
      get: (_t, k) => k === 'fillText' ? (t: string) => texts.push(t) : k === 'lineTo' ? () => lines++ : () => {},
      set: () => true,
    });
    const p = new Plots({ getContext: () => ctx, width: 200, height: 150 } as unknown as HTMLCanvasElement);
    p.push(1.25, [2.45, 12, 0, 1.7, 3]); // the only point after the rewind
    p.draw();
    expect(texts.length).toBe(p.series.length);
    expect(texts[0]).toMatch(/2\.45/);
    expect(lines).toBe(p.series.length); // a level line each
  });
});
