// Shared helpers for the browser tests and the benchmark: launching Chromium in a
// given GPU mode, waiting on viewer state, dropping files onto the page.
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

const COMMON = [
  '--no-sandbox', '--disable-background-networking', '--disable-component-update',
  '--disable-sync', '--no-first-run', '--disable-quic',
];

/** Chromium flags per mode: WebGL2 on SwiftShader, or WebGPU on SwiftShader Vulkan (WebGL2 off). */
export const MODES = {
  webgl2: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  webgpu: ['--enable-unsafe-webgpu', '--enable-features=Vulkan', '--use-vulkan=swiftshader',
    '--use-angle=vulkan', '--enable-unsafe-swiftshader', '--use-webgpu-adapter=swiftshader'],
};

/**
 * Launches headless Chromium with a fresh profile; returns { context, page, close, errors }.
 * `options` may set `viewport` (default 1280×800), `deviceScaleFactor` (default 1) and `keepStorage` (keep the
 * autosaved work between page loads; by default every load is a first visit).
 */
export async function launch(executablePath, mode, options = {}) {
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'mocap-chromium-'));
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath, headless: true, args: [...COMMON, ...MODES[mode]],
    viewport: options.viewport ?? { width: 1280, height: 800 },
    deviceScaleFactor: options.deviceScaleFactor ?? 1,
  });
  // Each page load is a first visit: the work the page autosaved in an earlier
  // step is not restored over what a test opens (autosave.mjs keeps it).
  if (!options.keepStorage) {
    await context.addInitScript(() => { try { indexedDB.deleteDatabase('mocap-autosave'); } catch { /* no storage */ } });
  }
  const page = context.pages()[0] ?? await context.newPage();
  const errors = [];
  page.on('console', (msg) => { if (msg.type() === 'error') errors.push(msg.text()); });
  page.on('pageerror', (err) => errors.push(String(err)));
  const close = async () => {
    await context.close();
    fs.rmSync(userDataDir, { recursive: true, force: true });
  };
  return { context, page, close, errors };
}

/** Current `window.mocapViewer.state()`. */
export const state = (page) => page.evaluate(() => window.mocapViewer.state());

/** Waits until `predicate(state)` holds (predicate is serialised to the page). */
export async function waitState(page, predicate, arg, timeout = 60000) {
  // One function built here (Node's eval), so the page never calls eval: its CSP forbids it.
  const check = (0, eval)(`(a) => { const s = window.mocapViewer && window.mocapViewer.state(); return !!s && (${predicate.toString()})(s, a); }`);
  await page.waitForFunction(check, arg, { timeout, polling: 50 });
  return state(page);
}

/** Waits until the viewer has rendered `n` more frames. */
export async function waitFrames(page, n = 2) {
  const start = (await state(page)).framesRendered;
  return waitState(page, (s, a) => s.framesRendered >= a, start + n);
}

/**
 * Runs `fn(viewer, arg)` in the page and waits until a frame has been rendered after it
 * (the frame counter is read in the same task, so a quick repaint cannot be missed).
 */
export async function changeAndRender(page, fn, arg) {
  const change = (0, eval)(`(a) => { const v = window.mocapViewer; const f = v.state().framesRendered; (${fn.toString()})(v, a); return f; }`);
  const f0 = await page.evaluate(change, arg);
  return waitState(page, (s, a) => s.framesRendered > a, f0);
}

/** Waits until the page finished loading a dropped file and rendered a frame with it. */
export async function waitDropped(page, name) {
  await page.waitForFunction((n) => window.mocapLastLoad && window.mocapLastLoad.name === n, name, { timeout: 60000 });
  return state(page);
}

/**
 * Replaces what the viewer has open by `copies` characters of the BVH `text`
 * (`clip0.bvh`, `clip1.bvh`, ...), plays them and waits until they are all open.
 */
export async function playCopies(page, text, copies) {
  await page.evaluate(([text, copies]) => {
    const v = window.mocapViewer;
    while (v.state().clips.length > 0) v.remove(0);
    const bytes = new TextEncoder().encode(text);
    for (let i = 0; i < copies; i++) v.add(`clip${i}.bvh`, bytes);
    v.play();
  }, [text, copies]);
  return waitState(page, (s, n) => s.clips.length === n, copies);
}

/**
 * Opens the viewer at `url`, waits for its default clip, then plays `copies`
 * characters of the BVH `text` ([`playCopies`]). For the performance tools.
 */
export async function openPlaying(page, url, text, copies) {
  await page.goto(url);
  await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 3);
  return playCopies(page, text, copies);
}

/**
 * The command line of a performance tool (frame-cpu.mjs, cold-cpu.mjs, profile.mjs):
 * `url`, its first argument (default: `cargo xtask serve`'s address);
 * `flag(name)`, whether `name` is given; `option(name, fallback)`, the value after
 * `name`; `chromium`, `--chromium` or Debian's; `clip`, `--file` or data/walk.bvh.
 */
export function toolArgs(args = process.argv.slice(2)) {
  const option = (name, fallback) => {
    const i = args.indexOf(name);
    return i >= 0 && i + 1 < args.length ? args[i + 1] : fallback;
  };
  return {
    url: args[0] && !args[0].startsWith('--') ? args[0] : 'http://127.0.0.1:8080/',
    flag: (name) => args.includes(name),
    option,
    chromium: option('--chromium', '/usr/bin/chromium'),
    clip: option('--file', new URL('../../data/walk.bvh', import.meta.url).pathname),
  };
}

/** Dispatches a real `drop` event carrying `bytes` as a File named `name`; returns the drop time. */
export async function dropFile(page, name, bytes) {
  const b64 = Buffer.from(bytes).toString('base64');
  return page.evaluate(([name, b64]) => {
    const bin = atob(b64);
    const data = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) data[i] = bin.charCodeAt(i);
    const dt = new DataTransfer();
    dt.items.add(new File([data], name));
    const canvas = document.getElementById('viewer');
    const t0 = performance.now();
    window.mocapLastLoad = null;
    for (const type of ['dragenter', 'dragover', 'drop']) {
      canvas.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true }));
    }
    return t0;
  }, [name, b64]);
}

/**
 * Drops several files at once (`files`: [{name, bytes}]), with Shift held when
 * `shift`; returns the drop time. Wait with `waitDropped(page, lastName)`.
 */
export async function dropFiles(page, files, shift = false) {
  const list = files.map((f) => [f.name, Buffer.from(f.bytes).toString('base64')]);
  return page.evaluate(([list, shift]) => {
    const dt = new DataTransfer();
    for (const [name, b64] of list) {
      const bin = atob(b64);
      const data = new Uint8Array(bin.length);
      for (let i = 0; i < bin.length; i++) data[i] = bin.charCodeAt(i);
      dt.items.add(new File([data], name));
    }
    const canvas = document.getElementById('viewer');
    const t0 = performance.now();
    window.mocapLastLoad = null;
    for (const type of ['dragenter', 'dragover', 'drop']) {
      canvas.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true, shiftKey: shift }));
    }
    return t0;
  }, [list, shift]);
}

/** A deliberate click: hover, then hold the button across a few (slow) frames, as a person would. */
export async function slowClick(page, x, y) {
  await page.mouse.move(x, y);
  await page.waitForTimeout(400);
  await page.mouse.down();
  await page.waitForTimeout(300);
  await page.mouse.up();
}

/** A mouse drag from (`x`, `y`) by (`dx`, `dy`) in `steps` moves `pause` ms apart, as a hand would. */
export async function drag(page, x, y, dx, dy, steps = 8, pause = 60) {
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let k = 1; k <= steps; k++) {
    await page.mouse.move(x + dx * k / steps, y + dy * k / steps);
    await page.waitForTimeout(pause);
  }
  await page.mouse.up();
}

/**
 * Decodes PNG bytes in a blank page of `context` (away from the viewer's CSP):
 * `{ width, data }`, `data` the RGBA bytes as a Buffer.
 */
export async function decodePng(context, png) {
  const page = await context.newPage();
  try {
    const { width, b64 } = await page.evaluate(async (src) => {
      const img = new Image();
      img.src = `data:image/png;base64,${src}`;
      await img.decode();
      const c = new OffscreenCanvas(img.width, img.height);
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      const bytes = g.getImageData(0, 0, img.width, img.height).data;
      // Back as base64 (a plain array of millions of numbers is slow to pass).
      let bin = '';
      for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
      return { width: img.width, b64: btoa(bin) };
    }, png.toString('base64'));
    return { width, data: Buffer.from(b64, 'base64') };
  } finally {
    await page.close();
  }
}

/** Screenshot of the central 3D area (between the side panels). */
export function view3d(page, file) {
  return page.screenshot({ path: file, clip: { x: 330, y: 120, width: 520, height: 420 } });
}

// A test report for one script: `check(cond, what)` prints ok/FAIL lines,
// `step(name, fn)` runs an async step and turns a throw into a failure, and
// `finish(what)` prints the summary and exits with the right status.
export function reporter(label) {
  let failures = 0;
  const check = (cond, what) => {
    console.log(`${cond ? 'ok  ' : 'FAIL'} [${label}] ${what}`);
    if (!cond) failures += 1;
  };
  const step = async (name, fn) => {
    try {
      await fn();
    } catch (e) {
      check(false, `${name}: ${e.message.split('\n')[0]}`);
    }
  };
  const finish = (what) => {
    console.log(failures === 0 ? `[${label}] all ${what} passed` : `[${label}] ${failures} failure(s)`);
    process.exit(failures === 0 ? 0 : 1);
  };
  return { check, step, finish };
}
