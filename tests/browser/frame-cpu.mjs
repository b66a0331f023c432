// Where a drawn frame's CPU time goes, per Chromium thread (a tool for performance work,
// not a test): node frame-cpu.mjs <url> [--three] [--file clip.bvh] [--n 16] [--secs 4]
// [--fragment '#shadows=0']. Opens the viewer at <url> (or, with --three, the three.js
// BVH example's page at <url>bench/three/bvh.html, as `cargo xtask serve` serves it) in
// headless Chromium with software WebGL2 at 1280×720, plays `--file` (default
// data/walk.bvh) as `--n` characters, and after 1.5 s reads every Chromium thread's CPU
// time from /proc (Linux) over `--secs` seconds: milliseconds per drawn frame per
// process type and thread name, the frame rate, and the total. The machine's cores are
// shared by all of them, so the total per frame is what bounds the frame rate.
import fs from 'node:fs';
import { launch, openPlaying, toolArgs } from './common.mjs';
import { threads, spentByThread } from './thread-cpu.mjs';

const { url, flag, option, chromium, clip: file } = toolArgs();
const three = flag('--three');
const copies = Number(option('--n', '1'));
const secs = Number(option('--secs', '4'));
const fragment = option('--fragment', '');
const text = fs.readFileSync(file, 'latin1');
const { page, close } = await launch(chromium, 'webgl2', { viewport: { width: 1280, height: 720 } });
try {
  let frames;
  if (three) {
    await page.goto(`${url}bench/three/bvh.html`);
    await page.waitForFunction(() => window.threeBench && window.threeBench.frames > 3, null, { timeout: 60000 });
    await page.evaluate(([t, n]) => window.openBvh(t, n), [text, copies]);
    frames = () => page.evaluate(() => window.threeBench.frames);
  } else {
    await openPlaying(page, url + fragment, text, copies);
    frames = () => page.evaluate(() => window.mocapViewer.state().framesRendered);
  }
  await new Promise((r) => setTimeout(r, 1500));
  const [f0, before, t0] = [await frames(), threads(chromium), Date.now()];
  await new Promise((r) => setTimeout(r, secs * 1000));
  const [f1, after, ms] = [await frames(), threads(chromium), Date.now() - t0];
  const drawn = Math.max(1, f1 - f0);
  const byThread = spentByThread(before, after);
  const rows = [...byThread].sort((a, b) => b[1] - a[1]);
  const total = rows.reduce((sum, [, v]) => sum + v, 0);
  console.log(`${three ? 'three.js' : 'viewer'}: ${drawn} frames in ${ms} ms, ${(1000 * drawn / ms).toFixed(1)} fps; CPU ${(total / drawn).toFixed(1)} ms per frame`);
  for (const [key, v] of rows.slice(0, 12)) console.log(`  ${key.padEnd(36)} ${(v / drawn).toFixed(2)} ms`);
} finally {
  await close();
}
