// Where a cold start's CPU time goes, per Chromium thread (a tool for performance work,
// not a test): node cold-cpu.mjs <url> [--runs 4]. Opens, in a fresh headless Chromium
// each time (software WebGL2, 1280×720), the viewer at <url> and the three.js BVH
// example's page at <url>bench/three/bvh.html (as `cargo xtask serve` serves both),
// alternating, and reads every Chromium thread's CPU time from /proc (Linux) from just
// before the navigation to the page's first-frame mark (`mocap-first-frame`,
// `three-first-frame`). Prints for each page the median first frame, the median CPU
// in all, and the mean milliseconds per process type and thread name. On a machine
// whose cores are all busy until the first frame, the CPU in all is what sets it.
import { launch, toolArgs } from './common.mjs';
import { threads, spentByThread } from './thread-cpu.mjs';

const { url, option, chromium } = toolArgs();
const runs = Number(option('--runs', '4'));
const pages = [
  ['viewer', url, 'mocap-first-frame'],
  ['three.js', `${url}bench/three/bvh.html?bvh=${encodeURIComponent(`${url}data/walk.bvh`)}`, 'three-first-frame'],
];
const results = pages.map(() => []);
for (let run = 0; run < runs; run++) {
  for (let i = 0; i < pages.length; i++) {
    const k = (i + run) % pages.length;
    const [, pageUrl, mark] = pages[k];
    const { page, close } = await launch(chromium, 'webgl2', { viewport: { width: 1280, height: 720 } });
    try {
      const before = threads(chromium);
      await page.goto(pageUrl);
      await page.waitForFunction((m) => performance.getEntriesByName(m).length > 0, mark, { timeout: 60000, polling: 20 });
      const spent = spentByThread(before, threads(chromium));
      const first = await page.evaluate((m) => performance.getEntriesByName(m)[0].startTime, mark);
      results[k].push({ first, spent });
    } finally {
      await close();
    }
  }
}
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
pages.forEach(([name], k) => {
  const total = (r) => [...r.spent.values()].reduce((a, b) => a + b, 0);
  console.log(`${name}: first frame ${median(results[k].map((r) => r.first)).toFixed(0)} ms, CPU ${median(results[k].map(total)).toFixed(0)} ms in all (medians of ${runs})`);
  const mean = new Map();
  for (const r of results[k]) for (const [key, v] of r.spent) mean.set(key, (mean.get(key) ?? 0) + v / runs);
  for (const [key, v] of [...mean].sort((a, b) => b[1] - a[1]).slice(0, 10)) console.log(`  ${key.padEnd(36)} ${v.toFixed(0)} ms`);
});
