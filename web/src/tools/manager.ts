// Routes pointer events (mouse, pen, touch) to the active tool. A press on the body starts the
// tool's drag and switches the camera off until the button is released; elsewhere the camera's
// controls have the pointer; a second finger is the camera's too (turn and pinch-zoom).

import type { Tool, ToolContext } from './tool';
import { pickBody } from './pick';

export class ToolManager {
  private active: Tool;
  private dragging: Tool | null = null;
  private readonly down = (ev: PointerEvent) => this.onDown(ev);
  private readonly moveHandler = (ev: PointerEvent) => { if (this.dragging) this.dragging.move(ev); };
  private readonly up = () => this.onUp();

  /**
   * `enabled`: whether a press may start a stroke now (not while the simulation is busy loading);
   * `allowed`: whether this tool can act now (it says why not itself).
   */
  constructor(private readonly ctx: ToolContext, readonly tools: Tool[], private readonly onChange: (t: Tool) => void,
    private readonly enabled: () => boolean = () => true, private readonly allowed: (t: Tool) => boolean = () => true) {
    this.active = tools[0];
    this.active.connect(ctx);
    const canvas = ctx.viewport.canvas;
    // Capture phase: we decide before the trackball sees the press.
    canvas.addEventListener('pointerdown', this.down, { capture: true });
    window.addEventListener('pointermove', this.moveHandler);
    window.addEventListener('pointerup', this.up);
    window.addEventListener('pointercancel', this.up);
  }

  get tool(): Tool { return this.active; }
  get isDragging(): boolean { return this.dragging !== null; }

  select(name: string): void {
    const t = this.tools.find((x) => x.name === name);
    if (!t || t === this.active) return;
    this.onUp();
    this.active.disconnect();
    this.active = t;
    t.connect(this.ctx);
    this.onChange(t);
  }

  private onDown(ev: PointerEvent): void {
    // A second finger: the camera's gesture (turn, pinch-zoom), not a stroke; one under way ends.
    if (!ev.isPrimary) { this.onUp(); return; }
    if (ev.button !== 0 || !this.enabled()) return;
    const hit = pickBody(this.ctx.viewport, ev); // any body: the stroke acts on the one under the pointer
    if (!hit && !this.active.anywhere) return;
    // A tool that can do nothing now (a drag while paused) says so and takes nothing.
    if (!this.allowed(this.active)) { ev.stopImmediatePropagation(); ev.preventDefault(); return; }
    // Nothing under the brush: said, and the press is nobody's (no stroke, no undo step, no turn).
    const why = hit ? this.active.refusal?.(hit) : null;
    if (why) { this.ctx.message(why, 'warn'); ev.stopImmediatePropagation(); ev.preventDefault(); return; }
    if (!this.active.start(hit ?? null, ev)) return;
    this.dragging = this.active;
    this.ctx.viewport.controls.enabled = false;
    ev.stopImmediatePropagation();
    ev.preventDefault();
  }

  private onUp(): void {
    if (!this.dragging) return;
    const t = this.dragging;
    this.dragging = null;
    t.end();
    this.ctx.viewport.controls.enabled = true;
  }

  dispose(): void {
    const canvas = this.ctx.viewport.canvas;
    canvas.removeEventListener('pointerdown', this.down, { capture: true });
    window.removeEventListener('pointermove', this.moveHandler);
    window.removeEventListener('pointerup', this.up);
    window.removeEventListener('pointercancel', this.up);
    for (const t of this.tools) t.dispose();
  }
}
