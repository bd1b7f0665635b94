import { beforeAll, describe, expect, it } from 'vitest';
import { loadEngine } from './setup';
import { SoftBody } from '../src/engine/softbody';
import { parse, serialize } from '../src/project';
import { capture, restore } from '../src/engine/state';
import { History, travel } from '../src/history';

beforeAll(loadEngine);

describe('engine binding', () => {
  it('builds the built-in models with their sizes', () => {
    const b = SoftBody.builtin('mushroom');
    expect(b.vertexCount).toBe(362);
    expect(b.faceCount).toBe(720);
    expect(b.springCount).toBe(1080);
    expect(b.syncRender().length).toBe(3 * 362);
    b.free();
    expect(() => SoftBody.builtin('teapot')).toThrow(/unknown built-in model/);
  });

  it('steps a self-colliding body (in its own one-body world) and keeps the switch', () => {
    const b = SoftBody.builtin('sphere');
    expect(b.get('selfCollision')).toBe(0);
    b.set('selfCollision', 1);
    expect(b.get('selfCollision')).toBe(1);
    b.set('gasAmount', 0); // gasless and pressed: it folds onto itself
    b.set('gravity', 9.81);
    b.set('groundOn', 1);
    b.set('groundHeight', -1);
    b.step(1e-3, 500);
    const s = b.stats();
    expect(Number.isFinite(s.volume) && s.step === 500).toBe(true);
    b.free();
  });

  it('refuses bad parameters with the reason and keeps the old value', () => {
    const b = SoftBody.builtin('sphere');
    b.set('stiffness', 250);
    expect(b.get('stiffness')).toBe(250);
    expect(() => b.set('stiffness', -1)).toThrow(/stiffness/);
    expect(() => b.set('stiffness', NaN)).toThrow(/stiffness/);
    expect(b.get('stiffness')).toBe(250);
    b.free();
  });

  it('rolls back an explosion and says so', () => {
    const b = SoftBody.builtin('sphere');
    b.set('stiffness', 1e7);
    b.set('gasAmount', 1);
    const before = b.positions().slice();
    let error = '';
    for (let i = 0; i < 50 && !error; i++) {
      try { b.step(0.01, 10); } catch (e) { error = String(e); }
    }
    expect(error).toMatch(/rolled back/);
    expect(b.positions().every(Number.isFinite)).toBe(true);
    expect(before.length).toBe(b.positions().length);
    b.free();
  });

  it('gas makes the body grow and P V = nRT', () => {
    const b = SoftBody.builtin('sphere');
    b.set('gravity', 0);
    b.set('gasAmount', 20 / (8.314462618 * 300));
    const v0 = b.stats().volume;
    for (let i = 0; i < 200; i++) b.step(1e-3, 5);
    const s = b.stats();
    expect(s.volume).toBeGreaterThan(v0 * 1.01);
    // P V = nRT = 20 J exactly up to rounding.
    expect(s.pressure * s.volume).toBeCloseTo(20, 9);
    b.free();
  });
});

describe('project state', () => {
  it('round-trips through a project file exactly, and the restored body steps identically', () => {
    const a = SoftBody.builtin('octopus', 2);
    a.set('gasAmount', 0.002);
    a.set('bendingStiffness', 50);
    a.set('groundOn', 1);
    a.set('groundHeight', -0.1);
    for (let i = 0; i < 30; i++) a.step(1e-3, 5);
    a.freezeUnderLoad();
    expect(a.prestress().some((f) => f !== 0)).toBe(true);
    a.setPinned(3, true);
    const m = a.masses().slice(); m[7] *= 4; a.setMasses(m);
    a.scaleRest(1.05);
    for (let i = 0; i < 10; i++) a.step(1e-3, 5);
    const text = serialize({ name: 'octo', state: capture(a), ui: { tool: 'grab' } });
    const b = restore(parse(text).state);
    expect(Array.from(b.positions())).toEqual(Array.from(a.positions()));
    expect(Array.from(b.restLengths())).toEqual(Array.from(a.restLengths()));
    expect(b.pinned()[3]).toBe(1);
    for (let i = 0; i < 20; i++) { a.step(1e-3, 5); b.step(1e-3, 5); }
    expect(Array.from(b.positions())).toEqual(Array.from(a.positions()));
    a.reset(); b.reset();
    expect(Array.from(b.positions())).toEqual(Array.from(a.positions()));
    a.free(); b.free();
  });

  it('rejects malformed project files with a reason', () => {
    expect(() => parse('nonsense')).toThrow(/not JSON/);
    expect(() => parse('{"format":"x"}')).toThrow(/not a SoftSculpt project/);
    expect(() => parse('{"format":"softsculpt-project","version":1,"body":{}}')).toThrow(/positions/);
  });
});

describe('history', () => {
  it('undoes and redoes in order, and a new operation clears redo', () => {
    const h = new History<number>(3);
    let value = 0;
    const set = (v: number) => { const old = value; value = v; return old; };
    h.push('a', value); value = 1;
    h.push('b', value); value = 2;
    expect(travel(h, 'undo', set)?.label).toBe('b');
    expect(value).toBe(1);
    expect(travel(h, 'undo', set)?.label).toBe('a');
    expect(value).toBe(0);
    expect(travel(h, 'undo', set)).toBeNull();
    expect(travel(h, 'redo', set)?.label).toBe('a');
    expect(value).toBe(1);
    h.push('c', value); value = 5;
    expect(h.canRedo).toBe(false);
    for (let i = 0; i < 10; i++) h.push('x', i);
    expect(h.sizes).toEqual([3, 0]);
  });
});
