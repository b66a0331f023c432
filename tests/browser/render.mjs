// Browser tests of what the 3D view draws: capsules by default with floor shadows,
// the m key and the fragment switch to sticks and turn shadows off, and the view
// keeps drawing correctly when the window is resized or the pixel ratio is 2;
// the fast look while playing (quality=fast|auto|full: one sample per pixel, the
// window and its panels at full resolution) and nothing drawn at rest.
// Usage: node render.mjs URL MODE OUT_DIR CHROMIUM
import fs from 'node:fs';
import path from 'node:path';
import { changeAndRender, decodePng, dropFile, launch, reporter, state, waitState } from './common.mjs';

const [base, mode, outDir, chromiumPath] = process.argv.slice(2);
const { check, step, finish } = reporter(`render ${mode}`);
const shot = (name) => path.join(outDir, `render-${mode}-${name}.png`);

/** Counts pixels of a PNG: lit figure, blue joint balls, and (with `reference`) pixels darker than it. */
async function pixelStats(context, png, reference) {
  const { data: d } = await decodePng(context, png);
  const r = reference ? (await decodePng(context, reference)).data : null;
  let figure = 0;
  let floor = 0;
  let darker = 0;
  let blue = 0;
  for (let i = 0; i < d.length; i += 4) {
    // Light grey, lit figure pixels (the default character colour).
    if (d[i] > 150 && d[i + 1] > 150 && d[i + 2] > 150 && Math.abs(d[i] - d[i + 2]) < 40) figure += 1;
    // The blue joint balls of stick mode.
    if (d[i + 2] > 150 && d[i + 2] > d[i] + 60) blue += 1;
    // The floor's grey-blue, lighter than the background (38, 40, 46).
    if (d[i + 2] >= 50 && d[i + 2] < 140 && d[i + 2] >= d[i] && Math.abs(d[i] - d[i + 1]) < 16) floor += 1;
    if (r && d[i] + d[i + 1] + d[i + 2] + 24 < r[i] + r[i + 1] + r[i + 2]) darker += 1;
  }
  return { figure, floor, darker, blue };
}

/** The 3D view between the side panels, as PNG bytes. */
const view = (page, file) => page.screenshot({ path: file, clip: { x: 300, y: 80, width: 640, height: 560 } });

const { context, page, close, errors } = await launch(chromiumPath, mode);
try {
  let capsules;
  await step('capsules with soft floor shadows by default', async () => {
    await page.goto(`${base}#play=0`);
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 0);
    const s = await changeAndRender(page, (v) => v.seek(30));
    check(s.drawMode === 'capsules' && s.shadows === true, `drawMode ${s.drawMode}, shadows ${s.shadows}`);
    check(s.view.includes('mode=capsules') && s.view.includes('shadows=1'), `fragment has the mode (${s.view})`);
    // Capsules alone are smooth without multisampling (outlines blended).
    check(!s.reduced && s.samples === 1, `a paused frame of capsules: full quality on one sample (reduced ${s.reduced}, ${s.samples} samples)`);
    capsules = await view(page, shot('capsules'));
    const px = await pixelStats(context, capsules);
    check(px.figure > 1500, `the lit figure covers many pixels (${px.figure})`);
    // The window reaches the page the right way up (WebGL2 presents it with a
    // flipped copy, vendor/wgpu-hal): the floor with its grid is in the lower
    // part of the view, the plain dark background above it.
    const { data, width } = await decodePng(context, capsules);
    const height = data.length / 4 / width;
    const meanRows = (from, to) => {
      let sum = 0;
      for (let y = from; y < to; y++) for (let x = 0; x < width; x++) sum += data[(y * width + x) * 4 + 1];
      return sum / ((to - from) * width);
    };
    const [top, bottom] = [meanRows(0, height >> 2), meanRows(height - (height >> 2), height)];
    check(bottom > top + 8, `floor below, background above (mean green ${bottom.toFixed(1)} below, ${top.toFixed(1)} above)`);
  });

  await step('shadows=0 in the fragment removes the floor shadow', async () => {
    const s = await changeAndRender(page, (v) => v.applyViewState('shadows=0'));
    const plain = await view(page, shot('no-shadows'));
    const px = await pixelStats(context, capsules, plain);
    check(px.darker > 300, `with shadows, floor pixels are darker (${px.darker} pixels)`);
    check(s.view.includes('shadows=0'), 'the fragment follows');
  });

  await step('the m key switches to sticks', async () => {
    await page.mouse.click(640, 400);
    await page.keyboard.press('m');
    await waitState(page, (s) => s.drawMode === 'sticks');
    const s = await changeAndRender(page, (v) => v.seek(31));
    check(s.samples === 1 && !s.reduced, `lines and joint balls: full quality on one sample, outlines blended (${s.samples} samples)`);
    const sticks = await view(page, shot('sticks'));
    const [a, b] = [await pixelStats(context, capsules), await pixelStats(context, sticks)];
    check(b.figure < a.figure, `sticks cover fewer pixels than capsules (${b.figure} < ${a.figure})`);
    check(b.blue > 20 && a.blue < 5, `sticks have blue joint balls, capsules none (${b.blue}, ${a.blue})`);
    check(s.view.includes('mode=sticks'), 'the fragment follows');
  });

  await step('the m key again switches to the body, then back to capsules', async () => {
    await page.keyboard.press('m');
    const s = await waitState(page, (s) => s.drawMode === 'body');
    const sb = await changeAndRender(page, (v) => v.seek(30));
    check(sb.samples === 4 && !sb.reduced, `the body (a mesh) is multisampled (${sb.samples} samples)`);
    const body = await view(page, shot('body'));
    const [a, b] = [await pixelStats(context, capsules), await pixelStats(context, body)];
    check(b.figure > a.figure, `the body covers more pixels than the capsules (${b.figure} > ${a.figure})`);
    check(b.blue < 5, `no joint balls on the body (${b.blue})`);
    check(s.view.includes('mode=body'), 'the fragment follows');
    const w = await changeAndRender(page, (v) => v.applyViewState('draw=joints,weights'));
    const weights = await view(page, shot('body-weights'));
    const pw = await pixelStats(context, weights, body);
    check(w.view.includes('weights'), `the weights view is in the fragment (${w.view})`);
    const grey = (await pixelStats(context, weights)).figure;
    check(grey < b.figure / 2, `the weights view colours the body (${grey} grey pixels left of ${b.figure})`);
    // The body casts its shadow at full quality (the shadow map is fitted to
    // where the posed body is).
    const sh = await changeAndRender(page, (v) => v.applyViewState('draw=joints&shadows=1'));
    const shadowed = await view(page, shot('body-shadow'));
    const ps = await pixelStats(context, shadowed, body);
    check(sh.samples === 4 && ps.darker > 300, `the body's shadow darkens the floor (${ps.darker} pixels, ${sh.samples} samples)`);
    await changeAndRender(page, (v) => v.applyViewState('shadows=0'));
    await page.keyboard.press('m');
    await waitState(page, (s) => s.drawMode === 'capsules');
  });

  await step('in Edit mode, dragging a hand in the view moves it to the pointer', async () => {
    await changeAndRender(page, (v) => { v.pause(); v.seek(30); v.applyViewState('draw=joints,interp,pose'); });
    const s0 = await waitState(page, (s) => s.poseMode === true);
    const start = await page.evaluate(() => window.mocapViewer.jointScreenPosition(0, 'LeftHand'));
    check(Array.isArray(start) || start instanceof Float32Array, `the hand is on screen at ${start}`);
    const [x, y] = start;
    const end = [x + 40, y - 30];
    await page.mouse.move(x, y);
    await page.mouse.down();
    for (let k = 1; k <= 8; k++) {
      await page.mouse.move(x + (end[0] - x) * k / 8, y + (end[1] - y) * k / 8);
      await page.waitForTimeout(60);
    }
    await page.mouse.up();
    const s = await waitState(page, (s) => s.clips[0].corrected === true && s.selectedJoint === 'LeftHand');
    await changeAndRender(page, (v) => v.pause());
    const now = await page.evaluate(() => window.mocapViewer.jointScreenPosition(0, 'LeftHand'));
    const d = Math.hypot(now[0] - end[0], now[1] - end[1]);
    check(d < 4, `the hand is under the pointer (${now} vs ${end}, ${d.toFixed(1)} px)`);
    check(s.view.includes('pose') && s0.view.includes('pose'), 'Edit mode is in the fragment');
    await view(page, shot('pose-drag'));
    await page.evaluate(() => window.mocapViewer.resetPose());
    const r = await waitState(page, (s) => s.clips[0].corrected === false);
    check(!r.clips[0].corrected, 'resetPose() restores the clip');
    await changeAndRender(page, (v) => v.applyViewState('draw=joints,interp'));
  });

  await step('a link with mode=sticks opens in stick mode', async () => {
    await page.goto('about:blank');
    await page.goto(`${base}#t=1&play=0&mode=sticks&shadows=1`);
    const s = await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 0);
    check(s.drawMode === 'sticks' && s.shadows, `drawMode ${s.drawMode}, shadows ${s.shadows}`);
  });

  await step('while playing slowly the view drops to one sample per pixel; at rest it is full quality', async () => {
    await page.goto('about:blank');
    await page.goto(`${base}#play=1&quality=fast`);
    let s = await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 3 && s.playing);
    s = await waitState(page, (s) => s.reduced);
    check(s.quality === 'fast' && s.view.includes('quality=fast'), `quality ${s.quality} (${s.view})`);
    // Text stays sharp: the window is drawn at the display's resolution in
    // every look (only the 3D view's own look changes), and the panels' pixels
    // while the view plays in the fast look are those at rest.
    const canvasSize = () => page.evaluate(() => {
      const c = document.getElementById('viewer');
      return { width: c.width, full: Math.round(c.getBoundingClientRect().width * devicePixelRatio) };
    });
    let size = await canvasSize();
    check(size.width === size.full, `the window is drawn at full resolution while reduced (${size.width} of ${size.full} pixels wide)`);
    const panels = {
      'tree panel': { x: 0, y: 30, width: 236, height: 560 },
      'inspector panel': { x: 1004, y: 30, width: 276, height: 560 },
      'top bar': { x: 0, y: 0, width: 1280, height: 26 },
    };
    const panelShots = async () => {
      const out = {};
      for (const [name, clip] of Object.entries(panels)) out[name] = await page.screenshot({ clip });
      return out;
    };
    const playingPanels = await panelShots();
    s = await state(page);
    check(s.reduced && s.playing, `the panels were taken while playing in the fast look (reduced ${s.reduced})`);
    const reducedPixels = s.viewPixels;
    // Under a still camera the fast look's frames start from the floor drawn
    // before (copied; on WebGL2 its colour, with its depth drawn).
    s = await waitState(page, (s) => s.floorCopied);
    check(s.reduced && s.floorCopied, `playing under a still camera copies the floor (${s.backend})`);
    const png = await view(page, shot('reduced'));
    const px = await pixelStats(context, png);
    check(px.figure > 1000, `the figure is drawn in the fast look (${px.figure} pixels)`);
    check(px.floor > 20000, `the floor is drawn in the fast look (${px.floor} pixels)`);
    s = await changeAndRender(page, (v) => v.pause());
    check(!s.reduced, 'the paused frame is drawn at full quality');
    // Only the 3D view is drawn smaller while it moves (half its pixels per
    // axis, stretched over it); at rest, at the view's own resolution.
    const half = (full, drawn) => Math.abs(Math.ceil(full / 2) - drawn) <= 1;
    check(s.viewPixels[0] > 100 && half(s.viewPixels[0], reducedPixels[0]) && half(s.viewPixels[1], reducedPixels[1]),
      `the 3D view is drawn at ${reducedPixels.join('x')} pixels in the fast look, ${s.viewPixels.join('x')} at rest`);
    size = await canvasSize();
    check(size.width === size.full, `at rest the window is drawn at full resolution (${size.width} of ${size.full} pixels wide)`);
    const restingPanels = await panelShots();
    for (const name of Object.keys(panels)) {
      const same = playingPanels[name].equals(restingPanels[name]);
      check(same, `the ${name}'s pixels while playing in the fast look are those at rest (${same ? 'identical' : 'they differ'})`);
      if (!same) {
        fs.writeFileSync(shot(`${name.replace(/ /g, '-')}-playing`), playingPanels[name]);
        fs.writeFileSync(shot(`${name.replace(/ /g, '-')}-rest`), restingPanels[name]);
      }
    }
    // On WebGL2 the window keeps its pixels and a frame redraws only what
    // changed (the 3D view around the figure, the timeline): after playing,
    // the window is what a whole redraw (after a resize there and back) shows.
    const whole = async () => {
      await page.waitForTimeout(300);
      return page.screenshot();
    };
    const viewport = page.viewportSize();
    const redrawWhole = async () => {
      for (const size of [{ width: viewport.width - 40, height: viewport.height }, viewport]) {
        const f0 = (await state(page)).framesRendered;
        await page.setViewportSize(size);
        await waitState(page, (s, f) => s.framesRendered > f, f0);
      }
      return whole();
    };
    const compareWhole = async (what, name) => {
      const inParts = await whole();
      const redrawn = await redrawWhole();
      const same = inParts.equals(redrawn);
      check(same, `${what} has the pixels of a whole redraw (${same ? 'identical' : 'they differ'})`);
      if (!same) {
        fs.writeFileSync(shot(`${name}-in-parts`), inParts);
        fs.writeFileSync(shot(`${name}-redrawn-whole`), redrawn);
      }
    };
    await compareWhole('the window redrawn in parts while playing', 'played');
    // The playhead jumps back along the timeline: where it was is redrawn too.
    await changeAndRender(page, (v) => v.seek(0));
    await compareWhole('the window after the playhead jumped back', 'jumped');
    // Full: never reduced while playing.
    await page.evaluate(() => { window.mocapViewer.applyViewState('quality=full'); window.mocapViewer.play(); });
    let reduced = false;
    for (let i = 0; i < 8; i++) {
      s = await changeAndRender(page, () => {});
      reduced ||= s.reduced;
    }
    check(s.quality === 'full' && !reduced, `quality=full keeps full quality while playing (${s.quality})`);
    // Auto: the rule (quality.rs) is "over the last 10 moving frames, after
    // the first 3, with the slowest left out, a mean frame time over 1/55 s
    // switches a moving view to the fast look until it rests". Watch the
    // frames in the page (the time each new frame arrives, and whether it was
    // reduced) and check that the switch happens after such a window and not
    // without one. A loaded machine may stall for a few frames at any time, so
    // the test reads the frames it saw rather than an average over the run.
    const frames = await page.evaluate(async () => {
      const v = window.mocapViewer;
      const seen = [];
      let last = v.state().framesRendered;
      const t0 = performance.now();
      await new Promise((done) => {
        const tick = () => {
          const s = v.state();
          if (s.framesRendered !== last) {
            last = s.framesRendered;
            seen.push({ t: performance.now(), reduced: s.reduced });
            // Switch to auto once two full-quality frames are seen, so the
            // frames that lead to the switch are all watched.
            if (seen.length === 2) v.applyViewState('quality=auto');
          }
          if (performance.now() - t0 < 2500) requestAnimationFrame(tick); else done();
        };
        requestAnimationFrame(tick);
      });
      return seen;
    });
    const slowMs = 1000 / 55;
    const WINDOW = 10;
    // Whether a window of WINDOW frame gaps ending before frame `end`, without
    // its largest gap, averages over `limit` ms.
    const windowBefore = (end, limit) => {
      // (The viewer times no frame of its first few after the switch to auto.)
      for (let i = WINDOW + 4; i < end; i++) {
        const gaps = frames.slice(i - WINDOW, i + 1).map((f, k, all) => (k ? f.t - all[k - 1].t : 0)).slice(1);
        const trimmed = (gaps.reduce((x, y) => x + y, 0) - Math.max(...gaps)) / (gaps.length - 1);
        if (trimmed > limit) return true;
      }
      return false;
    };
    const firstReduced = frames.findIndex((f) => f.reduced);
    const gaps = frames.slice(1).map((f, i) => f.t - frames[i].t);
    const meanMs = gaps.reduce((a, b) => a + b, 0) / Math.max(1, gaps.length);
    if (firstReduced >= 0) {
      // The frame that was drawn reduced follows the slow run (with some
      // slack: the page sees frames a little later than the viewer times them).
      check(windowBefore(firstReduced + 1, slowMs * 0.7), `auto: reduced after a window of slow frames (frame ${firstReduced} of ${frames.length}, ${meanMs.toFixed(0)} ms per frame)`);
      check(frames.slice(firstReduced).every((f) => f.reduced), 'auto: once reduced, frames stay reduced while playing');
    } else {
      check(frames.length > 5 && !windowBefore(frames.length, slowMs * 1.3), `auto: full quality without a window of slow frames (${frames.length} frames, ${meanMs.toFixed(0)} ms per frame)`);
    }
    await page.evaluate(() => window.mocapViewer.pause());
  });

  await step('paused with no input, the page draws nothing', async () => {
    await waitState(page, (s) => !s.playing);
    await new Promise((r) => setTimeout(r, 500));
    const before = (await state(page)).framesRendered;
    await new Promise((r) => setTimeout(r, 1500));
    const after = (await state(page)).framesRendered;
    check(after === before, `no frame drawn in 1.5 s (${before} -> ${after})`);
    // Nor anything else scheduled: no timers, no animation-frame callbacks.
    const scheduled = await page.evaluate(async () => {
      const [timeout, raf, interval] = [window.setTimeout, window.requestAnimationFrame, window.setInterval];
      const calls = { timeout: 0, raf: 0, interval: 0 };
      window.setTimeout = (...a) => { calls.timeout++; return timeout(...a); };
      window.requestAnimationFrame = (...a) => { calls.raf++; return raf(...a); };
      window.setInterval = (...a) => { calls.interval++; return interval(...a); };
      await new Promise((r) => timeout(r, 1500));
      Object.assign(window, { setTimeout: timeout, requestAnimationFrame: raf, setInterval: interval });
      return calls;
    });
    check(scheduled.timeout + scheduled.raf + scheduled.interval === 0, `nothing scheduled in 1.5 s at rest (${JSON.stringify(scheduled)})`);
  });

  await step('a hidden tab draws nothing, and plays on when shown', async () => {
    // Headless Chromium keeps background tabs visible: the page is told it is
    // hidden the way a browser tells it (document.hidden and visibilitychange).
    await page.evaluate(() => window.mocapViewer.play());
    await waitState(page, (s) => s.playing && s.framesRendered > 0);
    const setHidden = (hidden) => page.evaluate((hidden) => {
      Object.defineProperty(document, 'hidden', { configurable: true, get: () => hidden });
      Object.defineProperty(document, 'visibilityState', { configurable: true, get: () => (hidden ? 'hidden' : 'visible') });
      document.dispatchEvent(new Event('visibilitychange'));
    }, hidden);
    await setHidden(true);
    await new Promise((r) => setTimeout(r, 300));
    const before = (await state(page)).framesRendered;
    await new Promise((r) => setTimeout(r, 1500));
    const hidden = await state(page);
    check(hidden.framesRendered === before && hidden.playing, `hidden and playing: no frame drawn in 1.5 s (${before} -> ${hidden.framesRendered})`);
    await setHidden(false);
    const shown = await waitState(page, (s, f) => s.framesRendered > f + 2, hidden.framesRendered);
    check(shown.playing && shown.time !== hidden.time, `shown again: frames resume (${shown.framesRendered}) and playback goes on (t ${hidden.time.toFixed(2)} -> ${shown.time.toFixed(2)})`);
    await page.evaluate(() => { delete document.hidden; delete document.visibilityState; window.mocapViewer.pause(); });
  });

  await step('while dropped files are read, playback holds and nothing is drawn', async () => {
    // What the page does around reading a drop (holdFrames), seen from outside.
    await page.evaluate(() => window.mocapViewer.play());
    await waitState(page, (s) => s.playing && s.framesRendered > 0);
    // Held in the same task as the state is read: not even the frame already
    // asked for is drawn.
    const before = await page.evaluate(() => {
      const s = window.mocapViewer.state();
      window.mocapViewer.holdFrames(true);
      return s;
    });
    await new Promise((r) => setTimeout(r, 1500));
    const held = await state(page);
    check(held.framesRendered === before.framesRendered && held.time === before.time && held.playing,
      `held: no frame drawn in 1.5 s (${before.framesRendered} -> ${held.framesRendered}), the playhead stays (t ${before.time.toFixed(3)} -> ${held.time.toFixed(3)})`);
    await page.evaluate(() => window.mocapViewer.holdFrames(false));
    const after = await waitState(page, (s, f) => s.framesRendered > f + 2, held.framesRendered);
    // (Playback loops: the step is taken around the clip's length.)
    const length = (after.clips[0].frames - 1) * after.clips[0].frameTime;
    const advanced = (((after.time - held.time) % length) + length) % length;
    check(advanced > 0 && advanced < 0.5, `let go: frames resume and playback goes on from where it held (t ${held.time.toFixed(3)} -> ${after.time.toFixed(3)})`);
    // A real drop goes through the same hold and ends it.
    await dropFile(page, 'walk.bvh', fs.readFileSync(new URL('../../data/walk.bvh', import.meta.url)));
    await page.waitForFunction(() => window.mocapLastLoad && window.mocapLastLoad.dropToFrameMs, null, { timeout: 60000 });
    const dropped = await waitState(page, (s, f) => s.framesRendered > f + 3, (await state(page)).framesRendered);
    check(dropped.playing && dropped.clips.length === 1, `after a drop, playing on (${dropped.framesRendered} frames)`);
    await page.evaluate(() => window.mocapViewer.pause());
  });

  await step('resizing the window keeps the figure drawn', async () => {
    await page.goto('about:blank');
    await page.goto(`${base}#play=0`);
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 0);
    for (const size of [{ width: 900, height: 600 }, { width: 1280, height: 800 }]) {
      await page.setViewportSize(size);
      await changeAndRender(page, (v) => v.seek(30));
      const png = await page.screenshot({ path: shot(`resized-${size.width}`) });
      const px = await pixelStats(context, png);
      check(px.figure > 800, `${size.width}x${size.height}: the figure is drawn (${px.figure} pixels)`);
    }
  });
  check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
} finally {
  await close();
}

await step('at a device pixel ratio of 2 the view is sharp and drawn', async () => {
  const hi = await launch(chromiumPath, mode, { deviceScaleFactor: 2 });
  try {
    await hi.page.goto(`${base}#play=0`);
    await waitState(hi.page, (s) => s.clips.length === 1 && s.framesRendered > 0);
    await changeAndRender(hi.page, (v) => v.seek(30));
    const png = await hi.page.screenshot({ path: shot('dpr2') });
    const px = await pixelStats(hi.context, png);
    // Twice the pixels each way: about four times the figure pixels of ratio 1.
    check(px.figure > 4000, `the figure is drawn at full resolution (${px.figure} pixels)`);
    const s = await state(hi.page);
    check(s.error === null && hi.errors.length === 0, `no errors (${hi.errors.join(' | ')})`);
  } finally {
    await hi.close();
  }
});

finish('render');
