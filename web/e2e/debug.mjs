import { drag, inspect, launch, openModeler, settle, startServer, topVertex, vertex, dist } from './harness.mjs';
const server = await startServer(5198);
const browser = await launch();
const { page } = await openModeler(browser, server.url);
await settle(page);
const top = await topVertex(page);
await drag(page, top.screen, { x: top.screen.x, y: top.screen.y - 45 }, 20, 800);
await page.screenshot({ path: '/tmp/d1.png' });
console.log('com', JSON.stringify((await inspect(page, () => window.softsculpt.stats())).centerOfMass));
await page.mouse.up();
for (let i = 0; i < 6; i++) {
  await page.waitForTimeout(2000);
  const s = await inspect(page, () => ({ st: window.softsculpt.stats(), slow: window.softsculpt.slowMotion(), fps: window.softsculpt.fps() }));
  console.log(s.st.time.toFixed(2), s.st.maxSpeed.toFixed(4), s.slow, s.fps.toFixed(1), dist(await vertex(page, top.index), top.position).toFixed(4));
}
await page.screenshot({ path: '/tmp/d2.png' });
console.log('com', JSON.stringify((await inspect(page, () => window.softsculpt.stats())).centerOfMass));
console.log('pinned', (await inspect(page, () => window.softsculpt.pinned())).filter(Boolean).length);
process.exit(0);
await page.keyboard.press('n');
const t2 = await topVertex(page);
await drag(page, t2.screen, t2.screen, 2, 50);
await page.mouse.up();
console.log('pins', (await inspect(page, () => window.softsculpt.pinned())).filter(Boolean).length, await inspect(page, () => window.softsculpt.lastMessage()));
await page.keyboard.press('u');
await page.waitForTimeout(800);
console.log('n', await inspect(page, () => window.softsculpt.vertexCount()), await inspect(page, () => window.softsculpt.lastMessage()));
await browser.close(); server.stop();
