// Issue 37's small page defects where the logic is pure: the panel fields' digits, the HUD's
// volume of an open surface, how long a message stays. (The page itself: e2e/details.test.mjs.)

import { describe, expect, it } from 'vitest';
import { fieldText, volumeText } from '../src/format';
import { MESSAGE_MAX_MS, messageLifetime } from '../src/view/hud';

describe('a panel field\'s number', () => {
  it('has no float noise (the issue\'s fields)', () => {
    expect(fieldText(0.35 / 1.2 ** 3)).toBe('0.2025'); // was 0.20254629629629634
    expect(fieldText(0.35 * 1.2 / 1.2 + 5e-17)).toBe('0.35'); // 0.35000000000000003
    expect(fieldText(0.1 + 0.2)).toBe('0.3');
  });

  it('keeps every digit of everyday values, and small values readable', () => {
    for (const [v, t] of [[100, '100'], [9.81, '9.81'], [5000, '5000'], [1 / 60, '0.01667'], [1e-6, '0.000001'], [2.5e-8, '2.5e-8'], [0, '0'], [-0.25, '-0.25'], [600, '600']] as const) expect(fieldText(v)).toBe(t);
  });

  it('changes a value by less than the display precision (4 significant digits)', () => {
    for (const v of [0.20254629629629634, 123456.789, 3.14159265, 7.777777e-5]) {
      expect(Math.abs(Number(fieldText(v)) - v)).toBeLessThanOrEqual(5e-4 * Math.abs(v));
    }
  });
});

describe('the HUD\'s volume', () => {
  it('is a volume for a closed body and none for an open surface (no "V −1.08 m³" for a cloth)', () => {
    expect(volumeText(2.4512, true)).toBe('V 2.45 m³');
    expect(volumeText(-1.08, false)).not.toMatch(/\d/);
    expect(volumeText(-1.08, false)).toMatch(/open surface/);
  });
});

describe('a message\'s time on screen', () => {
  it('an error goes by itself after 10 s (it stayed until clicked), a long one later', () => {
    expect(messageLifetime('could not import garbage.obj: line 1', 'error')).toBe(10000);
    const long = messageLifetime('x'.repeat(300), 'error')!;
    expect(long).toBeGreaterThan(20000);
    expect(long).toBeLessThanOrEqual(MESSAGE_MAX_MS);
    expect(messageLifetime('x'.repeat(5000), 'error')).toBe(MESSAGE_MAX_MS);
  });

  it('notes and warnings as before (4 s, 8 s), a long warning longer; a sticky message stays', () => {
    expect(messageLifetime('playing', 'info')).toBe(4000);
    expect(messageLifetime('paused: the grab acts while the simulation plays', 'warn')).toBe(8000);
    expect(messageLifetime('x'.repeat(200), 'warn')!).toBeGreaterThan(8000);
    expect(messageLifetime('the engine could not start', 'error', true)).toBeNull();
  });
});
