// The page's feedback in numbers: stop messages in the user's terms, plots that do not magnify
// round-off, mirror symmetry, the strength ring's scale, the panel's digits.

import { describe, expect, it } from 'vitest';
import { EngineError } from '../src/engine/world';
import { explainStop } from '../src/worker/explain';
import { sig3 } from '../src/format';
import { Plots, NOISE_FRACTION } from '../src/view/plots';
import { boxCentre, isSymmetric, meanEdge, reflect, reflections } from '../src/tools/symmetry';
import { strengthFraction } from '../src/tools/cursor';
import { decimalsFor } from '../src/panel-params';
import { GrabTool } from '../src/tools/grab';
import { PressTool } from '../src/tools/press';

const blowUp = (fields: Record<string, unknown>) => new EngineError({ kind: 'step', message: 'the body collapsed at step 293485 (gas volume -2.194628710422476e0 m^3 …)', ...fields });

describe('a stop, said once in the user\'s terms', () => {
  it('names the simulated time in 3 digits, no step count, no raw float, and the ground as the cause', () => {
    const text = explainStop(blowUp({ cause: 'collapsed', time: 12.3456, rolled_back_to: 12.3, step: 293485, volume: -2.194628710422476 }), {
      integrator: 'implicit', dt: 1 / 60, changes: [{ id: 'ground', value: true, time: 11.9 }], groundUnderBody: true,
    });
    expect(text).toMatch(/turned inside out at t = 12\.3 s/);
    expect(text).not.toMatch(/293485|e0|2\.1946/);
    expect(text).toMatch(/ground was switched on with part of the body below it/);
    expect(text.match(/Likely cause/g)).toHaveLength(1);
  });

  it('blames an explicit step above the stable one before a recent change', () => {
    const text = explainStop(blowUp({ cause: 'non_finite', time: 2 }), {
      integrator: 'symplectic', dt: 0.02, stableDt: 5e-4, changes: [{ id: 'integrator', value: 'symplectic', time: 1.5 }],
    });
    expect(text).toMatch(/blew up at t = 2 s/);
    expect(text).toMatch(/time step 0\.02 s is larger than the symplectic integrator's stable step \(0\.0005 s\)/);
  });

  it('names a change made shortly before, and none made long before', () => {
    const ctx = (time: number) => ({ integrator: 'implicit', dt: 1 / 60, changes: [{ id: 'gas.amount', value: 0.0001, time }] });
    expect(explainStop(blowUp({ cause: 'non_finite', time: 10 }), ctx(9))).toMatch(/setting the gas amount to 0\.0001, 1 s before/);
    expect(explainStop(blowUp({ cause: 'non_finite', time: 10 }), ctx(1))).not.toMatch(/gas amount/);
  });

  it('puts a stop in the first second after an import down to the file, not the gas, unless the user changed something since', () => {
    // The teddy (15 pieces) stopped at t = 0.0123 s with "likely cause: too little gas".
    const imported = { name: 'teddy.obj', pieces: 15, minAngle: 3.7, time: 0 };
    const text = explainStop(blowUp({ cause: 'collapsed', time: 0.0123 }), { integrator: 'implicit', dt: 1 / 60, changes: [], imported });
    expect(text).toMatch(/Likely cause: the imported teddy\.obj as it came \(15 pieces, triangles as thin as 3\.7°\), 0\.0123 s after the import/);
    expect(text).toMatch(/largest piece only/);
    expect(text).not.toMatch(/gas/);
    // Later than a second, or after a change of the user's: the usual causes.
    expect(explainStop(blowUp({ cause: 'collapsed', time: 2 }), { integrator: 'implicit', dt: 1 / 60, changes: [], imported })).toMatch(/too little gas/);
    expect(explainStop(blowUp({ cause: 'collapsed', time: 0.5 }), { integrator: 'implicit', dt: 1 / 60, changes: [{ id: 'gas.amount', value: 0.0001, time: 0.4 }], imported })).toMatch(/setting the gas amount/);
    // One piece with even triangles: no thin triangles named, no pieces to leave out.
    const one = explainStop(blowUp({ cause: 'non_finite', time: 0.2 }), { integrator: 'implicit', dt: 1 / 60, changes: [], imported: { name: 'duck.stl', pieces: 1, minAngle: 31, time: 0 } });
    expect(one).toMatch(/the imported duck\.stl as it came \(one piece\)/);
    expect(one).not.toMatch(/thin|largest piece/);
  });

  it('rounds to three significant digits', () => {
    expect(sig3(12.3456)).toBe('12.3');
    expect(sig3(0.016666)).toBe('0.0167');
    expect(sig3(123456)).toBe('1.23e+5');
    expect(sig3(0)).toBe('0');
  });
});

describe('plots', () => {
  it('draw a resting body\'s 1e-22 J of kinetic energy flat beside 30 J of gas', () => {
    const p = new Plots({ getContext: () => null } as unknown as HTMLCanvasElement);
    for (let i = 0; i < 50; i++) p.push(i / 60, [2.5, 12, 1e-22 * (1 + Math.sin(i)), 1.7, 30]);
    const kinetic = p.series[2];
    const [lo, hi] = p.range(kinetic);
    // The range spans at least the group's noise floor: 1e-3 × 30 J; the wiggle (2e-22 J) is
    // then 7e-21 of the plot's height — flat.
    expect(hi - lo).toBeGreaterThanOrEqual(NOISE_FRACTION * 30 * (1 - 1e-12));
    expect(lo).toBe(0);
  });

  it('show a real swing at full height', () => {
    const p = new Plots({ getContext: () => null } as unknown as HTMLCanvasElement);
    for (let i = 0; i < 50; i++) p.push(i / 60, [2.5 + 0.5 * Math.sin(i / 5), 12, 0, 1.7, 30]);
    const [lo, hi] = p.range(p.series[0]);
    expect(hi - lo).toBeGreaterThan(0.9);
  });
});

describe('mirror symmetry', () => {
  it('gives every combination of the chosen axes, the identity first', () => {
    expect(reflections([false, false, false])).toEqual([[1, 1, 1]]);
    expect(reflections([true, false, false])).toEqual([[1, 1, 1], [-1, 1, 1]]);
    expect(reflections([true, true, true])).toHaveLength(8);
    expect(reflect([1.5, 2, 3], [-1, 1, 1], [0.5, 0, 0])).toEqual([-0.5, 2, 3]);
  });

  it('finds a shape symmetric up to its tessellation, and not an asymmetric one', () => {
    // A ring of 12 points around x = 1 (symmetric across x), then one point moved by 0.3 m.
    const ring: number[] = [];
    for (let k = 0; k < 12; k++) ring.push(1 + Math.cos((2 * Math.PI * k) / 12), Math.sin((2 * Math.PI * k) / 12), 0);
    expect(boxCentre(ring)[0]).toBeCloseTo(1, 12);
    expect(isSymmetric(ring, 0, 0.01)).toBe(true);
    const bent = ring.slice();
    bent[3 * 2] += 0.3;
    expect(isSymmetric(bent, 0, 0.01)).toBe(false);
    expect(meanEdge([0, 0, 0, 3, 4, 0], [0, 1])).toBe(5);
  });
});

describe('the panel and the ring', () => {
  it('show a strength on a log scale when its range spans decades', () => {
    const g = new GrabTool();
    g.strength = Math.sqrt(3000); // the geometric middle of 1–3000 1/s
    expect(strengthFraction(g)).toBeCloseTo(0.5, 12);
    const p = new PressTool();
    p.strength = Math.sqrt(0.01 * 0.5); // 0.01–0.5 m spans 50×: log scale too
    expect(strengthFraction(p)).toBeCloseTo(0.5, 12);
    p.strength = 0.5;
    expect(strengthFraction(p)).toBeCloseTo(1, 12);
  });

  it('round numbers to the step\'s digits or three significant digits of the range', () => {
    expect(decimalsFor(5000)).toBe(0);
    expect(decimalsFor(5)).toBe(2);
    expect(decimalsFor(0.05, 0.0005)).toBe(4);
    expect(decimalsFor(0.1, 0.0001)).toBe(4);
  });
});
