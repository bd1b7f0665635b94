import { describe, expect, it } from 'vitest';
import { supersede } from '../src/supersede';
import type { Frame } from '../src/protocol';

const frame = (extra: Partial<Frame> = {}): Frame => ({
  positions: new Float32Array(3), stats: {} as Frame['stats'], simMs: 0, slowMotion: false, realTimeFraction: 1, accuracy: 0, scene: null, ...extra,
});

describe('a frame superseded before it was drawn', () => {
  it('keeps what was sent once: the parameter table, the material presets (the material list appears) and the thread count', () => {
    const table = [{ id: 'stiffness' }] as unknown as Frame['table'];
    const presets = [{ name: 'clay', help: 'material: clay' }];
    const first = frame({ table, presets, threads: 2, history: [0, 0] });
    const next = frame({ positions: new Float32Array([1, 2, 3]), history: [1, 0] });
    const merged = supersede(first, next);
    expect(merged.table).toBe(table);
    expect(merged.presets).toBe(presets);
    expect(merged.threads).toBe(2);
    // The newer's own fields win.
    expect(merged.history).toEqual([1, 0]);
    expect(Array.from(merged.positions)).toEqual([1, 2, 3]);
  });

  it('does not carry a recording the newer frame says is over', () => {
    const merged = supersede(frame({ recording: { frames: 3, seconds: 0.05 } }), frame());
    expect(merged.recording).toBeUndefined();
  });
});
