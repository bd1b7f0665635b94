// `window.softsculpt`: a small read-only inspection handle for tests and the curious.
// Reading it never changes the model.

import { Vector3 } from 'three';
import type { App } from './app';

export function inspector(app: App) {
  return {
    ready: true,
    vertexCount: () => app.body().vertexCount,
    faceCount: () => app.body().faceCount,
    springCount: () => app.body().springCount,
    positions: () => Array.from(app.body().positions()),
    pinned: () => Array.from(app.body().pinned()),
    masses: () => Array.from(app.body().masses()),
    stats: () => app.body().stats(),
    param: (name: string) => app.body().get(name as never),
    tool: () => app.tools.tool.name,
    scene: () => app.sceneInfo,
    playing: () => app.settings.playing,
    settings: () => ({ ...app.settings }),
    history: () => app.history.sizes,
    lastMessage: () => app.lastMessageText,
    fps: () => app.hud.fps,
    slowMotion: () => app.slowMotion,
    simMs: () => app.simMs,
    helpVisible: () => app.hud.helpVisible,
    camera: () => app.viewport.camera.position.toArray(),
    pixels: () => {
      // Distinct colours in a 64×64 sample of the rendered view (the canvas keeps its buffer).
      const c = document.createElement('canvas');
      c.width = 64; c.height = 64;
      const g = c.getContext('2d')!;
      g.drawImage(app.viewport.canvas, 0, 0, 64, 64);
      const d = g.getImageData(0, 0, 64, 64).data;
      const seen = new Set<number>();
      for (let i = 0; i < d.length; i += 4) seen.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
      return seen.size;
    },
    /** Project coordinates of vertex i to page pixels (for driving the mouse in tests). */
    screenOf: (i: number) => {
      const x = app.body().positions();
      const v = app.viewport;
      const p = new Vector3(x[3 * i], x[3 * i + 1], x[3 * i + 2]).project(v.camera);
      const r = v.canvas.getBoundingClientRect();
      return { x: r.left + ((p.x + 1) / 2) * r.width, y: r.top + ((1 - p.y) / 2) * r.height };
    },
  };
}
