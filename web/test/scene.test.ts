// Scenes in the page: the engine's scene binding with the real wasm, on the shipped scenes.
import { beforeAll, describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { loadEngine } from './setup';
import { Scene } from '../src/engine/scene';

beforeAll(loadEngine);

const scene = (name: string) => readFileSync(new URL(`../../scenes/${name}`, import.meta.url), 'utf8');

describe('scene binding', () => {
  it('opens a shipped scene and fires its events on time (Fig. 2: more gas inflates)', () => {
    const s = Scene.open(scene('fig2_mushroom_gas.toml'));
    expect(s.names).toEqual(['mushroom']);
    expect(s.bodies[0].vertexCount).toBe(362);
    expect(s.dt).toBe(0.001);
    s.step(s.dt, 1400);
    const before = s.bodies[0].stats().volume;
    s.step(s.dt, 1500); // the gas is multiplied by five at 1.5 s
    expect(s.time).toBeCloseTo(2.9, 9);
    expect(s.bodies[0].stats().volume).toBeGreaterThan(1.1 * before);
    s.bodies[0].free();
    s.free();
  });

  it('reports a bad scene with its line and key, and a missing mesh by name', () => {
    expect(() => Scene.open('[world]\ndt = 0.001\n\n[[body]]\nmodel = "sphere"\nstifness = 3\n')).toThrow(/line 6: body\[0\]\.stifness: unknown field/);
    expect(() => Scene.open('[[body]]\nmesh = "rock.obj"\n')).toThrow(/rock\.obj/);
  });

  it('reads mesh files given with the scene, and describes its obstacles for drawing', () => {
    const tetra = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n';
    const text = '[[body]]\nmesh = "meshes/tet.obj"\n[[obstacle]]\nshape = "sphere"\ncenter = [0, -2, 0]\nradius = 1\n' +
      '[[obstacle]]\nshape = "box"\ncenter = [0, 0, 0]\nhalf_extents = [1, 2, 3]\n[[obstacle]]\nshape = "mesh"\nmesh = "tet.obj"\ntranslate = [5, 0, 0]\n';
    const s = Scene.open(text, new Map([['tet.obj', new TextEncoder().encode(tetra)]]));
    expect(s.bodies[0].vertexCount).toBe(4);
    const o = s.obstacles();
    expect(o.map((x) => x.kind)).toEqual(['sphere', 'box', 'mesh']);
    expect(o[0]).toMatchObject({ center: [0, -2, 0], radius: 1 });
    expect(o[1]).toMatchObject({ half: [1, 2, 3], axes: [[1, 0, 0], [0, 1, 0], [0, 0, 1]] });
    if (o[2].kind !== 'mesh') throw new Error('mesh expected');
    expect(o[2].positions.length).toBe(12);
    expect(o[2].positions[0]).toBe(5);
    expect(o[2].indices.length).toBe(12);
    s.bodies[0].free();
    s.free();
  });

  it('saves the bodies as a scene that opens again the same, keeping obstacles and events', () => {
    const s = Scene.open(scene('fig4a_mushroom_press_wind.toml'));
    s.step(s.dt, 300);
    s.bodies[0].setPinned(0, true);
    const text = Scene.save(s.bodies, s.dt, s.duration, s);
    expect(text).toMatch(/\[\[event\]\]/);
    const again = Scene.open(text);
    expect(again.names).toEqual(['mushroom']);
    const a = s.bodies[0], b = again.bodies[0];
    expect(b.vertexCount).toBe(a.vertexCount);
    const sorted = (x: Float64Array) => Array.from({ length: x.length / 3 }, (_, i) => `${x[3 * i]},${x[3 * i + 1]},${x[3 * i + 2]}`).sort();
    expect(sorted(b.positions())).toEqual(sorted(a.positions()));
    expect(b.pinned().reduce((n, p) => n + p, 0)).toBe(a.pinned().reduce((n, p) => n + p, 0));
    for (const x of [s, again]) { x.bodies.forEach((body) => body.free()); x.free(); }
  });
});
