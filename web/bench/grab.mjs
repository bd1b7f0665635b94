// The grab as a user meets it, in Chromium at the modeler's default settings: the mushroom
// subdivided (U pressed, as a user would) SUB times, left to settle, its top dragged with the
// mouse (default tool, mirror X as the panel has it) and held, then let go. Prints simulated
// seconds per real second in each phase (1 = real time) and, at the end of the hold, how far
// the top vertex (under the cursor when the drag began) is from the cursor on the screen;
// screenshots in e2e/screenshots/bench-grab-*.png.
//   node bench/grab.mjs [SUB=2] [DIST…]
// (needs web/dist built; several builds, e.g. `dist /tmp/base-dist`, are measured side by side,
// one page at a time, in the order given, ROUNDS times: env ROUNDS, default 1; a DIST may end in
// an address query, e.g. `dist 'dist?threads=1'`: the threaded page against one thread)
import { drag, launch, openModeler, shot, startServer, topVertex } from '../e2e/harness.mjs';

const sub = Number(process.argv[2] ?? 2);
const dists = process.argv.length > 3 ? process.argv.slice(3) : ['dist'];
const rounds = Number(process.env.ROUNDS ?? 1);
const browser = await launch();
const servers = [];
for (const [k, dist] of dists.entries()) {
  const [dir, query] = dist.split('?');
  const s = await startServer(Number(process.env.E2E_PORT ?? 5187) + k, dir);
  servers.push({ dist, ...s, url: query ? `${s.url}?${query}` : s.url });
}

/** Simulated seconds per real second over `ms` of wall time while `during` runs. */
async function rate(page, ms, during) {
  const t0 = await page.evaluate(() => [window.softsculpt.stats().time, performance.now()]);
  await Promise.all([page.waitForTimeout(ms), during?.()]);
  const t1 = await page.evaluate(() => [window.softsculpt.stats().time, performance.now()]);
  return (t1[0] - t0[0]) / ((t1[1] - t0[1]) / 1000);
}

console.log(`mushroom subdivided ${sub}×; simulated s per real s (1 = real time)`);
console.log('build  vertices  at rest  pull+hold 4 s  released 0-5 s  released 5-10 s  vertex to cursor');
for (let r = 0; r < rounds; r++) {
  for (const [k, { dist, url }] of servers.entries()) {
    const { page, ctx, errors } = await openModeler(browser, url);
    for (let s = 0; s < sub; s++) {
      const n = await page.evaluate(() => window.softsculpt.vertexCount());
      await page.keyboard.press('u');
      await page.waitForFunction((m) => window.softsculpt.vertexCount() > m && !window.softsculpt.busy(), n, { timeout: 120000 });
    }
    const nv = await page.evaluate(() => window.softsculpt.vertexCount());
    await page.waitForTimeout(4000);
    const rest = await rate(page, 3000);
    const top = await topVertex(page);
    const from = top.screen, to = { x: from.x + 150, y: from.y - 100 };
    const hold = await rate(page, 4000, () => drag(page, from, to, 25));
    const seen = await page.evaluate((i) => window.softsculpt.screenOf(i), top.index);
    const gap = Math.hypot(seen.x - to.x, seen.y - to.y);
    await shot(page, `bench-grab-held-${k}`);
    await page.mouse.up();
    const after1 = await rate(page, 5000);
    const after2 = await rate(page, 5000);
    await shot(page, `bench-grab-after-${k}`);
    console.log(`${dist}  ${nv}  ${rest.toFixed(3)}  ${hold.toFixed(3)}  ${after1.toFixed(3)}  ${after2.toFixed(3)}  cursor−vertex ${gap.toFixed(0)} px${errors.length ? `  errors: ${errors.join('; ')}` : ''}`);
    await ctx.close();
  }
}
await browser.close();
for (const s of servers) s.stop();
process.exit(0);
