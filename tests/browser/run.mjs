// Browser tests for one GPU mode: node run.mjs <url> <webgl2|webgpu> <outDir> <chromium> <expected.json>
import fs from 'node:fs';
import path from 'node:path';
import { launch, state, waitState, waitFrames, dropFile, view3d, changeAndRender, waitDropped, slowClick, reporter } from './common.mjs';

const [url, mode, outDir, chromiumPath, expectedPath] = process.argv.slice(2);
const expected = JSON.parse(fs.readFileSync(expectedPath, 'utf8'));
const shot = (name) => path.join(outDir, `${mode}-${name}.png`);
const { check, step, finish } = reporter(`${mode}`);

const { page, close, errors } = await launch(chromiumPath, mode);
try {
  await step('page loads and default clip animates', async () => {
    await page.goto(url);
    const s = await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 3);
    check(s.clips[0].name === 'walk.bvh' && s.playing, `default clip walk.bvh playing (${s.clips[0].frames} frames)`);
    const backend = { webgl2: 'Gl', webgpu: 'BrowserWebGpu' }[mode];
    check(s.backend === backend, `3D view drawn with wgpu backend ${s.backend} (expected ${backend})`);
    await page.screenshot({ path: shot('page') });
    // index.html preloads the modules main.js imports and the WebAssembly: each
    // is fetched once, the modules asked for before main.js itself arrived (not
    // found in it), the WebAssembly by its preload (a preload that init() did not
    // match would download the 6 MB module twice).
    const imports = [...fs.readFileSync(new URL('../../web/main.js', import.meta.url), 'utf8')
      .matchAll(/^import[^'"]*['"]([^'"]+)['"]/gm)].map((m) => new URL(m[1], `${url}web/main.js`).pathname);
    const fetched = await page.evaluate(() => performance.getEntriesByType('resource')
      .map((r) => ({ path: new URL(r.name).pathname, by: r.initiatorType, start: r.startTime, end: r.responseEnd })));
    const once = (want) => fetched.filter((r) => r.path.endsWith(want));
    const main = once('/web/main.js');
    check(imports.length >= 4 && main.length === 1, `main.js fetched once, its ${imports.length} imports read`);
    for (const want of imports) {
      const hits = once(want);
      check(hits.length === 1 && main.length === 1 && hits[0].start < main[0].end, `${want} fetched once, asked for before main.js arrived (${JSON.stringify(hits)})`);
    }
    // And index.html preloads nothing else (a module no longer imported would
    // be downloaded for nothing).
    const preloaded = [...fs.readFileSync(new URL('../../index.html', import.meta.url), 'utf8')
      .matchAll(/<link rel="modulepreload" href="([^"]+)">/g)].map((m) => new URL(m[1], url).pathname);
    const mainPath = new URL('web/main.js', url).pathname;
    const stray = preloaded.filter((p) => p !== mainPath && !imports.includes(p));
    check(preloaded.length === imports.length + 1 && stray.length === 0, `index.html preloads main.js and its imports only (${preloaded.length} preloads, stray: ${stray.join(', ') || 'none'})`);
    const wasm = once('/pkg/mocap_web_bg.wasm');
    check(wasm.length === 1 && wasm[0].by === 'link', `the WebAssembly fetched once, by its preload (${JSON.stringify(wasm)})`);
    const a = await view3d(page, shot('anim-a'));
    await page.waitForTimeout(600);
    await waitFrames(page, 3);
    const b = await view3d(page, shot('anim-b'));
    check(!a.equals(b), 'two screenshots of the 3D view differ while playing');
    const s2 = await state(page);
    check(s2.frame !== s.frame || s2.time !== s.time, `playhead moves (${s.time.toFixed(3)} -> ${s2.time.toFixed(3)} s)`);
    check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
  });

  await step('once idle after its first frame the page readies the glTF code, changing nothing', async () => {
    const warm = await page.waitForFunction(() => {
      const mark = performance.getEntriesByName('mocap-warm-up')[0];
      return mark ? { detail: mark.detail } : null;
    }, null, { timeout: 10000 }).then((h) => h.jsonValue()).catch(() => null);
    check(warm !== null && warm.detail === true, `the page's warm-up ran (${JSON.stringify(warm && warm.detail)})`);
    const s = await state(page);
    check(s.clips.length === 1 && s.clips[0].name === 'walk.bvh' && !s.error, `the stage is as it was (${s.clips.map((c) => c.name)}, error ${s.error})`);
    check(await page.evaluate(() => window.mocapViewer.warmUp()), 'warmUp() runs again on demand');
  });

  await step('the start message shows only when the start takes over a second', async () => {
    // The WebAssembly held back 3 s: the page is blank at first, then says
    // it is loading, then the viewer replaces the message. A fresh browser: the
    // first's offline copy (sw.js) would answer without the hold.
    const { page, close } = await launch(chromiumPath, mode);
    await page.route('**/pkg/mocap_web_bg.wasm', async (route) => {
      await new Promise((r) => setTimeout(r, 3000));
      await route.continue();
    });
    try {
      await page.goto(url, { waitUntil: 'commit' });
      await page.waitForSelector('#status', { state: 'attached' });
      const early = await page.evaluate(() => {
        const st = document.getElementById('status');
        const delays = st.getAnimations().map((a) => a.effect.getTiming().delay);
        return { t: performance.now(), visibility: getComputedStyle(st).visibility, delays };
      });
      check(early.delays.length === 1 && early.delays[0] === 1000, `the message waits 1 s before it shows (${JSON.stringify(early)})`);
      if (early.t < 900) check(early.visibility === 'hidden', `blank before then (${early.visibility} at ${early.t.toFixed(0)} ms)`);
      // The delay counts from the message's first style (the page's first frame).
      await page.waitForFunction(() => getComputedStyle(document.getElementById('status')).visibility === 'visible', null, { polling: 50, timeout: 2500 }).catch(() => null);
      const late = await page.evaluate(() => {
        const st = document.getElementById('status');
        return { visibility: getComputedStyle(st).visibility, hidden: st.hidden, text: st.textContent, started: !!window.mocapViewer };
      });
      check(!late.started && late.visibility === 'visible' && !late.hidden && late.text === 'Loading viewer\u2026', `after 1 s, still loading, it says so (${JSON.stringify(late)})`);
      const s = await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 0);
      check(s.clips[0].name === 'walk.bvh' && await page.evaluate(() => document.getElementById('status').hidden), 'once the viewer draws, the message is gone');
    } finally {
      await close();
    }
  });

  await step('clicking a joint in the hierarchy selects it', async () => {
    await slowClick(page, 62, 130); // "Spine", second joint row of the default clip's tree (under the character and offset rows)
    const s = await waitState(page, (s) => s.selectedJoint !== null, null, 20000);
    check(s.selectedJoint === 'Spine', `clicked tree row selects ${s.selectedJoint}`);
    await page.screenshot({ path: shot('tree-click') });
  });

  if (expected.length === 0) console.log(`skip [${mode}] corpus drop tests: ../shared/corpus not found`);
  for (const [i, file] of expected.entries()) {
    const name = path.basename(file.path);
    await step(`drop ${name}`, async () => {
      const before = await view3d(page, shot(`drop${i}-before`));
      await dropFile(page, name, fs.readFileSync(file.path));
      const s = await waitDropped(page, name);
      check(s.clips[0].frames === file.frames, `${name}: ${s.clips[0].frames} frames, mocap info says ${file.frames}`);
      const load = await page.evaluate(() => window.mocapLastLoad);
      check(s.error === null && load.firstFrame === 0, `${name}: no error, first frame shown is frame ${load.firstFrame}`);
      await waitFrames(page, 3);
      const after = await view3d(page, shot(`drop${i}-after`));
      check(!before.equals(after), `${name}: the 3D view changed`);
      const s2 = await state(page);
      const names = s2.clips[0].jointNames;
      check(names.length > 0 && names.every((n) => s2.treeLabels.includes(n)), `${name}: hierarchy shows all ${names.length} joint names`);
    });
  }

  await step('Open… button shows a file picker that loads the file', async () => {
    const file = new URL('../../data/walk.bvh', import.meta.url).pathname;
    const chooser = page.waitForEvent('filechooser', { timeout: 30000 });
    await slowClick(page, 37, 12); // the egui "Open…" button, top left
    const fc = await chooser;
    await page.evaluate(() => { window.mocapLastLoad = null; });
    await fc.setFiles(file);
    const s = await waitDropped(page, 'walk.bvh');
    check(s.clips[0].name === 'walk.bvh' && s.clips[0].frames === 67, `picked walk.bvh is open (${s.clips[0].frames} frames)`);
  });

  await step('scrubbing changes the pose', async () => {
    await changeAndRender(page, (v) => { v.pause(); v.seek(0); });
    const a = await view3d(page, shot('scrub-0'));
    const frames = (await state(page)).clips[0].frames;
    const mid = Math.floor(frames / 2);
    const s = await changeAndRender(page, (v, f) => v.seek(f), mid);
    const b = await view3d(page, shot('scrub-mid'));
    check(s.frame === mid && !s.playing, `seek(${mid}) lands on frame ${s.frame}, paused`);
    check(!a.equals(b), 'pose at frame 0 and mid-clip differ');
  });

  await step('selecting a joint highlights it and shows the inspector', async () => {
    const s0 = await state(page);
    const joint = s0.clips[0].jointNames[Math.min(2, s0.clips[0].jointNames.length - 1)];
    const s = await changeAndRender(page, (v, j) => v.selectJoint(j), joint);
    await page.screenshot({ path: shot('selected') });
    check(s.selectedJoint === joint, `selectJoint(${joint}) -> selectedJoint ${s.selectedJoint}`);
  });

  await step('keyboard: space toggles play, arrows step', async () => {
    await page.mouse.click(600, 400);
    const s0 = await state(page);
    await page.keyboard.press('Space');
    const s1 = await waitState(page, (s, a) => s.playing !== a, s0.playing);
    check(s1.playing !== s0.playing, `space: playing ${s0.playing} -> ${s1.playing}`);
    await page.keyboard.press('Space');
    const s2 = await waitState(page, (s, a) => s.playing === a, s0.playing);
    check(s2.playing === s0.playing, 'space again toggles back');
    await changeAndRender(page, (v) => { v.pause(); v.seek(5); });
    await page.keyboard.press('ArrowRight');
    const s3 = await waitState(page, (s) => s.frame !== 5);
    check(s3.frame === 6, `ArrowRight steps 5 -> ${s3.frame}`);
  });

  await step('malformed file shows an error and keeps the clip', async () => {
    const before = await state(page);
    await dropFile(page, 'broken.bvh', Buffer.from('HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n  CHANNELS 3 Xposition\n'));
    const s = await waitDropped(page, 'broken.bvh');
    await page.screenshot({ path: shot('error') });
    check(/broken\.bvh:\d+:\d+/.test(s.error), `error names file, line and column: ${s.error}`);
    check(s.clips.length === 1 && s.clips[0].name === before.clips[0].name, `previous clip ${before.clips[0].name} still open`);
    check(s.errorNote === 'What was open is still open.', `the banner says the clip is still open: ${s.errorNote}`);
  });
} finally {
  await close();
}
finish('browser tests');
