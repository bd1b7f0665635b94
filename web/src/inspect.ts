// `window.softsculpt`: a small read-only inspection handle for tests and the curious. It reads
// the page's mirror of the latest frame drawn (positions as drawn, in f32), synchronously;
// reading it never changes the model. `ready` turns true when the first frame of the model has
// been drawn.

import { Vector3 } from 'three';
import type { App } from './app';
import type { Params } from './protocol';

const num = (v: unknown) => (typeof v === 'number' ? v : typeof v === 'boolean' ? Number(v) : undefined);
const vec = (p: Params, k: number) => (Array.isArray(p.wind) ? p.wind[k] : undefined);
/** The page's parameter names before the engine's table ids, as numbers (kept so scripts and tests reading them go on working). */
const LEGACY: Record<string, (p: Params) => number | undefined> = {
  springDamping: (p) => num(p.spring_damping), bendingStiffness: (p) => num(p.bending), gasAmount: (p) => num(p['gas.amount']),
  temperature: (p) => num(p['gas.temperature']), windX: (p) => vec(p, 0), windY: (p) => vec(p, 1), windZ: (p) => vec(p, 2),
  windDrag: (p) => num(p.wind_drag), groundOn: (p) => num(p.ground), groundHeight: (p) => num(p['ground.height']),
  friction: (p) => num(p['ground.friction']), totalMass: (p) => num(p.mass), selfCollision: (p) => num(p.self_collision),
  ambientPressure: (p) => num(p['gas.ambient']),
};

export function inspector(app: App) {
  const m = app.mirror;
  return {
    get ready() { return m.ready; },
    /** Threads the engine steps on (2 or more: the threaded build; `?threads=1` in the address forces one). */
    threads: () => m.threads,
    vertexCount: () => m.vertexCount,
    /** Bodies drawn: the active one and the others (a scene's, an import's pieces). */
    bodies: () => 1 + m.others.length,
    faceCount: () => m.faceCount,
    springCount: () => m.springCount,
    /** The active body's triangles (vertex indices, three per face). */
    triangles: () => Array.from(m.triangles),
    positions: () => Array.from(m.positions),
    pinned: () => Array.from(m.pinned),
    masses: () => Array.from(m.masses),
    stats: () => structuredClone(m.stats),
    /** A parameter by its table id (docs/parameters.md), or by the page's earlier name (`groundOn`, `windX`, …) as a number. */
    param: (name: string) => (name in m.params ? m.params[name] : LEGACY[name]?.(m.params)),
    tool: () => app.tools.tool.name,
    scene: () => (m.scene ? { ...m.scene } : null),
    playing: () => m.settings.playing,
    settings: () => ({ ...m.settings }),
    history: () => [...m.history] as [number, number],
    lastMessage: () => app.lastMessageText,
    fps: () => app.hud.fps,
    /** New shapes from the worker drawn per second (the view redraws between them). */
    shapesPerSecond: () => app.hud.shapesPerSecond,
    slowMotion: () => m.slowMotion,
    simMs: () => m.simMs,
    /** The long operation the simulation is busy with ("subdividing"…), or null. */
    busy: () => app.busy,
    helpVisible: () => app.hud.helpVisible,
    camera: () => app.viewport.camera.position.toArray(),
    /** The view's drawing: the buffer's pixel ratio (on a software renderer below 1 in a window above 0.3 Mpx, unless `full`), whether WebGL runs without a GPU, renders so far. */
    drawing: () => ({ pixelRatio: app.viewport.resolution, software: app.viewport.software, full: app.viewport.fullResolution, renders: app.viewport.renders }),
    /** The camera controls: mode, target, and the camera's up and right axes (a level horizon: right.y = 0). */
    view: () => {
      const c = app.viewport.camera;
      c.updateMatrixWorld();
      const e = c.matrixWorld.elements;
      return { mode: app.viewport.rig.mode, target: app.viewport.rig.target.toArray(), position: c.position.toArray(), right: [e[0], e[1], e[2]], up: [e[4], e[5], e[6]] };
    },
    /** The brush ring as last drawn: radius (m), strength fraction, copies (mirror images), their centres (m), or null. */
    ring: () => (app.cursor.ring.shown ? { ...app.cursor.ring.shown } : null),
    brush: () => ({ radius: app.brush.radius, strength: app.tools.tool.strength }),
    symmetry: () => [...app.symmetryAxes],
    /** Each vertex's strain l/L − 1 while the strain view is on, else []. */
    strain: () => Array.from(m.strain),
    // --- page leftovers (#10): the overlay and the plots, for e2e/leftovers.test.mjs ---
    /** Whether the body is drawn with a colour overlay (mass, pins, strain) rather than its plain colour. */
    overlay: () => app.viewport.surface.material.vertexColors,
    /** The plots' series as drawn: label and values (oldest first). */
    plots: () => app.plots.series.map((s) => ({ label: s.label, values: [...app.plots.shown(s)] })),
    // --- end page leftovers ---
    /** The banner at the top ("Paused — Space to play", an adjusting value) or null. */
    banner: () => app.hud.stateText,
    hintVisible: () => app.hud.hintVisible,
    /** Every message shown now: { text, kind }. */
    messages: () => app.hud.shownMessages(),
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
    /** Body k's positions as drawn (0: the first; an import's pieces, a scene's bodies follow). */
    bodyPositions: (k: number) => Array.from(m.shapes()[k]?.positions ?? []),
    /** Project a point (m) to page pixels. */
    screenOfPoint: (q: [number, number, number]) => {
      const v = app.viewport;
      const p = new Vector3(q[0], q[1], q[2]).project(v.camera);
      const r = v.canvas.getBoundingClientRect();
      return { x: r.left + ((p.x + 1) / 2) * r.width, y: r.top + ((1 - p.y) / 2) * r.height };
    },
    /** The wind arrow as drawn last: whether it shows, its tail and tip in page pixels. */
    windArrow: () => {
      const v = app.viewport, a = v.windArrow;
      const dir = new Vector3(0, 1, 0).applyQuaternion(a.quaternion);
      // ArrowHelper: a line of length − head, then the cone (scale y: the head's length).
      const tip = a.position.clone().addScaledVector(dir, a.line.scale.y + a.cone.scale.y);
      const r = v.canvas.getBoundingClientRect();
      const px = (q: Vector3) => { const p = q.clone().project(v.camera); return { x: r.left + ((p.x + 1) / 2) * r.width, y: r.top + ((1 - p.y) / 2) * r.height }; };
      return { visible: a.visible, tail: px(a.position), tip: px(tip) };
    },
    /** Project coordinates of vertex i to page pixels (for driving the mouse in tests). */
    screenOf: (i: number) => {
      const x = m.positions;
      const v = app.viewport;
      const p = new Vector3(x[3 * i], x[3 * i + 1], x[3 * i + 2]).project(v.camera);
      const r = v.canvas.getBoundingClientRect();
      return { x: r.left + ((p.x + 1) / 2) * r.width, y: r.top + ((1 - p.y) / 2) * r.height };
    },
  };
}
