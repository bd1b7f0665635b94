// End-to-end harness: serve the built modeler (web/dist) on 127.0.0.1 and drive Debian's chromium
// with playwright-core. Screenshots go to e2e/screenshots/ (ignored by git).

import { spawn } from 'node:child_process';
import { after, before } from 'node:test';
import { join } from 'node:path';
import { mkdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const WEB = fileURLToPath(new URL('..', import.meta.url));
export const SHOTS = fileURLToPath(new URL('./screenshots/', import.meta.url));
mkdirSync(SHOTS, { recursive: true });

/** `vite preview` of the built modeler (`outDir`: another build, e.g. a baseline for benchmarks). */
/** The port of the e2e server: 5199, or E2E_PORT (when another checkout's tests hold 5199). */
export async function startServer(port = Number(process.env.E2E_PORT ?? 5199), outDir = 'dist') {
  // Something already answering on the port would be tested instead (an old server, an old build).
  const url = `http://127.0.0.1:${port}/`;
  if (await fetch(url).then(() => true, () => false)) throw new Error(`port ${port} is in use: stop what serves ${url} first`);
  // Vite's own entry run by this node (no npx wrapper), in its own process group, so that
  // stopping it stops the server itself and nothing keeps the test process alive.
  const vite = fileURLToPath(new URL('../node_modules/vite/bin/vite.js', import.meta.url));
  const proc = spawn(process.execPath, [vite, 'preview', '--host', '127.0.0.1', '--port', String(port), '--strictPort', '--outDir', outDir], { cwd: WEB, stdio: ['ignore', 'pipe', 'pipe'], detached: true });
  let out = '';
  proc.stdout.on('data', (d) => (out += d));
  proc.stderr.on('data', (d) => (out += d));
  const stop = () => {
    try { process.kill(-proc.pid, 'SIGTERM'); } catch {}
    proc.stdout.destroy();
    proc.stderr.destroy();
    proc.unref();
  };
  for (let i = 0; i < 150; i++) {
    try {
      const r = await fetch(url);
      if (r.ok) return { url, stop };
    } catch {}
    await new Promise((r) => setTimeout(r, 100));
  }
  stop();
  throw new Error(`the preview server did not start: ${out}`);
}

/** A test file's preview server and browser, started before its tests and stopped after them. */
export function browserSuite() {
  const suite = { server: null, browser: null };
  before(async () => {
    suite.server = await startServer();
    suite.browser = await launch();
  });
  after(async () => {
    await suite.browser?.close();
    suite.server?.stop();
  });
  return suite;
}

export const shot = (page, name) => page.screenshot({ path: join(SHOTS, `${name}.png`) });

export async function launch() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run'],
  });
}

/** A fresh page (own storage) on the modeler, ready. */
export async function openModeler(browser, url, context) {
  const ctx = context ?? (await browser.newContext({ viewport: { width: 1280, height: 800 }, acceptDownloads: true }));
  const page = await ctx.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(url);
  await page.waitForFunction(() => window.softsculpt?.ready === true, null, { timeout: 30000 });
  return { page, ctx, errors };
}

export const inspect = (page, expr, arg) => page.evaluate(expr, arg);

/** Wait until `s` more simulated seconds have passed (the page's clock, not the wall's); on a
 * timeout, say where the simulation stood. */
export async function simulate(page, s, timeout = 90000) {
  const t0 = await inspect(page, () => window.softsculpt.stats().time);
  try {
    await page.waitForFunction(([t, d]) => window.softsculpt.stats().time > t + d, [t0, s], { timeout });
  } catch (e) {
    const state = await inspect(page, () => ({ time: window.softsculpt.stats().time, playing: window.softsculpt.playing(), message: window.softsculpt.lastMessage() }));
    throw new Error(`${s} s of simulation from t = ${t0} s did not pass: ${JSON.stringify(state)}`);
  }
}

/** Wait until the body is (nearly) still. */
export async function settle(page, speed = 0.02, timeout = 20000) {
  await page.waitForFunction((s) => window.softsculpt.stats().maxSpeed < s, speed, { timeout, polling: 100 });
}

/** The vertex with the largest y (the top of the model) and its screen position. */
export async function topVertex(page) {
  return page.evaluate(() => {
    const x = window.softsculpt.positions();
    let best = 0;
    for (let i = 0; i < x.length / 3; i++) if (x[3 * i + 1] > x[3 * best + 1]) best = i;
    return { index: best, screen: window.softsculpt.screenOf(best), position: x.slice(3 * best, 3 * best + 3) };
  });
}

/**
 * Press at `from`, move to `to` in `steps` moves, and keep the button down for `hold` more
 * simulated seconds (the page's clock: a loaded machine simulates slower, and holds longer).
 */
export async function drag(page, from, to, steps = 20, hold = 0) {
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let i = 1; i <= steps; i++) {
    await page.mouse.move(from.x + ((to.x - from.x) * i) / steps, from.y + ((to.y - from.y) * i) / steps);
    await page.waitForTimeout(20); // paces the moves, as a hand does (pointer events, not an outcome)
  }
  if (hold) await simulate(page, hold);
}

/**
 * Wait for `n` more animation frames of the page: what the page does by itself on an input (the
 * camera, the brush ring, the banner, the panel) is done and drawn by then. Counted in
 * requestAnimationFrame callbacks, not milliseconds.
 */
export async function animationFrames(page, n = 3) {
  await page.evaluate((k) => new Promise((done) => {
    let i = 0;
    const f = () => (++i >= k ? done() : requestAnimationFrame(f));
    requestAnimationFrame(f);
  }), n);
}

export const vertex = (page, i) => page.evaluate((j) => window.softsculpt.positions().slice(3 * j, 3 * j + 3), i);
export const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

/**
 * Record, in the page, the longest gap between requestAnimationFrame callbacks and the Long
 * Tasks (PerformanceObserver 'longtask') from now until `until` (a page function of `arg`) holds,
 * checked in every animation frame (so what the page draws after that is not counted), then
 * `settleMs` more. `action(aside)` runs meanwhile; `aside(f)` runs the test's own `f` (a
 * screenshot, which stalls the page to capture it) with the recording paused. `startPaused`:
 * recording begins when the first `aside` returns. Returns { maxGapMs, longTasks: [ms…], ms }.
 */
export async function frameGaps(page, action, until, arg, { timeout = 180000, settleMs = 500, startPaused = false } = {}) {
  await page.evaluate(({ src, arg, settleMs, startPaused }) => {
    const w = window;
    if (!w.__gaps) {
      w.__gaps = { on: false, last: 0, max: 0, long: [] };
      // Timed with performance.now() in the callback: the timestamp a frame is given can predate
      // a long block of the main thread (the frame was begun before it), and would hide it.
      const loop = () => {
        const t = performance.now();
        const g = w.__gaps;
        if (g.on) {
          g.max = Math.max(g.max, t - g.last);
          g.last = t;
          if (!g.doneAt && g.until()) g.doneAt = t;
          if (g.doneAt && t - g.doneAt >= g.settleMs) { g.on = false; g.ms = t - g.t0; }
        }
        requestAnimationFrame(loop);
      };
      requestAnimationFrame(loop);
      new PerformanceObserver((list) => { for (const e of list.getEntries()) if (w.__gaps.on) w.__gaps.long.push(Math.round(e.duration)); }).observe({ type: 'longtask' });
    }
    const until = new Function('arg', `return (${src})(arg);`);
    Object.assign(w.__gaps, { on: !startPaused, paused: startPaused, last: performance.now(), max: 0, long: [], t0: performance.now(), doneAt: 0, ms: undefined, settleMs, until: () => until(arg) });
  }, { src: until.toString(), arg, settleMs, startPaused });
  const aside = async (f) => {
    await page.evaluate(() => { const g = window.__gaps; if (g.on) g.max = Math.max(g.max, performance.now() - g.last); g.paused ||= g.on; g.on = false; });
    await f();
    await page.evaluate(() => { const g = window.__gaps; if (g.paused) Object.assign(g, { on: true, paused: false, last: performance.now() }); });
  };
  await action(aside);
  await page.waitForFunction(() => !window.__gaps.on && window.__gaps.ms !== undefined, null, { timeout, polling: 100 });
  return page.evaluate(() => {
    const g = window.__gaps;
    return { maxGapMs: Math.round(g.max), longTasks: g.long, ms: Math.round(g.ms) };
  });
}

/**
 * Wait (up to `timeout` ms) until `cond(arg)` holds in the page, then return: the assertion that
 * follows says what is there if it never did. For outcomes the page shows without simulating
 * (the camera, a message, the panel), where there is no simulated time to wait for.
 */
export const until = (page, cond, arg, timeout = 30000) => page.waitForFunction(cond, arg, { timeout, polling: 50 }).catch(() => {});

/**
 * Wait until `value(arg)`, a page function giving JSON data, has stayed the same over `frames`
 * animation frames in a row (a view that has eased to rest, the last frame stepped before a
 * pause drawn: the worker's tick under way when the pause came, then its frame, take far fewer
 * than 30 of the page's frames); on a timeout, say what it last was.
 */
export async function steady(page, value, arg, { frames = 30, timeout = 30000 } = {}) {
  await page.evaluate(() => { window.__steady = { last: undefined, count: 0 }; });
  try {
    await page.waitForFunction(({ src, arg, frames }) => {
      const s = window.__steady, v = JSON.stringify(new Function('arg', `return (${src})(arg);`)(arg));
      if (v !== s.last) { s.last = v; s.count = 0; }
      return ++s.count >= frames;
    }, { src: value.toString(), arg, frames }, { timeout, polling: 'raf' });
  } catch (e) {
    throw new Error(`${value} did not stay the same for ${frames} frames: last ${await page.evaluate(() => window.__steady.last)}`);
  }
}

/**
 * Wait until the page has kept what a reload or a restart brings back: the worker's autosave
 * (IndexedDB, src/storage.ts) holding `undo` undo steps and, with `camera`, the camera as it is
 * now (localStorage, 'softsculpt.camera'). Checked every animation frame; returns whether it
 * came within `timeout` ms.
 */
export const autosaved = (page, undo, { camera = false, timeout = 30000 } = {}) => page.evaluate(async ({ undo, camera, timeout }) => {
  const record = () => new Promise((resolve) => {
    // As the page opens it (storage.ts): version 1, the store made if the database is new.
    const r = indexedDB.open('softsculpt', 1);
    r.onupgradeneeded = () => r.result.createObjectStore('projects');
    r.onerror = () => resolve(null);
    r.onsuccess = () => {
      const db = r.result, store = db.transaction('projects', 'readonly').objectStore('projects');
      const pointer = store.get('autosave-current');
      pointer.onerror = () => { db.close(); resolve(null); };
      pointer.onsuccess = () => {
        if (!pointer.result) { db.close(); resolve(null); return; }
        const slot = store.get(pointer.result);
        slot.onsuccess = () => { db.close(); resolve(slot.result ?? null); };
        slot.onerror = () => { db.close(); resolve(null); };
      };
    };
  });
  const cameraKept = () => {
    const kept = JSON.parse(localStorage.getItem('softsculpt.camera') ?? 'null')?.position;
    const here = window.softsculpt.camera();
    return kept && Math.hypot(kept[0] - here[0], kept[1] - here[1], kept[2] - here[2]) < 1e-9;
  };
  const t0 = performance.now();
  for (;;) {
    const rec = await record();
    if (rec?.history?.undo?.length === undo && (!camera || cameraKept())) return true;
    if (performance.now() - t0 > timeout) return false;
    await new Promise((r) => requestAnimationFrame(r));
  }
}, { undo, camera, timeout });
