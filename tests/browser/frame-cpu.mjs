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
import { launch, waitState, playCopies } from './common.mjs';

const args = process.argv.slice(2);
const url = args[0] ?? 'http://127.0.0.1:8000/';
const opt = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 && i + 1 < args.length ? args[i + 1] : fallback;
};
const three = args.includes('--three');
const file = opt('--file', new URL('../../data/walk.bvh', import.meta.url).pathname);
const copies = Number(opt('--n', '1'));
const secs = Number(opt('--secs', '4'));
const fragment = opt('--fragment', '');
const chromium = opt('--chromium', '/usr/bin/chromium');
const TICKS_PER_S = 100;

/** CPU milliseconds so far of every thread of every Chromium process, by pid/tid. */
function threads() {
  const out = new Map();
  for (const pid of fs.readdirSync('/proc')) {
    if (!/^\d+$/.test(pid)) continue;
    let cmd;
    try { cmd = fs.readFileSync(`/proc/${pid}/cmdline`, 'latin1'); } catch { continue; }
    if (!cmd.startsWith(chromium.replace('/usr/bin/', '/usr/lib/')) && !cmd.startsWith(chromium)) continue;
    const type = (cmd.match(/--type=([a-z-]+)/) || [null, 'browser'])[1];
    let tids;
    try { tids = fs.readdirSync(`/proc/${pid}/task`); } catch { continue; }
    for (const tid of tids) {
      try {
        const stat = fs.readFileSync(`/proc/${pid}/task/${tid}/stat`, 'latin1');
        const name = stat.slice(stat.indexOf('(') + 1, stat.lastIndexOf(')')).replace(/\d+$/, '#');
        const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
        out.set(`${pid}/${tid}`, { key: `${type}:${name}`, ms: (Number(fields[11]) + Number(fields[12])) * 1000 / TICKS_PER_S });
      } catch { /* the thread ended */ }
    }
  }
  return out;
}

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
    await page.goto(url + fragment);
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 3);
    await playCopies(page, text, copies);
    frames = () => page.evaluate(() => window.mocapViewer.state().framesRendered);
  }
  await new Promise((r) => setTimeout(r, 1500));
  const [f0, before, t0] = [await frames(), threads(), Date.now()];
  await new Promise((r) => setTimeout(r, secs * 1000));
  const [f1, after, ms] = [await frames(), threads(), Date.now() - t0];
  const drawn = Math.max(1, f1 - f0);
  const byThread = new Map();
  for (const [id, t] of after) {
    const spent = t.ms - (before.get(id)?.ms ?? 0);
    if (spent > 0) byThread.set(t.key, (byThread.get(t.key) ?? 0) + spent);
  }
  const rows = [...byThread].sort((a, b) => b[1] - a[1]);
  const total = rows.reduce((sum, [, v]) => sum + v, 0);
  console.log(`${three ? 'three.js' : 'viewer'}: ${drawn} frames in ${ms} ms, ${(1000 * drawn / ms).toFixed(1)} fps; CPU ${(total / drawn).toFixed(1)} ms per frame`);
  for (const [key, v] of rows.slice(0, 12)) console.log(`  ${key.padEnd(36)} ${(v / drawn).toFixed(2)} ms`);
} finally {
  await close();
}
