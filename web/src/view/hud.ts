// Text overlays: the readout (fps, simulation time per frame, sizes), the progress of a long
// operation in the worker, messages, and help.

import type { MessageKind, SceneInfo } from '../protocol';

export class Hud {
  private readonly readout: HTMLElement;
  private readonly messages: HTMLElement;
  private readonly help: HTMLElement;
  private readonly busy: HTMLElement;
  private readonly state: HTMLElement;
  private readonly hint: HTMLElement;
  private frames = 0;
  private shapes = 0;
  private lastFps = performance.now();
  fps = 0;
  /** New shapes from the worker drawn per second (`tick`'s `fresh`). */
  shapesPerSecond = 0;

  constructor(root: HTMLElement, helpText: string) {
    this.readout = el(root, 'div', 'readout');
    this.messages = el(root, 'div', 'messages');
    this.busy = el(root, 'div', 'progress');
    this.busy.hidden = true;
    this.help = el(root, 'div', 'help');
    this.help.innerHTML = helpText;
    this.help.hidden = true;
    this.help.addEventListener('click', () => (this.help.hidden = true));
    // What the simulation is doing, where one looks: "paused — Space to play".
    this.state = el(root, 'div', 'state');
    this.state.hidden = true;
    // First visit: where the shortcuts are (until `?` is pressed once).
    this.hint = el(root, 'div', 'hint');
    this.hint.textContent = 'Press ? for the tools and shortcuts';
    this.hint.hidden = seenHelp();
    window.addEventListener('resize', () => this.keepClear());
  }

  /** The paused / slow-motion banner (null: none). */
  setState(text: string | null): void {
    this.state.hidden = text === null;
    if (text !== null && this.state.textContent !== text) this.state.textContent = text;
  }
  get stateText(): string | null { return this.state.hidden ? null : this.state.textContent; }

  shownMessages(): { text: string; kind: string }[] {
    return Array.from(this.messages.children).map((m) => ({ text: m.textContent ?? '', kind: m.className.replace('message ', '') }));
  }

  /**
   * Drop the messages that are not errors (a new model: what they said is about the old one),
   * except those of the last half second: the new model's own report (an import's "imported …,
   * cloth-like") comes just before its first frame.
   */
  clearMessages(): void {
    const now = performance.now();
    for (const m of Array.from(this.messages.children) as HTMLElement[]) if (!m.classList.contains('error') && now - Number(m.dataset.at ?? 0) > 500) m.remove();
  }

  /** One drawn frame; `fresh`: it shows a new shape from the worker. */
  tick(fresh = false): void {
    this.frames++;
    if (fresh) this.shapes++;
    const now = performance.now();
    if (now - this.lastFps >= 500) {
      this.fps = (this.frames * 1000) / (now - this.lastFps);
      this.shapesPerSecond = (this.shapes * 1000) / (now - this.lastFps);
      this.frames = 0;
      this.shapes = 0;
      this.lastFps = now;
    }
  }

  /** Runs after every readout update, so other readings (the panel's P and V) show the same frame. */
  private shown: (() => void)[] = [];
  onShow(f: () => void): void { this.shown.push(f); }

  show(lines: string[]): void {
    const text = lines.join('\n');
    if (this.readout.textContent !== text) {
      this.readout.textContent = text;
      this.keepClear();
    }
    for (const f of this.shown) f();
  }

  /**
   * The readout's lines end before what stands to their right at the top of the window: the
   * "Press ?" hint while it shows, else the panel (#panel, lil-gui). A longer line (slow motion,
   * time-limited steps, threads, recording) wraps onto the next line instead of running under
   * them, and the hint and the panel never move for it: before, the first line ran under the
   * panel in slow motion, and the hint jumped below the readout (70 px) when it grew.
   */
  private keepClear(): void {
    const panel = document.getElementById('panel')?.getBoundingClientRect();
    const hint = this.hint.hidden ? null : this.hint.getBoundingClientRect();
    const limit = Math.min(hint && hint.width > 0 ? hint.left : Infinity, panel && panel.width > 0 ? panel.left : Infinity, window.innerWidth);
    const left = this.readout.getBoundingClientRect().left;
    const width = `${Math.max(READOUT_MIN_WIDTH, Math.floor(limit - READOUT_GAP - left))}px`;
    if (this.readout.style.maxWidth !== width) this.readout.style.maxWidth = width;
  }

  /** A long operation under way ("subdividing", with the fraction done if known), or none (null). */
  progress(label: string | null, fraction?: number): void {
    this.busy.hidden = label === null;
    if (label !== null) this.busy.textContent = `${label}…${fraction === undefined ? '' : ` ${Math.round(100 * fraction)}%`}`;
  }
  get progressText(): string | null { return this.busy.hidden ? null : this.busy.textContent; }

  /**
   * A message, dismissed by a click or after `messageLifetime` (an error 10 s or longer for a
   * long one); `sticky`: it stays until clicked (the page cannot go on: reload it).
   */
  message(text: string, kind: MessageKind = 'info', sticky = false): void {
    // The same text again replaces itself; at most four messages stay (the oldest go first).
    for (const old of Array.from(this.messages.children)) if (old.textContent === text) old.remove();
    while (this.messages.children.length >= 4) this.messages.firstElementChild!.remove();
    const m = el(this.messages, 'div', `message ${kind}`);
    m.dataset.at = String(performance.now());
    m.textContent = text;
    m.title = 'click to dismiss';
    m.addEventListener('click', () => m.remove());
    const lifetime = messageLifetime(text, kind, sticky);
    if (lifetime !== null) setTimeout(() => m.remove(), lifetime);
  }

  toggleHelp(show?: boolean): void {
    this.help.hidden = show === undefined ? !this.help.hidden : !show;
    if (!this.help.hidden) {
      this.hint.hidden = true;
      this.keepClear();
      try { localStorage.setItem(HELP_SEEN, '1'); } catch { /* not kept */ }
    }
  }
  get hintVisible(): boolean { return !this.hint.hidden; }
  get helpVisible(): boolean { return !this.help.hidden; }
}

/** The space kept between the readout and the hint or the panel (px). */
const READOUT_GAP = 10;
/** The readout is never narrower than this (px; a window narrower than the panel leaves no room). */
const READOUT_MIN_WIDTH = 240;

/** How long a message stays on screen at least: a note, a warning, an error (ms). */
export const MESSAGE_MS: Record<MessageKind, number> = { info: 4000, warn: 8000, error: 10000 };
/** Reading time of a long warning or error: ms per character (about 14 characters a second), after 2 s to notice it. */
const READ_MS_PER_CHAR = 70;
/** The longest a message stays (ms): the HUD shows at most four, the oldest go first anyway. */
export const MESSAGE_MAX_MS = 30000;

/**
 * How long a message stays before it goes by itself (ms), or null: until clicked (`sticky`).
 * A note 4 s; a warning or an error 8 s or 10 s, longer when its text takes longer to read
 * (an error used to stay until clicked, piling up red boxes over the model).
 */
export function messageLifetime(text: string, kind: MessageKind, sticky = false): number | null {
  if (sticky) return null;
  if (kind === 'info') return MESSAGE_MS.info;
  return Math.min(MESSAGE_MAX_MS, Math.max(MESSAGE_MS[kind], 2000 + READ_MS_PER_CHAR * text.length));
}

/** The HUD line of an open scene. */
export function sceneLine({ name, time, duration, bodies }: SceneInfo): string {
  return `scene ${name}: ${bodies} ${bodies === 1 ? 'body' : 'bodies'}   t ${time.toFixed(2)} of ${duration} s${time >= duration ? ' (events done)' : ''}`;
}

const HELP_SEEN = 'softsculpt.helpSeen';
function seenHelp(): boolean {
  try { return localStorage.getItem(HELP_SEEN) === '1'; } catch { return false; }
}

function el(parent: HTMLElement, tag: string, cls: string): HTMLElement {
  const e = document.createElement(tag);
  e.className = cls;
  parent.appendChild(e);
  return e;
}
