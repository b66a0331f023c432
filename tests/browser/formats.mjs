// Browser tests of the formats beyond BVH, for one GPU mode:
// node formats.mjs <url> <webgl2|webgpu> <outDir> <chromium> <acclaim.json>
// - dropping an Acclaim skeleton with its motion opens one character with the
//   motion's frame count, and a joint stands where the core puts it;
// - a motion dropped alone uses the last skeleton; ?url=skel.asf&url=take.amc pairs;
// - a BVA file opens as segments;
// - a 200,000-level-deep (valid) BVH opens without killing the page, and a good file
//   opens after it;
// - a Quake 2 MD2 model dropped with its skin opens as one character with its
//   animations; picking one plays it (the picture changes while it plays) and the
//   skin's colours are on screen (not without the skin); ?url=model&url=skin#anim=
//   opens the pair on that animation; a JPEG skin works as the BMP one does.
import fs from 'node:fs';
import path from 'node:path';
import { launch, state, waitState, waitFrames, changeAndRender, decodePng, dropFiles, waitDropped, view3d, reporter } from './common.mjs';

const [url, mode, outDir, chromiumPath, acclaimPath] = process.argv.slice(2);
const acclaim = JSON.parse(fs.readFileSync(acclaimPath, 'utf8'));
const shot = (name) => path.join(outDir, `${mode}-formats-${name}.png`);
const { check, step, finish } = reporter(`${mode} formats`);
const read = (p) => fs.readFileSync(p);
const base = (p) => path.basename(p);

/** Pixel statistics of a PNG, and how many pixels differ from `other`. */
async function pixels(context, png, other) {
  const { data: d } = await decodePng(context, png);
  const r = other ? (await decodePng(context, other)).data : null;
  let saturated = 0;
  let changed = 0;
  for (let i = 0; i < d.length; i += 4) {
    const hi = Math.max(d[i], d[i + 1], d[i + 2]);
    const lo = Math.min(d[i], d[i + 1], d[i + 2]);
    // Strong colour: the faerie skin's red wings and green dress, never the grey
    // floor, the dark background or the neutral material.
    if (hi - lo > 70) saturated += 1;
    if (r && Math.abs(d[i] - r[i]) + Math.abs(d[i + 1] - r[i + 1]) + Math.abs(d[i + 2] - r[i + 2]) > 30) changed += 1;
  }
  return { saturated, changed };
}

const { context, page, close, errors } = await launch(chromiumPath, mode);
try {
  await page.goto(url);
  await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);

  await step('drop an ASF skeleton with its AMC motion', async () => {
    await dropFiles(page, [{ name: base(acclaim.asf), bytes: read(acclaim.asf) }, { name: base(acclaim.amc), bytes: read(acclaim.amc) }]);
    const s = await waitDropped(page, base(acclaim.amc));
    check(s.error === null, `no error (${s.error})`);
    check(s.clips.length === 1 && s.clips[0].name === base(acclaim.amc), `one character named after the motion (${s.clips.map((c) => c.name)})`);
    check(s.clips[0].frames === acclaim.frames, `${s.clips[0].frames} frames, the core says ${acclaim.frames}`);
    // A paused page draws only what changed: wait for the frame after the seek (read
    // in the same task as the seek, so a quick repaint cannot be missed), not for two more.
    await changeAndRender(page, (v) => { v.pause(); v.seek(0); });
    const p = await page.evaluate(([j]) => window.mocapViewer.jointPosition(0, j), [acclaim.joint]);
    const d = p ? Math.hypot(p[0] - acclaim.position[0], p[1] - acclaim.position[1], p[2] - acclaim.position[2]) : Infinity;
    check(d < 1e-4, `${acclaim.joint} at frame 0 is at [${p}], the core says [${acclaim.position}]`);
    await view3d(page, shot('acclaim'));
    await page.screenshot({ path: shot('acclaim-page') });
    await page.evaluate(() => window.mocapViewer.play());
  });

  await step('a motion dropped alone uses the last skeleton opened', async () => {
    await dropFiles(page, [{ name: base(acclaim.amc), bytes: read(acclaim.amc) }]);
    const s = await waitDropped(page, base(acclaim.amc));
    check(s.error === null && s.clips.length === 1 && s.clips[0].frames === acclaim.frames, `AMC alone opens (${s.error})`);
  });

  await step('the BVA fixture opens as segments', async () => {
    const bva = new URL('../../data/walk.bva', import.meta.url).pathname;
    await dropFiles(page, [{ name: 'walk.bva', bytes: read(bva) }]);
    const s = await waitDropped(page, 'walk.bva');
    check(s.error === null && s.clips[0].frames === 67, `walk.bva: ${s.clips[0].frames} frames (${s.error})`);
    await changeAndRender(page, (v) => v.play());
    await waitFrames(page, 2);
    await view3d(page, shot('bva'));
  });

  await step('a 200,000-level-deep BVH opens, then a good file', async () => {
    const rendered = (await state(page)).framesRendered;
    await page.evaluate(() => {
      const depth = 200000;
      const parts = ['HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n'];
      for (let i = 1; i < depth; i++) parts.push(`JOINT j${i}\n{\nOFFSET 0 0.01 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n`);
      parts.push('End Site\n{\nOFFSET 0 0.01 0\n}\n', '}\n'.repeat(depth), 'MOTION\nFrames: 1\nFrame Time: 0.033333\n', '1 2 3 '.repeat(depth), '\n');
      const dt = new DataTransfer();
      dt.items.add(new File([parts.join('')], 'deep.bvh'));
      window.mocapLastLoad = null;
      const canvas = document.getElementById('viewer');
      for (const type of ['dragenter', 'dragover', 'drop']) canvas.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true }));
    });
    const s = await waitDropped(page, 'deep.bvh');
    check(s.error === null && s.clips.length === 1 && s.clips[0].joints === 200000, `deep.bvh: ${s.clips[0] && s.clips[0].joints} joints (${s.error})`);
    const s2 = await waitState(page, (s, a) => s.framesRendered > a + 2, rendered);
    check(s2.framesRendered > rendered, 'the page keeps drawing');
    await page.screenshot({ path: shot('deep') });
    const walk = new URL('../../data/walk.bvh', import.meta.url).pathname;
    await dropFiles(page, [{ name: 'walk.bvh', bytes: read(walk) }]);
    const s3 = await waitDropped(page, 'walk.bvh');
    check(s3.error === null && s3.clips[0].name === 'walk.bvh' && s3.clips[0].frames === 67, 'a good file opens after the deep one');
  });

  const md2 = (p) => path.join(acclaim.corpus, 'md2', p);
  await step('an MD2 model dropped without its skin is drawn in the neutral material', async () => {
    await dropFiles(page, [{ name: 'faerie.md2', bytes: read(md2('irrlicht_faerie/faerie.md2')) }]);
    const s = await waitDropped(page, 'faerie.md2');
    check(s.error === null && s.clips.length === 1 && s.clips[0].skin === null, `faerie.md2 opens without a skin (${s.error})`);
    await changeAndRender(page, (v) => { v.pause(); v.seek(0); });
  });
  const plain = await view3d(page, shot('md2-plain'));

  await step('an MD2 model dropped with its skin opens with its animations; picking one plays it', async () => {
    await dropFiles(page, [{ name: 'faerie.md2', bytes: read(md2('irrlicht_faerie/faerie.md2')) }, { name: 'faerie2.bmp', bytes: read(md2('irrlicht_faerie/faerie2.bmp')) }]);
    const s = await waitDropped(page, 'faerie2.bmp');
    const c = s.clips[0];
    check(s.error === null && s.clips.length === 1, `one character, no error (${s.error})`);
    check(c.skin === 'faerie2.bmp', `the dropped skin is used (${c.skin})`);
    check(c.frames === 198 && c.animation === 'all' && c.joints === 0, `all 198 frames play at first (${c.frames}, ${c.animation})`);
    check(c.animations.length === 20 && c.animations.includes('run') && c.animations.includes('death3'), `its animations are listed (${c.animations})`);
    check(Math.abs(c.frameTime - 0.1) < 1e-9, `10 frames per second (${c.frameTime})`);
    await changeAndRender(page, (v) => { v.pause(); v.seek(0); });
    const still = await view3d(page, shot('md2-skin'));
    const px = await pixels(context, still, plain);
    const neutral = await pixels(context, plain);
    check(px.saturated > 400 && px.saturated > 10 * (neutral.saturated + 1), `the skin's colours are on screen (${px.saturated} strongly coloured pixels, ${neutral.saturated} without the skin)`);
    check(await page.evaluate(() => window.mocapViewer.setAnimation(0, 'run')), 'setAnimation(0, "run")');
    check(!(await page.evaluate(() => window.mocapViewer.setAnimation(0, 'fly'))), 'an unknown animation is refused');
    const r = await waitState(page, (s) => s.clips[0].animation === 'run');
    check(r.clips[0].frames === 6 && r.view.includes('anim=1:run'), `run: 6 frames on the timeline, kept in the fragment (${r.clips[0].frames}, ${r.view})`);
    await page.evaluate(() => { window.mocapViewer.seek(0); window.mocapViewer.play(); });
    await waitFrames(page, 3);
    const a = await view3d(page, shot('md2-run-a'));
    const t0 = (await state(page)).time;
    // The playhead moves on (however slowly the software GPU draws; a 0.5 s loop
    // comes back to 0 now and then, so any later sample may read 0 again).
    const moving = await waitState(page, (s, t) => s.playing && s.time !== t, t0);
    await waitFrames(page, 2);
    const b = await view3d(page, shot('md2-run-b'));
    const s2 = await state(page);
    const moved = await pixels(context, a, b);
    check(moving.playing && moving.time !== t0, `it plays (time ${t0} → ${moving.time}, frame ${moving.clips[0].modelFrame} ${moving.clips[0].frameName})`);
    check(s2.clips[0].modelFrame >= 40 && s2.clips[0].modelFrame <= 45 && /^run/.test(s2.clips[0].frameName), 'the frames drawn are the run frames');
    check(moved.changed > 100, `the picture changes while it plays (${moved.changed} pixels)`);
    await page.screenshot({ path: shot('md2-page') });
  });

  let jpegBytes = Buffer.alloc(0);
  await step('an MD2 model dropped with a JPEG skin is drawn with it', async () => {
    // The BMP skin re-encoded as JPEG by the browser (the project has no JPEG
    // skin of its own, and the corpus none).
    const bmp = [...read(md2('irrlicht_faerie/faerie2.bmp'))];
    const jpeg = await page.evaluate(async (bytes) => {
      const bitmap = await createImageBitmap(new Blob([new Uint8Array(bytes)], { type: 'image/bmp' }));
      const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
      canvas.getContext('2d').drawImage(bitmap, 0, 0);
      const blob = await canvas.convertToBlob({ type: 'image/jpeg', quality: 0.9 });
      return [...new Uint8Array(await blob.arrayBuffer())];
    }, bmp);
    check(jpeg[0] === 0xff && jpeg[1] === 0xd8, `the browser made a JPEG (${jpeg.length} bytes)`);
    await dropFiles(page, [{ name: 'faerie.md2', bytes: read(md2('irrlicht_faerie/faerie.md2')) }, { name: 'faerie2.jpg', bytes: Buffer.from(jpeg) }]);
    const s = await waitDropped(page, 'faerie2.jpg');
    check(s.error === null && s.clips.length === 1 && s.clips[0].skin === 'faerie2.jpg', `the JPEG skin is used (${s.clips[0] && s.clips[0].skin}, ${s.error})`);
    await changeAndRender(page, (v) => { v.pause(); v.seek(0); });
    const still = await view3d(page, shot('md2-jpeg'));
    const px = await pixels(context, still, plain);
    check(px.saturated > 400, `the JPEG skin's colours are on screen (${px.saturated} strongly coloured pixels)`);
    jpegBytes = Buffer.from(jpeg);
  });

  await step('a drop that partly opens says so: the model opens, its skin cut inside its header is named', async () => {
    await dropFiles(page, [{ name: 'faerie.md2', bytes: read(md2('irrlicht_faerie/faerie.md2')) }, { name: 'cut.jpg', bytes: jpegBytes.subarray(0, 200) }]);
    const s = await waitDropped(page, 'cut.jpg');
    check(s.clips.length === 1 && s.clips[0].name === 'faerie.md2' && s.clips[0].skin === null, `the model opens without the skin (${s.clips.map((c) => c.name)}, ${s.clips[0] && s.clips[0].skin})`);
    check(/^cut\.jpg:byte \d+: /.test(s.error ?? ''), `the skin's error names it: ${s.error}`);
    check(s.errorNote === 'The other files opened.', `the banner does not claim that what was open is still open: ${s.errorNote}`);
    await page.screenshot({ path: shot('md2-partly') });
  });

  await step('?url=model.md2&url=skin.pcx#anim=1:run opens the pair on that animation', async () => {
    const rel = (p) => `corpus/md2/${p}`;
    await page.goto(`${url}?url=${encodeURIComponent(rel('waste/tris.md2'))}&url=${encodeURIComponent(rel('waste/waste.pcx'))}#anim=1:run&play=0&t=0.2`);
    const s = await waitState(page, (s) => s.clips.length === 1 && s.clips[0].name === 'tris.md2' && s.clips[0].modelFrame !== null && s.framesRendered > 2);
    const c = s.clips[0];
    check(s.error === null && c.skin === 'waste.pcx' && c.animation === 'run' && c.frames === 6, `linked model opens with its skin on run (${c.skin}, ${c.animation}, ${s.error})`);
    check(c.modelFrame === 42 && c.frameName === 'run3', `t=0.2 shows run3, frame 42 (${c.modelFrame} ${c.frameName})`);
    await view3d(page, shot('md2-link'));
  });

  await step('?url=skeleton.asf&url=motion.amc opens the pair', async () => {
    const rel = (p) => `corpus/${path.relative(acclaim.corpus, p)}`;
    await page.goto(`${url}?url=${encodeURIComponent(rel(acclaim.asf))}&url=${encodeURIComponent(rel(acclaim.amc))}`);
    const s = await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);
    check(s.error === null && s.clips[0].name === base(acclaim.amc) && s.clips[0].frames === acclaim.frames, `linked pair opens (${s.clips.map((c) => c.name)}, ${s.error})`);
    await view3d(page, shot('acclaim-link'));
  });

  check(errors.filter((e) => !/Failed to load resource/.test(e)).length === 0, `no console errors (${errors.join(' | ')})`);
} finally {
  await close();
}
finish('format checks');
