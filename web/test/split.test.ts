// The worker's split steps (src/worker/split.ts): an implicit step that does not converge is
// taken again as two half steps, recursively, and the state is never advanced by a failed try.
import { describe, expect, it } from 'vitest';
import { notConverged, stepSplitting } from '../src/worker/split';

const unconverged = () => Object.assign(new Error('not converged'), { kind: 'step', fields: { converged: false } });
const blowUp = () => Object.assign(new Error('blew up'), { kind: 'step', fields: {} });

/** A fake world whose steps converge only at dt ≤ `limit`; a failed call leaves `time` alone. */
function world(limit: number) {
  const w = { time: 0, calls: [] as [number, number][] };
  const step = (dt: number, n: number, _last = false) => {
    w.calls.push([dt, n]);
    if (dt > limit) throw unconverged();
    w.time += dt * n;
  };
  return { w, step };
}

describe('split steps', () => {
  it('takes a converging step as it is', () => {
    const { w, step } = world(1);
    expect(stepSplitting(step, 1 / 60, 1)).toBe(0);
    expect(w.calls).toEqual([[1 / 60, 1]]);
  });

  it('splits an unconverged step into two halves and covers the same time', () => {
    const { w, step } = world(0.01);
    expect(stepSplitting(step, 1 / 60, 1)).toBe(1);
    expect(w.time).toBeCloseTo(1 / 60, 15);
    expect(w.calls.slice(1)).toEqual([[1 / 120, 1], [1 / 120, 1]]);
  });

  it('splits again where the halves fail too, up to three levels (dt/8)', () => {
    const { w, step } = world(0.0025); // dt/8 = 2.08 ms converges, dt/4 = 4.2 ms does not
    expect(stepSplitting(step, 1 / 60, 1)).toBe(1 + 2 + 4);
    expect(w.time).toBeCloseTo(1 / 60, 15);
    expect(Math.min(...w.calls.map(([dt]) => dt))).toBeCloseTo(1 / 480, 15);
  });

  it('tells only the shortest split that no shorter one follows (the engine then keeps its whole cap)', () => {
    const seen: [number, boolean][] = [];
    const { step } = world(0.0025);
    stepSplitting((dt, n, last) => { seen.push([dt, last]); step(dt, n, last); }, 1 / 60, 1);
    // dt/8 is the last split: told so; every longer try is not.
    for (const [dt, last] of seen) expect(last).toBe(Math.abs(dt - 1 / 480) < 1e-15);
    expect(seen.some(([, last]) => last)).toBe(true);
  });

  it('gives up past three levels with the engine error, the state untouched', () => {
    const { w, step } = world(1e-4);
    expect(() => stepSplitting(step, 1 / 60, 1)).toThrow('not converged');
    // Every try failed (no half step converges), so no time was taken.
    expect(w.time).toBe(0);
  });

  it('takes a failed batch one step at a time, splitting only what needs it', () => {
    let tries = 0;
    const calls: [number, number][] = [];
    // The second full step of three fails once (a grab yanked hard), then everything converges.
    const step = (dt: number, n: number) => {
      calls.push([dt, n]);
      if (n === 3 || (n === 1 && dt === 1 / 60 && ++tries === 2)) throw unconverged();
    };
    expect(stepSplitting(step, 1 / 60, 3)).toBe(1);
    expect(calls).toEqual([[1 / 60, 3], [1 / 60, 1], [1 / 60, 1], [1 / 120, 1], [1 / 120, 1], [1 / 60, 1]]);
  });

  it('passes any other failure (a blow-up) straight on', () => {
    const step = () => { throw blowUp(); };
    expect(() => stepSplitting(step, 1 / 60, 1)).toThrow('blew up');
    expect(notConverged(blowUp())).toBe(false);
    expect(notConverged(unconverged())).toBe(true);
  });
});
