// Editing through the page's own controls, as a person does it: the Edit mode
// checkbox, a hand dragged in the view, `k` to key it, the key's diamond dragged
// along the timeline, Edit ▸ Reverse and Ctrl+Z, and Edit ▸ Layer with a joint
// mapped by hand in its table. The positions clicked are those of the default
// 1280×800 layout (toolbar, tree and menus), checked by the state after each.
// node editing.mjs <url> <outDir> <chromium>
import fs from 'node:fs';
import path from 'node:path';
import { changeAndRender, decodePng, drag, launch, reporter, slowClick, waitState } from './common.mjs';

const [base, outDir, chromiumPath] = process.argv.slice(2);
const { check, step, finish } = reporter('editing');
const shot = (name) => path.join(outDir, `editing-${name}.png`);
const walk = fs.readFileSync(new URL('../../data/walk.bvh', import.meta.url)).toString();

/** The mean x of the key-diamond yellow pixels in a screenshot strip (or null). */
async function diamondX(context, png) {
  const { width, data: d } = await decodePng(context, png);
  let sum = 0;
  let n = 0;
  for (let i = 0; i < d.length; i += 4) {
    if (d[i] > 230 && d[i + 1] > 170 && d[i + 1] < 225 && d[i + 2] < 90) {
      sum += (i / 4) % width;
      n += 1;
    }
  }
  return n > 4 ? sum / n : null;
}

/**
 * Opens a toolbar menu by clicking it at `x`, then waits until its popup covers the
 * left edge of the 3D view at (`probeX`, 150) (the popup's flat fill, not the sky);
 * clicks again if it did not open. Returns whether it opened.
 */
async function openMenu(context, page, x, probeX) {
  for (let attempt = 0; attempt < 3; attempt++) {
    await slowClick(page, x, 12);
    for (let k = 0; k < 10; k++) {
      await page.waitForTimeout(100);
      const { data: d } = await decodePng(context, await page.screenshot({ clip: { x: probeX, y: 150, width: 4, height: 4 } }));
      if (d[0] < 34 && d[1] < 34 && d[2] < 34 && Math.abs(d[2] - d[0]) < 4) return true;
    }
  }
  return false;
}

/** The channel values of joint `name` at `frame` in BVH text. */
function channelsOf(text, name, frame) {
  const [hierarchy, motion] = text.split(/\nMOTION\s*\n/);
  let column = 0;
  let at = null;
  let current = null;
  for (const line of hierarchy.split('\n')) {
    const words = line.trim().split(/\s+/);
    if (words[0] === 'ROOT' || words[0] === 'JOINT') current = words[1];
    if (words[0] === 'CHANNELS') {
      const n = Number(words[1]);
      if (current === name) at = [column, n];
      column += n;
    }
  }
  const rows = motion.split('\n').slice(2).filter((l) => l.trim().length > 0);
  const values = rows[frame].trim().split(/\s+/).map(Number);
  return at ? values.slice(at[0], at[0] + at[1]) : null;
}

const { context, page, close, errors } = await launch(chromiumPath, 'webgl2');
try {
  await page.goto(base);
  await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);

  await step('Edit mode by its checkbox, a hand dragged and keyed with k, its diamond dragged along the timeline', async () => {
    await changeAndRender(page, (v) => { v.pause(); v.seek(20); });
    await slowClick(page, 755, 12);
    const on = await waitState(page, (s) => s.poseMode === true);
    check(on.poseMode, 'the Edit mode checkbox turns Edit mode on');
    const [x, y] = await page.evaluate(() => Array.from(window.mocapViewer.jointScreenPosition(0, 'LeftHand')));
    await drag(page, x, y, 40, -32);
    await waitState(page, (s) => s.clips[0].corrected === true);
    await page.keyboard.press('k');
    const keyed = await waitState(page, (s) => s.clips[0].keys.length === 1);
    check(keyed.clips[0].keys[0] === 20 && keyed.undo === 'Key at frame 20', `k keys frame 20 (${keyed.clips[0].keys}, undo "${keyed.undo}")`);
    await changeAndRender(page, (v) => v.pause());
    const strip = await page.screenshot({ clip: { x: 0, y: 750, width: 1280, height: 20 } });
    const x20 = await diamondX(context, strip);
    check(x20 !== null, `the key's diamond is on the scrub bar (x ${x20})`);
    // The bar starts at x 8; frame 20 is at x20, so frame 40 is twice as far.
    const x40 = 8 + 2 * (x20 - 8);
    await page.mouse.move(x20, 760);
    await page.mouse.down();
    for (let k = 1; k <= 10; k++) {
      await page.mouse.move(x20 + (x40 - x20) * k / 10, 760);
      await page.waitForTimeout(50);
    }
    await page.screenshot({ path: shot('key-drag') });
    await page.mouse.up();
    const moved = await waitState(page, (s) => s.clips[0].keys.length === 1 && s.clips[0].keys[0] !== 20);
    const to = moved.clips[0].keys[0];
    check(Math.abs(to - 40) <= 1 && moved.frame === to && !moved.playing, `the key moved to frame ${to} and the playhead with it (frame ${moved.frame})`);
    check(/key/i.test(moved.undo ?? ''), `moving it is one undoable step ("${moved.undo}")`);
  });

  await step('Edit ▸ Reverse clicked, then Ctrl+Z', async () => {
    const before = await page.evaluate(() => window.mocapViewer.saveBvh(0)[1]);
    check(await openMenu(context, page, 931, 990), 'the Edit menu opens');
    await page.screenshot({ path: shot('menu') });
    await slowClick(page, 944, 135);
    const reversed = await waitState(page, (s) => s.undo === 'Reverse');
    check(reversed.clips[0].frames === 67 && reversed.clips[0].edited, `Reverse is made and can be undone ("${reversed.undo}")`);
    await page.keyboard.press('Control+z');
    const undone = await waitState(page, (s) => s.redo === 'Reverse');
    const after = await page.evaluate(() => window.mocapViewer.saveBvh(0)[1]);
    check(after === before, `Ctrl+Z gives back the clip as it was (undo now "${undone.undo}")`);
  });

  await step('Edit ▸ Layer on RightShoulder with RightArm mapped to the layer\'s LeftArm in its table', async () => {
    await page.evaluate((t) => window.mocapViewer.add('second.bvh', new TextEncoder().encode(t)), walk);
    await waitState(page, (s) => s.clips.length === 2);
    // The layer plays the walk backwards, so what it drives differs from the base.
    const reversed = await page.evaluate(() => window.mocapViewer.edit(1, 'reverse') ?? null);
    check(reversed === null, `the second clip is reversed (${reversed})`);
    await changeAndRender(page, (v) => { v.pause(); v.seek(20); v.applyViewState('draw=joints,interp'); });
    await slowClick(page, 117, 360);
    await waitState(page, (s) => s.selectedJoint === 'RightShoulder' && s.selectedCharacter === 0);
    check(await openMenu(context, page, 950, 990), 'the Edit menu opens');
    await slowClick(page, 1036, 434);
    await changeAndRender(page, (v) => v.pause());
    await page.screenshot({ path: shot('layer-window') });
    await slowClick(page, 790, 301);
    await changeAndRender(page, (v) => v.pause());
    await page.screenshot({ path: shot('layer-combo') });
    await slowClick(page, 757, 489);
    await changeAndRender(page, (v) => v.pause());
    await slowClick(page, 790, 324);
    await changeAndRender(page, (v) => v.pause());
    await slowClick(page, 787, 351);
    await changeAndRender(page, (v) => v.pause());
    await page.screenshot({ path: shot('layer-mapped') });
    await slowClick(page, 650, 379);
    const layered = await waitState(page, (s) => (s.undo ?? '').startsWith('Layer'));
    check(layered.undo === 'Layer second.bvh on RightShoulder', `Layer is one undoable edit ("${layered.undo}")`);
    const text = await page.evaluate(() => window.mocapViewer.saveBvh(0)[1]);
    const near = (a, b) => a && b && a.length === b.length && a.every((x, i) => Math.abs(x - b[i]) < 0.01);
    for (const f of [10, 50]) {
      const arm = channelsOf(text, 'RightArm', f);
      check(near(arm, channelsOf(walk, 'LeftArm', 66 - f)), `frame ${f}: RightArm plays the layer's LeftArm, chosen in the table (${arm})`);
      const fore = channelsOf(text, 'RightForeArm', f);
      check(near(fore, channelsOf(walk, 'RightForeArm', f)) && !near(fore, channelsOf(walk, 'RightForeArm', 66 - f)),
        `frame ${f}: RightForeArm, left out in the table, keeps the base (${fore})`);
      check(near(channelsOf(text, 'LeftArm', f), channelsOf(walk, 'LeftArm', f)), `frame ${f}: LeftArm, outside the subtree, is unchanged`);
    }
  });
  await step('Capture skeleton clicked on an MD2 model: progress, then the skeleton inside the mesh', async () => {
    await page.goto(`${base}?url=corpus/md2/waste/tris.md2&url=corpus/md2/waste/waste.pcx`);
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);
    const orangeIn = async () => {
      const { data: d } = await decodePng(context, await page.screenshot({ clip: { x: 330, y: 120, width: 520, height: 480 } }));
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] > 200 && d[i + 1] > 110 && d[i + 1] < 190 && d[i + 2] < 120) n += 1;
      return n;
    };
    await changeAndRender(page, (v) => { v.seek(40); v.pause(); });
    const before = await orangeIn();
    await changeAndRender(page, (v) => { v.seek(0); v.pause(); });
    await slowClick(page, 1064, 588);
    let seen = null;
    for (let i = 0; i < 400 && !seen; i++) {
      seen = await page.evaluate(() => window.mocapViewer.captureProgress() ?? null);
      if (!seen) await page.waitForTimeout(5);
    }
    check(seen && seen.length === 2 && seen[1] > 198, `the button starts a capture that reports progress (${seen})`);
    const s = await waitState(page, (s) => s.clips.length === 2, undefined, 120000);
    check(s.layout === 'overlay' && s.clips[1].name === 'tris-capture.bvh' && s.clips[1].frames === 198 && s.clips[0].animation === 'all',
      `the captured clip joins in overlay, every frame in step (${s.layout}, ${s.clips.map((c) => `${c.name} ${c.frames}`).join(', ')})`);
    const report = await page.evaluate(() => window.mocapViewer.captureReport());
    check(/max resid/.test(report) && /Hips/.test(report), 'the per-joint report is there');
    await changeAndRender(page, (v) => { v.seek(40); v.pause(); });
    await page.screenshot({ path: shot('capture'), clip: { x: 330, y: 120, width: 520, height: 480 } });
    const orange = await orangeIn();
    check(orange > before + 300, `the orange skeleton is drawn over the model (${orange} orange pixels, ${before} before the capture)`);
  });
  await step('Fit skeleton on the model, a joint dragged in the view, Done: the next capture uses that rig', async () => {
    await page.goto(`${base}?url=corpus/md2/waste/tris.md2&url=corpus/md2/waste/waste.pcx`);
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);
    await changeAndRender(page, (v) => v.pause());
    await slowClick(page, 1048, 565);
    await waitState(page, (s) => s.frame === 0 && !s.playing);
    const rig0 = JSON.parse(await page.evaluate(() => window.mocapViewer.rigJson() ?? 'null'));
    check(rig0 && rig0.format === 'mocap-capture-rig' && rig0.joints.length > 15, `Fit skeleton makes a rig (${rig0 && rig0.joints.length} joints)`);
    await changeAndRender(page, (v) => v.pause());
    const [x, y] = Array.from(await page.evaluate(() => window.mocapViewer.rigJointScreenPosition('Head_End')));
    await drag(page, x, y, 24, -18, 6, 50);
    await changeAndRender(page, (v) => v.pause());
    await page.screenshot({ path: shot('rig-setup') });
    const rig1 = JSON.parse(await page.evaluate(() => window.mocapViewer.rigJson()));
    const moved = (j) => rig1.joints.find((x) => x.name === j).position.some((c, i) => Math.abs(c - rig0.joints.find((x) => x.name === j).position[i]) > 0.5);
    check(moved('Head_End') && !moved('Hips'), 'dragging a cross moves that rig joint only');
    const [px, py] = Array.from(await page.evaluate(() => window.mocapViewer.rigJointScreenPosition('Head_End')));
    check(Math.hypot(px - (x + 24), py - (y - 18)) < 4, `the joint is under the pointer (${px.toFixed(0)},${py.toFixed(0)})`);
    await slowClick(page, 1149, 654);
    await changeAndRender(page, (v) => v.pause());
    const kept = JSON.parse(await page.evaluate(() => window.mocapViewer.rigJson() ?? 'null'));
    check(kept && JSON.stringify(kept.joints) === JSON.stringify(rig1.joints), 'Done keeps the rig for the next capture');
    const error = await page.evaluate(() => window.mocapViewer.capture(0, true) ?? null);
    const s = await waitState(page, (s) => s.clips.length === 2);
    const report = await page.evaluate(() => window.mocapViewer.captureReport());
    check(error === null && s.clips[1].name === 'tris-capture.bvh' && report.split('\n').filter((l) => /^Head_End /.test(l)).length === 1, `captured with it (${error})`);
  });
  check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
} finally {
  await close();
}
finish('editing');
