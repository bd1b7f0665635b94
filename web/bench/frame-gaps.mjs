// The main thread's longest frame gap (ms between requestAnimationFrame timestamps) while the
// modeler loads the built-in bunny, subdivides it, imports a 40,962-vertex icosphere, subdivides
// that, and imports a 163,842-vertex one (simulation playing, default settings); with the Long
// Tasks the page reported meanwhile.
//   node bench/frame-gaps.mjs [DIST…]   (default: dist; e.g. `dist /tmp/softsculpt-main-dist`
//   to compare with the main-thread version built by bench/baseline.sh, in one run)
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { frameGaps, launch, openModeler, startServer } from '../e2e/harness.mjs';
import { writeIcosphere } from '../e2e/icosphere.mjs';

const dists = process.argv.slice(2).length ? process.argv.slice(2) : ['dist'];
const dir = mkdtempSync(join(tmpdir(), 'gaps-'));
const l6 = writeIcosphere(dir, 6), l7 = writeIcosphere(dir, 7);
const browser = await launch();

for (const [k, dist] of dists.entries()) {
  const server = await startServer(5190 + k, dist);
  const { page } = await openModeler(browser, server.url);
  await page.waitForTimeout(1000);
  const rows = [];
  const run = async (label, action, until, arg) => {
    // From the command until the animation frame that shows the new model (the same window for
    // every build; what is drawn after it is the new model's drawing cost, not loading).
    const r = await frameGaps(page, action, until, arg, { settleMs: 0, timeout: 300000 });
    rows.push({ label, ...r });
    console.log(`${dist}  ${label.padEnd(34)} longest gap ${String(r.maxGapMs).padStart(6)} ms   long tasks ${r.longTasks.length} (max ${Math.max(0, ...r.longTasks)} ms)   ${r.ms} ms in all`);
  };
  const builtin = page.locator('#panel .lil-controller', { hasText: 'built-in' }).locator('select');
  await run('load the bunny (1,839 vertices)', () => builtin.selectOption('bunny'), () => window.softsculpt.vertexCount() === 1839);
  await run('subdivide the bunny', () => page.keyboard.press('u'), () => window.softsculpt.vertexCount() > 1839);
  const input = page.locator('input[data-picker=import]');
  await run('import 40,962 vertices', () => input.setInputFiles(l6), () => window.softsculpt.vertexCount() === 40962);
  await run('subdivide it (to 163,842)', () => page.keyboard.press('u'), () => window.softsculpt.vertexCount() === 163842);
  await run('import 163,842 vertices', () => input.setInputFiles(l7), () => window.softsculpt.vertexCount() === 163842 && /imported icosphere_L7/.test(window.softsculpt.lastMessage()));
  await page.context().close();
  server.stop();
}
await browser.close();
