// The world binding (crates/softsculpt-wasm through src/engine/world.ts) with the real wasm:
// physics-meaningful checks of what crosses the binding.
import { beforeAll, describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { loadEngine } from './setup';
import { EngineError, World } from '../src/engine/world';
import { raw } from '../src/engine/wasm';
import { MATERIAL_KEYS } from '../src/panel-material';
import { SHOWN } from '../src/panel-params';

beforeAll(loadEngine);

const scene = (name: string) => readFileSync(new URL(`../../scenes/${name}`, import.meta.url), 'utf8');
const R = 8.314462618;
const EPS = Number.EPSILON;

/** The error `f` throws (it must throw an EngineError). */
function thrown(f: () => unknown): EngineError {
  try { f(); } catch (e) { if (e instanceof EngineError) return e; throw e; }
  throw new Error('expected an EngineError');
}

/** A world of one edited, gas-filled octopus resting on a ground and carrying loads. */
function editedOctopus(): World {
  const w = World.create();
  const b = w.addBuiltin('octopus', 2);
  w.setParam(b, 'gas.amount', 0.002);
  w.setParam(b, 'bending', 50);
  w.setParam(b, 'ground', true);
  w.setParam(b, 'ground.height', -0.1);
  w.step(150);
  w.freeze(b, true);
  w.setPins(b, Array.from({ length: w.body(b).vertexCount }, (_, i) => (i % 17 === 3 ? 1 : 0)));
  const m = w.body(b).masses.slice(); m[7] *= 4; w.setMasses(b, m);
  w.scaleRest(b, new Float64Array(w.body(b).vertexCount).fill(1.05));
  w.body(b).userForces[3 * 11 + 1] = 0.5; // N, up
  w.applyLoads(b);
  w.step(50);
  return w;
}

describe('world binding', () => {
  it('an empty world has the parameter table defaults, and a body the default material', () => {
    const w = World.create();
    const table = w.paramTable();
    expect(table.find((p) => p.id === 'stiffness')).toMatchObject({ scope: 'body', unit: 'N/m' });
    w.addBuiltin('mushroom');
    expect(w.bodyCount).toBe(1);
    const b = w.body(0);
    expect([b.vertexCount, b.faceCount, b.springCount]).toEqual([362, 720, 1080]);
    const now = w.params(0);
    for (const p of table.filter((q) => q.scope === 'body' || q.scope === 'world')) {
      if (p.id === 'mass' || p.id.startsWith('ground.')) continue; // mass as asked; no ground
      expect(now[p.id], p.id).toEqual(p.default);
    }
    expect(now.mass).toBeCloseTo(1, 12);
    expect(now['ground.height']).toBeNull();
    w.free();
  });

  it('the modeler preset sets its values (30 J of gas: P V = nRT), and an unknown one is refused whole', () => {
    const w = World.create();
    const b = w.addBuiltin('sphere', 1);
    w.applyPreset(b, 'modeler');
    const p = w.params(b);
    expect(p.integrator).toBe('implicit');
    expect(p.dt).toBeCloseTo(1 / 60, 15);
    expect(p.ground).toBe(true);
    // n = nRT / (R T) and back: a few roundings of relative size EPS.
    expect(Math.abs((p['gas.amount'] as number) * R * (p['gas.temperature'] as number) - 30)).toBeLessThan(30 * 8 * EPS);
    const e = thrown(() => w.applyPreset(b, 'marshmallow'));
    expect(e.kind).toBe('parameter');
    expect(e.message).toContain("unknown preset 'marshmallow'");
    w.free();
  });

  it('gas pushes out with P V = nRT through the stats view', () => {
    const w = World.create();
    w.addBuiltin('sphere');
    w.setParam(0, 'gravity', 0);
    w.setParam(0, 'gas.nrt', 20);
    w.sync();
    const v0 = w.body(0).stats.volume;
    w.step(1000);
    w.sync();
    const s = w.body(0).stats;
    expect(s.volume).toBeGreaterThan(1.01 * v0);
    expect(s.step).toBe(1000);
    expect(s.time).toBeCloseTo(1, 12);
    // P = nRT / V: the product is nRT up to a few roundings.
    expect(Math.abs(s.pressure * s.volume - 20)).toBeLessThanOrEqual(8 * EPS * 20);
    expect(w.params(0)['gas.amount']).toBeCloseTo(20 / (R * 300), 15);
    w.free();
  });

  it('a snapshot restored into another world steps to the same bits', () => {
    const a = editedOctopus();
    const bytes = a.snapshot();
    expect(new TextDecoder().decode(bytes.slice(0, 5))).toBe('SSNAP');
    const b = World.create();
    b.restore(bytes);
    expect(Array.from(b.body(0).positions)).toEqual(Array.from(a.body(0).positions));
    a.step(100); b.step(100);
    expect(Array.from(b.body(0).positions)).toEqual(Array.from(a.body(0).positions));
    expect(Array.from(b.body(0).velocities)).toEqual(Array.from(a.body(0).velocities));
    a.reset(0); b.reset(0);
    expect(Array.from(b.body(0).positions)).toEqual(Array.from(a.body(0).positions));
    a.sync(); b.sync();
    expect(b.body(0).stats).toEqual(a.body(0).stats);
    expect(b.body(0).pinned[3]).toBe(1);
    a.free(); b.free();
  });

  it('the rigidity is a body parameter like bending: in the table, the panel and the material keys, kept by a snapshot, checked', () => {
    const w = World.create();
    const table = w.paramTable();
    expect(table.find((p) => p.id === 'rigidity')).toMatchObject({ scope: 'body', unit: 'J', default: 0 });
    for (const k of MATERIAL_KEYS) {
      expect(table.find((p) => p.id === k)?.scope, k).toBe('body');
      expect(SHOWN[k], k).toBeDefined();
    }
    const b = w.addBuiltin('sphere', 1);
    w.setParam(b, 'rigidity', 0.2);
    expect(w.params(b).rigidity).toBe(0.2);
    const e = thrown(() => w.setParam(b, 'rigidity', -1));
    expect(e.kind).toBe('parameter');
    expect(e.message).toContain('rigidity');
    expect(w.params(b).rigidity).toBe(0.2);
    const c = World.create();
    c.restore(w.snapshot());
    expect(c.params(0).rigidity).toBe(0.2);
    w.free(); c.free();
  });

  it('a bad snapshot is refused with the core message and the world stays as it was', () => {
    const w = editedOctopus();
    const good = w.snapshot();
    const before = w.body(0).positions.slice();
    const truncated = thrown(() => w.restore(good.slice(0, 100)));
    expect(truncated.kind).toBe('snapshot');
    expect(truncated.message).toMatch(/truncated: 100 of \d+ bytes/);
    const flipped = good.slice(); flipped[flipped.length - 10] ^= 0xff;
    expect(thrown(() => w.restore(flipped)).message).toMatch(/corrupted: checksum mismatch/);
    const newer = good.slice(); newer[5] = 99;
    expect(thrown(() => w.restore(newer)).message).toMatch(/version 99 is newer/);
    expect(thrown(() => w.restore(new TextEncoder().encode('hello'))).message).toMatch(/not a SoftSculpt snapshot/);
    expect(Array.from(w.body(0).positions)).toEqual(Array.from(before));
    w.free();
  });

  it('a blow-up rolls the whole world back and names the time of the failing step', () => {
    const w = World.create();
    w.addBuiltin('sphere');
    w.setParam(0, 'stiffness', 1e7);
    w.setParam(0, 'gas.amount', 1);
    w.setParam(0, 'dt', 0.01);
    let error: EngineError | null = null;
    let before = new Float64Array(), t0 = 0;
    for (let i = 0; i < 50 && !error; i++) {
      w.sync();
      before = w.body(0).positions.slice();
      t0 = w.body(0).stats.time;
      try { w.step(10); } catch (e) { error = e as EngineError; }
    }
    expect(error).toBeInstanceOf(EngineError);
    if (!error) return;
    expect(error.kind).toBe('step');
    expect(error.message).toMatch(/rolled back/);
    // The failing step started within the call: t0 ≤ time < t0 + 10 dt.
    expect(error.time).toBeGreaterThanOrEqual(t0 - 1e-12);
    expect(error.time).toBeLessThan(t0 + 10 * 0.01);
    expect(error.rolledBackTo).toBe(t0);
    w.sync();
    expect(w.body(0).stats.time).toBe(t0);
    expect(Array.from(w.body(0).positions)).toEqual(Array.from(before));
    w.free();
  });

  it('refuses a bad parameter naming it and its unit, and keeps the old value', () => {
    const w = World.create();
    w.addBuiltin('sphere');
    w.setParam(0, 'stiffness', 250);
    const neg = thrown(() => w.setParam(0, 'stiffness', -1));
    expect(neg).toMatchObject({ kind: 'parameter', parameter: 'stiffness', unit: 'N/m' });
    expect(neg.message).toMatch(/stiffness: must be ≥ 0 N\/m, got -1/);
    expect(thrown(() => w.setParam(0, 'stiffness', NaN)).parameter).toBe('stiffness');
    // @ts-expect-error a misspelt id: tsc refuses it (ParamId), and the engine too, at run time
    expect(thrown(() => w.setParam(0, 'stifness', 3)).message).toMatch(/stifness: no such parameter/);
    expect(thrown(() => w.setParam(0, 'integrator', 'leapfrog')).message).toMatch(/unknown choice 'leapfrog'/);
    expect(thrown(() => w.setParam(0, 'ground', 1)).message).toMatch(/expected true or false/);
    expect(thrown(() => w.setParam(3, 'stiffness', 1)).message).toMatch(/no body 3/);
    expect(w.params(0).stiffness).toBe(250);
    w.setParam(0, 'wind', [1, 0, -2]);
    expect(w.params(0).wind).toEqual([1, 0, -2]);
    w.free();
  });

  it('typed-array views are re-made after wasm memory grows', () => {
    const w = World.create();
    w.addBuiltin('sphere');
    const old = w.body(0).positions;
    const copy = old.slice();
    const size = raw().memory.buffer.byteLength;
    const block = raw().ss_alloc(size); // more than is free: memory must grow
    expect(raw().memory.buffer.byteLength).toBeGreaterThan(size);
    expect(old.length).toBe(0); // the old buffer is detached
    expect(Array.from(w.body(0).positions)).toEqual(Array.from(copy));
    raw().ss_dealloc(block, size);
    w.step(1);
    w.sync();
    const b = w.body(0);
    for (let i = 0; i < b.vertexCount * 3; i++) expect(b.render[i]).toBe(Math.fround(b.positions[i]));
    w.free();
  });

  it('staged loads act: a force gives momentum F t, pins hold, a uniform pressure nets no force', () => {
    const w = World.create();
    w.addBuiltin('sphere');
    w.setParam(0, 'gravity', 0);
    const b = w.body(0);
    const n = b.vertexCount, F = 0.3; // N in +x, spread equally
    for (let i = 0; i < n; i++) b.userForces[3 * i] = F / n;
    w.applyLoads(0);
    w.step(200);
    w.sync();
    const t = 200 * 1e-3;
    // Springs are internal (they cancel pairwise): only the load changes the momentum.
    expect(Math.abs(w.body(0).stats.momentum[0] - F * t)).toBeLessThanOrEqual(200 * n * 4 * EPS * F * t);
    expect(Math.abs(w.body(0).stats.momentum[1])).toBeLessThanOrEqual(200 * n * 4 * EPS * F * t);

    const pins = new Uint8Array(n); pins[0] = 1; pins[5] = 1;
    w.setPins(0, pins);
    const x0 = w.body(0).positions.slice(0, 18);
    w.step(50);
    const x = w.body(0).positions;
    for (const i of [0, 5]) for (let d = 0; d < 3; d++) expect(x[3 * i + d]).toBe(x0[3 * i + d]);
    w.sync();
    expect(Array.from(w.body(0).pinned.slice(0, 6))).toEqual([1, 0, 0, 0, 0, 1]);

    const still = World.create();
    still.addBuiltin('sphere');
    still.setParam(0, 'gravity', 0);
    still.sync();
    // A pressure force times the time: 50 Pa × area ~ V^(2/3) × 0.1 s.
    const scale = 50 * still.body(0).stats.volume ** (2 / 3) * 0.1;
    still.body(0).facePressures.fill(50); // Pa on every face of the closed surface, inward
    still.applyLoads(0);
    still.step(100);
    still.sync();
    expect(Math.hypot(...still.body(0).stats.momentum)).toBeLessThan(1e-9 * scale);
    w.free(); still.free();
  });

  it('subdivision replaces the body and its views keep the mass', () => {
    const w = World.create();
    w.addBuiltin('octopus', 2);
    const n = w.body(0).vertexCount, f = w.body(0).faceCount;
    expect(w.subdivide(0)).toBe(0);
    const b = w.body(0);
    expect(b.faceCount).toBe(4 * f);
    expect(b.vertexCount).toBeGreaterThan(n);
    const total = b.masses.reduce((s, m) => s + m, 0);
    expect(Math.abs(total - 2)).toBeLessThanOrEqual(b.vertexCount * EPS * 2);
    expect(b.springs.length).toBe(2 * b.springCount);
    expect(Math.max(...b.triangles)).toBe(b.vertexCount - 1);
    w.free();
  });

  it('loads and operations refuse a missing body or a bad world handle', () => {
    const w = World.create();
    expect(thrown(() => w.freeze(0)).kind).toBe('usage');
    expect(thrown(() => w.body(0).positions).message).toMatch(/no body 0/);
    w.free();
    expect(thrown(() => w.step(1)).kind).toBe('usage');
  });

  it('reports a bad OBJ as a mesh error with its line, and load warnings as a list', () => {
    const w = World.create();
    const bad = thrown(() => w.addObj(new TextEncoder().encode('v 0 0 0\nv 1 0 0\nf 1 2 x\n')));
    expect(bad.kind).toBe('mesh');
    expect(bad.line).toBe(3);
    // A tetrahedron with a duplicated vertex: welded, with a warning.
    const tet = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 0\nf 1 3 2\nf 5 2 4\nf 2 3 4\nf 3 1 4\n';
    expect(w.addObj(new TextEncoder().encode(tet))).toBe(0);
    expect(w.body(0).vertexCount).toBe(4);
    expect(w.warnings.length).toBeGreaterThan(0);
    expect(thrown(() => w.addBuiltin('teapot')).message).toMatch(/unknown built-in model 'teapot'/);
    w.free();
  });

  it('sketches a balloon from an outline: closed, inflated, its silhouette the outline; a bow tie is refused', () => {
    const w = World.create();
    // A 2 m square.
    const b = w.addSketch(Float64Array.from([-1, -1, 1, -1, 1, 1, -1, 1]));
    const body = w.body(b);
    // Closed, of a sphere's topology: F = 2V − 4.
    expect(body.faceCount).toBe(2 * body.vertexCount - 4);
    w.sync();
    expect(w.body(b).stats.volume).toBeGreaterThan(0.5);
    // Its shadow on the outline's plane stays within the square's (up to 5 %: the gas stretches it a little).
    const x = body.positions;
    for (let i = 0; i < x.length; i += 3) for (const d of [0, 1]) expect(Math.abs(x[i + d])).toBeLessThan(1.05);
    expect(thrown(() => w.addSketch(Float64Array.from([0, 0, 1, 1, 1, 0, 0, 1]))).message).toMatch(/crosses itself/);
    w.free();
  });
});

describe('scenes through the world binding', () => {
  it('opens a shipped scene and fires its events on time (Fig. 2: more gas inflates)', () => {
    const w = World.create();
    const s = w.openScene(scene('fig2_mushroom_gas.toml'));
    expect(s).toMatchObject({ names: ['mushroom'], dt: 0.001 });
    w.step(1400);
    w.sync();
    const before = w.body(0).stats.volume;
    w.step(1500); // the gas is multiplied by five at 1.5 s
    w.sync();
    expect(w.body(0).stats.time).toBeCloseTo(2.9, 9);
    expect(w.body(0).stats.volume).toBeGreaterThan(1.1 * before);
    w.free();
  });

  it('reports a bad scene with its line and key, and leaves the world as it was', () => {
    const w = World.create();
    w.addBuiltin('sphere');
    const e = thrown(() => w.openScene('[world]\ndt = 0.001\n\n[[body]]\nmodel = "sphere"\nstifness = 3\n'));
    expect(e).toMatchObject({ kind: 'scene', line: 6, key: 'body[0].stifness' });
    expect(thrown(() => w.openScene('[[body]]\nmesh = "rock.obj"\n')).message).toMatch(/rock\.obj/);
    expect(w.bodyCount).toBe(1);
    w.free();
  });

  it('reads mesh files given with the scene and describes its obstacles', () => {
    const w = World.create();
    const tetra = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n';
    const text = '[[body]]\nmesh = "meshes/tet.obj"\n[[obstacle]]\nshape = "sphere"\ncenter = [0, -2, 0]\nradius = 1\n' +
      '[[obstacle]]\nshape = "box"\ncenter = [0, 0, 0]\nhalf_extents = [1, 2, 3]\n[[obstacle]]\nshape = "mesh"\nmesh = "tet.obj"\ntranslate = [5, 0, 0]\n';
    w.openScene(text, new Map([['tet.obj', new TextEncoder().encode(tetra)]]));
    expect(w.body(0).vertexCount).toBe(4);
    const o = w.obstacles();
    expect(o.map((x) => x.kind)).toEqual(['sphere', 'box', 'mesh']);
    expect(o[0]).toMatchObject({ center: [0, -2, 0], radius: 1 });
    expect(o[1]).toMatchObject({ half: [1, 2, 3], axes: [[1, 0, 0], [0, 1, 0], [0, 0, 1]] });
    if (o[2].kind !== 'mesh') throw new Error('mesh expected');
    expect(o[2].positions.length).toBe(12);
    expect(o[2].positions[0]).toBe(5);
    expect(o[2].indices.length).toBe(12);
    w.free();
  });

  it('saves the world as a scene that opens again with the same bodies, obstacles and events', () => {
    const w = World.create();
    w.openScene(scene('fig4a_mushroom_press_wind.toml'));
    w.step(300);
    const pins = w.body(0).pinned.slice(); pins[0] = 1;
    w.setPins(0, pins);
    const text = w.saveScene();
    expect(text).toMatch(/\[\[event\]\]/);
    const again = World.create();
    expect(again.openScene(text).names).toEqual(['mushroom']);
    const a = w.body(0), b = again.body(0);
    expect(b.vertexCount).toBe(a.vertexCount);
    const sorted = (x: Float64Array) => Array.from({ length: x.length / 3 }, (_, i) => `${x[3 * i]},${x[3 * i + 1]},${x[3 * i + 2]}`).sort();
    expect(sorted(b.positions)).toEqual(sorted(a.positions));
    const count = (p: Uint8Array) => p.reduce((n, x) => n + x, 0);
    expect(count(b.pinned)).toBe(count(pins));
    expect(again.params(0).stiffness).toBe(w.params(0).stiffness);
    w.free(); again.free();
  });

  it('clear forgets the scene but keeps the settings; restore keeps the scene', () => {
    const w = World.create();
    w.openScene(scene('fig4a_mushroom_press_wind.toml'));
    w.restore(w.snapshot());
    expect(w.saveScene()).toMatch(/name = "mushroom"[\s\S]*\[\[event\]\]/);
    w.clear();
    expect(w.bodyCount).toBe(0);
    w.addBuiltin('sphere');
    expect(w.params(0).wind).toEqual([1.5, 0, 0]); // the scene's wind stays
    const text = w.saveScene();
    expect(text).toMatch(/name = "body1"/);
    expect(text).not.toMatch(/\[\[event\]\]/);
    w.free();
  });
});

describe('undo deltas and version-1 projects through the world binding', () => {
  it('undoing a brush stroke puts back what it painted and leaves the rest moving; redo paints again', () => {
    const w = World.create();
    w.addBuiltin('sphere');
    w.step(10);
    const b = () => w.body(0);
    const rest0 = b().rest.slice();
    w.mark();
    const x = b().positions;
    // Inflate a brush on the top: 20 % at the top vertex, weight (1 − (d/r)²)² out to r = 0.6 m,
    // about four edges, so the mesh carries the field as it is (a sharper one is spread over
    // more of the body first: the core's body/growth.rs) and the stroke touches the top only.
    const n = b().vertexCount;
    const t = Array.from({ length: n }, (_, i) => i).reduce((m, i) => (x[3 * i + 1] > x[3 * m + 1] ? i : m), 0);
    const top = x[3 * t + 1];
    const r = 0.6;
    const factors = Float64Array.from({ length: n }, (_, i) => {
      const d = Math.hypot(x[3 * i] - x[3 * t], x[3 * i + 1] - x[3 * t + 1], x[3 * i + 2] - x[3 * t + 2]);
      return d < r ? 1 + 0.2 * (1 - (d / r) ** 2) ** 2 : 1;
    });
    w.scaleRest(0, factors);
    w.step(20);
    const painted = b().rest.slice();
    const far = factors.findIndex((f, i) => f === 1 && x[3 * i + 1] < -0.5 * top);
    const farBefore = b().positions.slice(3 * far, 3 * far + 3);
    const undo = w.delta('touched');
    expect(undo.length).toBeLessThan(8 * rest0.length); // fewer bytes than the rest lengths themselves
    const redo = w.applyDelta(undo);
    expect(Array.from(b().rest)).toEqual(Array.from(rest0));
    expect(Array.from(b().positions.slice(3 * far, 3 * far + 3))).toEqual(Array.from(farBefore)); // not rewound
    w.applyDelta(redo);
    expect(Array.from(b().rest)).toEqual(Array.from(painted));
    w.free();
  });

  it('undoing a subdivision brings the whole earlier world back', () => {
    const w = World.create();
    w.addBuiltin('octopus');
    w.step(30);
    const before = w.snapshot();
    w.mark();
    w.subdivide(0);
    w.step(5);
    const n = w.body(0).vertexCount;
    const redo = w.applyDelta(w.delta('all'));
    expect(Array.from(w.snapshot())).toEqual(Array.from(before));
    w.applyDelta(redo);
    expect(w.body(0).vertexCount).toBe(n);
    w.free();
  });

  it('refuses a delta made for another model, or damaged bytes, and leaves the world as it was', () => {
    const a = World.create(), b = World.create();
    a.addBuiltin('sphere'); b.addBuiltin('sphere');
    expect(thrown(() => a.delta('all')).message).toMatch(/no mark/);
    a.mark();
    a.scaleRest(0, new Float64Array(a.body(0).vertexCount).fill(1.1));
    const d = a.delta('touched');
    b.addBuiltin('mushroom'); // two bodies: the delta was made for one
    const before = b.snapshot();
    const foreign = thrown(() => b.applyDelta(d));
    expect(foreign.kind).toBe('delta');
    expect(foreign.message).toMatch(/does not fit/);
    const damaged = d.slice(); damaged[damaged.length - 1] ^= 0x55;
    expect(thrown(() => a.applyDelta(damaged)).kind).toBe('delta');
    expect(thrown(() => a.applyDelta(d.slice(0, 7))).kind).toBe('delta');
    expect(Array.from(b.snapshot())).toEqual(Array.from(before));
    a.free(); b.free();
  });

  it('a version-1 project opens where it was saved and steps on like the saved body', () => {
    const a = World.create();
    a.addBuiltin('sphere', 2);
    a.setParam(0, 'stiffness', 300);
    a.setParam(0, 'gas.amount', 0.004);
    a.sync();
    const v = a.body(0);
    const arr = (x: ArrayLike<number>) => Array.from(x);
    const file = {
      format: 'softsculpt-project', version: 1, name: 'ball',
      body: {
        triangles: arr(v.triangles), pinned: arr(v.pinned), gas: [0, v.stats.volume], frozenGas: [0, v.stats.volume],
        params: { stiffness: 300, springDamping: 0.1, bendingStiffness: 0, damping: 0, gravity: 9.81, gasAmount: 0.004, temperature: 300,
          volumeMode: 0, windX: 0, windY: 0, windZ: 0, windDrag: 1, groundOn: 0, groundHeight: 0, friction: 0.5, integrator: 3, selfCollision: 0 },
        positions: arr(v.positions), velocities: arr(v.velocities), restLengths: arr(v.rest), masses: arr(v.masses),
        frozenPositions: arr(v.positions), frozenRestLengths: arr(v.rest), prestress: new Array(v.positions.length).fill(0),
        frozenPrestress: new Array(v.positions.length).fill(0), bendingRestLengths: arr(v.bendingRest), frozenBendingRestLengths: arr(v.bendingRest),
      },
      ui: { dt: 0.001, tool: 'inflate' },
    };
    const b = World.create();
    b.addBuiltin('octopus');
    const meta = b.openProjectV1(JSON.stringify(file));
    expect(meta).toMatchObject({ name: 'ball', ui: { tool: 'inflate' } });
    expect(b.bodyCount).toBe(1);
    expect(b.params(0)).toMatchObject({ stiffness: 300, 'gas.amount': 0.004 });
    a.step(50); b.step(50);
    expect(Array.from(b.body(0).positions)).toEqual(Array.from(a.body(0).positions));
    // A damaged one is refused naming what is wrong; the world stays.
    const bad = { ...file, body: { ...file.body, pinned: file.body.pinned.slice(1) } };
    const e = thrown(() => b.openProjectV1(JSON.stringify(bad)));
    expect(e.kind).toBe('project');
    expect(e.message).toMatch(/'pinned' has 641 values, expected 642/);
    expect(Array.from(b.body(0).positions)).toEqual(Array.from(a.body(0).positions));
    a.free(); b.free();
  });

  it('target springs hold a vertex at its anchor in implicit steps of 1/60 s, any stiffness, and clear', () => {
    const w = World.create();
    w.addBuiltin('sphere', 1);
    w.setParam(0, 'integrator', 'implicit');
    w.setParam(0, 'dt', 1 / 60);
    w.setParam(0, 'damping', 2);
    w.setParam(0, 'tolerance', 1e-3); // the modeler's
    const x0 = w.body(0).positions.slice();
    const anchor = [x0[0] + 0.3, x0[1], x0[2]];
    // Stiffness 1e5 N/m on a vertex of 1/642 kg: ω dt ≈ 130, far past any explicit limit.
    w.setTargets(0, Float64Array.from([0, ...anchor, 1e5, 10]));
    w.step(120);
    const x = w.body(0).positions;
    // At rest the target spring balances the springs pulling back (k = 100 N/m, a few of them
    // stretched by 0.3 m: tens of N), so the vertex is within 1e-3 m of the anchor.
    expect(Math.hypot(x[0] - anchor[0], x[1] - anchor[1], x[2] - anchor[2])).toBeLessThan(1e-3);
    expect(Array.from(x).every(Number.isFinite)).toBe(true);
    w.setTargets(0, new Float64Array(0));
    w.step(300);
    // Cleared: the vertex is no longer held (the stretched springs pull it off the anchor).
    expect(Math.abs(w.body(0).positions[0] - anchor[0])).toBeGreaterThan(0.01);
    expect(Array.from(w.body(0).positions).every(Number.isFinite)).toBe(true);
    expect(thrown(() => w.setTargets(0, Float64Array.from([999, 0, 0, 0, 1, 0]))).message).toMatch(/out of range/);
    w.free();
  });
});
