// glTF characters in the page: a GLB dropped with a BVH opens as a character
// drawn in its own look, its animations listed; the BVH's motion retargeted onto
// it (JS retarget, as Edit ▸ Retarget onto… does) opens beside it wearing the
// look, its feet on the floor; Save as glTF gives a GLB that opens again; a
// `?url=` link to a .gltf fetches its .bin from beside it.
//   node character.mjs <url> <outDir> <chromium> <gltfDir>
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { launch, state, waitState, dropFiles, changeAndRender, waitDropped, view3d, decodePng, reporter } from './common.mjs';

const [base, outDir, chromiumPath, gltfDir] = process.argv.slice(2);
const shot = (name) => path.join(outDir, `webgl2-character-${name}.png`);
const { check, step, finish } = reporter('character');
const glb = fs.readFileSync(path.join(gltfDir, 'walk.glb'));
const lying = fs.readFileSync(path.join(gltfDir, 'walk-z-up.glb'));
const walk = fs.readFileSync(new URL('../../data/walk.bvh', import.meta.url));

const textured = fs.readFileSync(path.join(gltfDir, 'walk-textured.glb'));

const { context, page, close, errors } = await launch(chromiumPath, 'webgl2');
try {
  await step('a GLB opens as a character in its own look', async () => {
    await page.goto(base);
    await page.waitForFunction(() => window.mocapReady === true, null, { timeout: 90000 });
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);
    await dropFiles(page, [{ name: 'character.glb', bytes: glb }, { name: 'moves.bvh', bytes: walk }]);
    const s = await waitDropped(page, 'moves.bvh');
    check(s.error === null, `no error (${s.error})`);
    check(s.clips.length === 2 && s.clips[0].name === 'character.glb', `open: ${s.clips.map((c) => c.name).join(', ')}`);
    check(JSON.stringify(s.clips[0].animations) === '["walk"]', `its animations: ${JSON.stringify(s.clips[0].animations)}`);
    check(s.clips[0].frames === 67, `${s.clips[0].frames} frames`);
    await changeAndRender(page, (v) => { v.pause(); v.seek(20); });
    await page.screenshot({ path: shot('opened') });
  });

  await step('the BVH retargeted onto it opens beside it, wearing the look', async () => {
    const before = await view3d(page, shot('before'));
    const error = await page.evaluate(() => window.mocapViewer.retarget(1, 0));
    check(error === undefined, `retarget: ${error ?? 'done'}`);
    const s = await changeAndRender(page, (v) => v.seek(30));
    check(s.clips.length === 3 && s.clips[2].name === 'moves.bvh on character.glb', `added: ${s.clips.map((c) => c.name).join(', ')}`);
    check(s.clips[2].joints === s.clips[0].joints, `on the character's ${s.clips[0].joints} joints`);
    const bad = await page.evaluate(() => window.mocapViewer.retarget(1, 0, 'Wing=Hips'));
    check(typeof bad === 'string' && bad.includes('Wing'), `a bad map is refused: ${bad}`);
    const after = await view3d(page, shot('retargeted'));
    check(!before.equals(after), 'the view shows the new character');
    await page.screenshot({ path: shot('three') });
  });

  await step('Save as glTF gives a GLB that opens again', async () => {
    const bytes = await page.evaluate(() => Array.from(window.mocapViewer.saveGltf(2).slice(0, 4)));
    check(String.fromCharCode(...bytes) === 'glTF', `saveGltf(2) starts with ${String.fromCharCode(...bytes)}`);
    const saved = await page.evaluate(() => {
      const b = window.mocapViewer.saveGltf(2);
      let s = '';
      for (let i = 0; i < b.length; i += 0x8000) s += String.fromCharCode(...b.subarray(i, i + 0x8000));
      return btoa(s);
    });
    await dropFiles(page, [{ name: 'saved.glb', bytes: Buffer.from(saved, 'base64') }, { name: 'lying.glb', bytes: lying }], true);
    const s = await waitDropped(page, 'lying.glb');
    check(s.error === null && s.clips.length === 5 && s.clips[3].name === 'saved.glb', `opened again: ${s.clips.map((c) => c.name).join(', ')} ${s.error ?? ''}`);
    check(s.clips[3].joints === s.clips[0].joints && s.clips[3].frames === s.clips[1].frames, 'same joints and frames');
    await changeAndRender(page, (v) => v.seek(40));
    await page.screenshot({ path: shot('saved') });
    check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
  });
  await step('a textured character is drawn with its texture', async () => {
    // xtask's walk-textured.glb: orange and teal stripes around the body.
    await dropFiles(page, [{ name: 'textured.glb', bytes: textured }]);
    const s = await waitDropped(page, 'textured.glb');
    check(s.error === null && s.clips.length === 1, `opened: ${s.clips.map((c) => c.name).join(', ')} ${s.error ?? ''}`);
    await changeAndRender(page, (v) => { v.pause(); v.seek(10); v.applyViewState('mode=body'); });
    const png = await view3d(page, shot('textured'));
    const { data } = await decodePng(context, png);
    let [orange, teal] = [0, 0];
    for (let i = 0; i < data.length; i += 4) {
      const [r, g, b] = [data[i], data[i + 1], data[i + 2]];
      if (r > g + 20 && g > b + 20 && r > 80) orange += 1;
      if (g > r + 40 && b > r + 40) teal += 1;
    }
    check(orange > 300 && teal > 300, `both stripes on screen (${orange} orange, ${teal} teal pixels)`);
    await page.screenshot({ path: shot('textured-page') });
  });

  await step('a ?url= link to a .gltf fetches its .bin beside it', async () => {
    const json = JSON.parse(fs.readFileSync(path.join(gltfDir, 'walk.gltf'), 'utf8'));
    const bin = Buffer.from(json.buffers[0].uri.split(',')[1], 'base64');
    json.buffers[0].uri = 'walk%20data.bin';
    const files = { '/models/walk.gltf': Buffer.from(JSON.stringify(json)), '/models/walk data.bin': bin };
    const server = http.createServer((req, res) => {
      const body = files[decodeURIComponent(new URL(req.url, 'http://x').pathname)];
      res.writeHead(body ? 200 : 404, { 'Access-Control-Allow-Origin': '*', 'Content-Type': 'application/octet-stream' });
      res.end(body ?? 'not found');
    });
    await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
    const origin = `http://127.0.0.1:${server.address().port}`;
    await page.goto(`${base}?url=${encodeURIComponent(`${origin}/models/walk.gltf`)}`);
    await page.waitForFunction(() => window.mocapReady === true, null, { timeout: 90000 });
    const s = await waitState(page, (s) => s.clips.length === 1 && s.clips[0].name === 'walk.gltf' && s.framesRendered > 2);
    check(s.error === null && s.clips[0].frames === 67, `walk.gltf and its .bin opened (${s.clips[0].frames} frames, ${s.error})`);
    check(!s.view.includes('data.bin'), 'the shared link names the .gltf only');
    server.close();
  });
} finally {
  await close();
}
finish('glTF character checks');
