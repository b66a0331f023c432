// Where the page's own thread spends its time, by function (a tool for performance
// work, not a test): V8's sampling CPU profiler over the viewer in headless Chromium
// with software WebGL2 at 1280×720. Functions have their Rust names when the page is a
// build that keeps the wasm's name section: `cargo xtask dist --names`, then
// `cargo xtask serve --no-build`.
//   node profile.mjs <url> --start [--who NAME]
//     from the navigation to the first drawn frame (the `mocap-first-frame` mark): ms
//   node profile.mjs <url> [--file clip.bvh] [--n 16] [--secs 4] [--who NAME]
//     while playing `--file` (default data/walk.bvh) as `--n` characters: ms per frame
// Prints the functions with the most time of their own, the most time with what they
// call, and with `--who` the call chains that reach functions whose names hold NAME.
// `(program)` is V8's and Blink's own work (compiling, collecting, the bindings),
// `(idle)` the thread waiting; the sampling adds to every figure.
import fs from 'node:fs';
import { launch, openPlaying, toolArgs } from './common.mjs';

const { url, flag, option, chromium, clip } = toolArgs();
const start = flag('--start');
const who = option('--who', null);
const MARK = 'mocap-first-frame';
// The function that marks the first frame, found in the samples: the profile's own
// clock is not the page's, so the cut is where the page was seen setting the mark.
const MARKER = 'MOCAP_FIRST_FRAME_MARKER';

const { page, context, close } = await launch(chromium, 'webgl2', { viewport: { width: 1280, height: 720 } });
try {
  if (start) {
    await context.addInitScript(([mark, marker]) => {
      const original = performance.mark.bind(performance);
      // Named so that the samples show it (a literal name: V8's profiler names a
      // computed one after the variable it is stored in); busy for 5 ms so that a
      // sample lands in it.
      const wrapped = {
        MOCAP_FIRST_FRAME_MARKER(name, options) {
          if (name === mark) {
            const t = performance.now();
            while (performance.now() - t < 5) { /* be sampled */ }
          }
          return original(name, options);
        },
      };
      performance.mark = wrapped[marker];
    }, [MARK, MARKER]);
  }
  const cdp = await context.newCDPSession(page);
  await cdp.send('Profiler.enable');
  await cdp.send('Profiler.setSamplingInterval', { interval: 100 });
  let frames = 1;
  let profile;
  if (start) {
    await cdp.send('Profiler.start');
    await page.goto(url);
    await page.waitForFunction((m) => performance.getEntriesByName(m).length > 0, MARK, { timeout: 60000 });
    ({ profile } = await cdp.send('Profiler.stop'));
    const at = await page.evaluate((m) => performance.getEntriesByName(m)[0].startTime, MARK);
    console.log(`first frame at ${at.toFixed(0)} ms (under the profiler)`);
  } else {
    const secs = Number(option('--secs', '4'));
    await openPlaying(page, url, fs.readFileSync(clip, 'latin1'), Number(option('--n', '1')));
    await new Promise((r) => setTimeout(r, 2000));
    const drawn = () => page.evaluate(() => window.mocapViewer.state().framesRendered);
    const f0 = await drawn();
    await cdp.send('Profiler.start');
    await new Promise((r) => setTimeout(r, secs * 1000));
    ({ profile } = await cdp.send('Profiler.stop'));
    frames = Math.max(1, (await drawn()) - f0);
    console.log(`${frames} frames drawn in ${secs} s; figures in ms per frame`);
  }
  report(profile, frames, start ? MARKER : null);
} finally {
  await close();
}

// Prints `profile`'s samples (up to the first sample in `cutAt`, if given) as
// milliseconds divided by `frames`.
function report(profile, frames, cutAt) {
  const nodes = new Map(profile.nodes.map((n) => [n.id, n]));
  const parent = new Map();
  for (const n of profile.nodes) for (const c of n.children ?? []) parent.set(c, n.id);
  const name = (id) => {
    const f = nodes.get(id).callFrame;
    return f.functionName || `(anonymous ${f.url.split('/').pop()}:${f.lineNumber + 1}:${f.columnNumber + 1})`;
  };
  const own = new Map();
  const within = new Map();
  const chains = new Map();
  const add = (map, key, ms) => map.set(key, (map.get(key) ?? 0) + ms);
  for (let i = 0; i < profile.samples.length; i++) {
    const id = profile.samples[i];
    if (cutAt && name(id) === cutAt) break;
    // A sample's time is the gap to the next one.
    const ms = (profile.timeDeltas[i + 1] ?? 0) / 1000;
    add(own, name(id), ms);
    const stack = [];
    for (let x = id; x !== undefined; x = parent.get(x)) stack.push(name(x));
    for (const n of new Set(stack)) add(within, n, ms);
    if (who) {
      const at = stack.findIndex((n) => n.includes(who));
      if (at >= 0) add(chains, stack.slice(at, at + 8).join('\n      <- '), ms);
    }
  }
  const short = (n) => n.replace(/\[[0-9a-f]{8,}\]/g, '').slice(0, 150);
  const top = (map, count) => [...map].sort((a, b) => b[1] - a[1]).slice(0, count);
  console.log('--- own time');
  for (const [n, ms] of top(own, 30)) console.log(`${(ms / frames).toFixed(3).padStart(9)}  ${short(n)}`);
  console.log('--- with what it calls');
  for (const [n, ms] of top(within, 60)) console.log(`${(ms / frames).toFixed(3).padStart(9)}  ${short(n)}`);
  if (who) {
    console.log(`--- call chains reaching "${who}"`);
    for (const [chain, ms] of top(chains, 6)) console.log(`${(ms / frames).toFixed(3).padStart(9)}  ${chain.split('\n').map(short).join('\n')}\n`);
  }
}
