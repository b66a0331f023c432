// Browser tests of the formats beyond BVH, for one GPU mode:
// node formats.mjs <url> <webgl2|webgpu> <outDir> <chromium> <acclaim.json>
// - dropping an Acclaim skeleton with its motion opens one character with the
//   motion's frame count, and a joint stands where the core puts it;
// - a motion dropped alone uses the last skeleton; ?url=skel.asf&url=take.amc pairs;
// - a BVA file opens as segments;
// - a 200,000-level-deep (valid) BVH opens without killing the page, and a good file
//   opens after it.
import fs from 'node:fs';
import path from 'node:path';
import { launch, state, waitState, waitFrames, dropFiles, waitDropped, view3d, reporter } from './common.mjs';

const [url, mode, outDir, chromiumPath, acclaimPath] = process.argv.slice(2);
const acclaim = JSON.parse(fs.readFileSync(acclaimPath, 'utf8'));
const shot = (name) => path.join(outDir, `${mode}-formats-${name}.png`);
const { check, step, finish } = reporter(`${mode} formats`);
const read = (p) => fs.readFileSync(p);
const base = (p) => path.basename(p);

const { page, close, errors } = await launch(chromiumPath, mode);
try {
  await page.goto(url);
  await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);

  await step('drop an ASF skeleton with its AMC motion', async () => {
    await dropFiles(page, [{ name: base(acclaim.asf), bytes: read(acclaim.asf) }, { name: base(acclaim.amc), bytes: read(acclaim.amc) }]);
    const s = await waitDropped(page, base(acclaim.amc));
    check(s.error === null, `no error (${s.error})`);
    check(s.clips.length === 1 && s.clips[0].name === base(acclaim.amc), `one character named after the motion (${s.clips.map((c) => c.name)})`);
    check(s.clips[0].frames === acclaim.frames, `${s.clips[0].frames} frames, the core says ${acclaim.frames}`);
    await page.evaluate(() => { window.mocapViewer.pause(); window.mocapViewer.seek(0); });
    await waitFrames(page, 2);
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
