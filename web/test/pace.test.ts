// The HUD's pace line (view/pace.ts): it says when the page waits for a step that takes seconds
// instead of repeating the last frame's "real time".
import { describe, expect, it } from 'vitest';
import { paceText, STALL_MS, viewText } from '../src/view/pace';

const base = { playing: true, busy: false, slowMotion: false, realTimeFraction: 1, sinceFrameMs: 16 };

describe('the HUD pace', () => {
  it('shows the last frame’s pace while frames come', () => {
    expect(paceText(base)).toBe('real time');
    expect(paceText({ ...base, slowMotion: true, realTimeFraction: 0.126 })).toBe('13% of real time (slow motion)');
  });
  it('says it waits, and how long, when no frame came for a second while playing', () => {
    expect(paceText({ ...base, sinceFrameMs: STALL_MS - 1 })).toBe('real time');
    expect(paceText({ ...base, sinceFrameMs: 2345 })).toBe('waiting for a step: 2.3 s so far');
  });
  it('says paused when paused, and leaves a long operation to its progress line', () => {
    expect(paceText({ ...base, playing: false, sinceFrameMs: 60000 })).toBe('paused');
    expect(paceText({ ...base, busy: true, sinceFrameMs: 60000 })).toBe('real time');
  });
  it('says, in slow motion, how often the shape changes, not only how often the view redraws it', () => {
    expect(viewText(44.2, 43.9, false)).toBe('view 44 fps');
    expect(viewText(44.2, 2.04, true)).toBe('view 44 fps, new shape 2.0/s');
    expect(viewText(30, 12.4, true)).toBe('view 30 fps, new shape 12/s');
  });
});
