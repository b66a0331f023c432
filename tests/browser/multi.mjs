// Browser tests for several characters: dropping several files at once, Shift-drop
// adds, visibility, removal, layout, selection in a second character, and repeated
// `?url=` links from a second (CORS) origin with Share reproducing them all.
// node multi.mjs <url> <webgl2|webgpu> <outDir> <chromium> [corpusDir]
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { launch, state, waitState, waitFrames, dropFiles, view3d, changeAndRender, waitDropped, slowClick, reporter } from './common.mjs';

const [base, mode, outDir, chromiumPath, corpusDir] = process.argv.slice(2);
const shot = (name) => path.join(outDir, `${mode}-multi-${name}.png`);
const { check, step, finish } = reporter(`${mode} multi`);

const walk = fs.readFileSync(new URL('../../data/walk.bvh', import.meta.url));

// Walk's motion at 120 fps (4× the frame rate, a quarter of the duration), for runs without the corpus.
const fastWalk = Buffer.from(walk.toString('latin1').replace(/Frame Time:\s*[\d.]+/, 'Frame Time: 0.00833333'), 'latin1');

// Two clips of different frame rates dropped together, and a third added with Shift.
const CORPUS = [
  ['bvh/assimp_cmu/01_01.bvh', 2752, 1 / 120],
  ['bvh/bandai_namco/dataset-2_walk_elderly_004.bvh', 466, 1 / 30],
  ['bvh/snu_mass/walk.bvh', 132, 1 / 120],
];
const haveCorpus = corpusDir && CORPUS.every(([rel]) => fs.existsSync(path.join(corpusDir, rel)));
const FILES = haveCorpus
  ? CORPUS.map(([rel, frames, frameTime]) => ({ name: path.basename(rel), bytes: fs.readFileSync(path.join(corpusDir, rel)), frames, frameTime }))
  : [
    { name: 'walk-a.bvh', bytes: fastWalk, frames: 67, frameTime: 1 / 120 },
    { name: 'walk-b.bvh', bytes: walk, frames: 67, frameTime: 1 / 30 },
    { name: 'walk-c.bvh', bytes: walk, frames: 67, frameTime: 1 / 30 },
  ];
if (!haveCorpus) console.log(`note [${mode} multi] corpus not found: dropping walk.bvh copies instead`);
const [first, second, third] = FILES;
const near = (a, b) => Math.abs(a - b) < 1e-6;

/** Serves FILES by name with CORS (a second origin for `?url=`). */
function corsServer() {
  const server = http.createServer((req, res) => {
    const name = decodeURIComponent(new URL(req.url, 'http://x').pathname.slice(1));
    const file = FILES.find((f) => f.name === name);
    const headers = { 'Access-Control-Allow-Origin': '*' };
    if (!file) {
      res.writeHead(404, { ...headers, 'Content-Type': 'text/plain' });
      res.end('not found');
      return;
    }
    res.writeHead(200, { ...headers, 'Content-Type': 'text/plain', 'Content-Length': file.bytes.length });
    res.end(file.bytes);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve({ server, origin: `http://127.0.0.1:${server.address().port}` })));
}

const cors = await corsServer();
const { page, close, errors } = await launch(chromiumPath, mode);
const open = async (query) => {
  await page.goto(`${base}${query}`);
  await page.waitForFunction(() => window.mocapReady === true, null, { timeout: 90000 });
  return state(page);
};

try {
  await step('dropping two files at once opens both, side by side', async () => {
    await open('');
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);
    await dropFiles(page, [first, second]);
    const s = await waitDropped(page, second.name);
    check(s.clips.length === 2 && s.clips[0].name === first.name && s.clips[1].name === second.name,
      `two clips open: ${s.clips.map((c) => c.name).join(', ')}`);
    check(s.clips[0].frames === first.frames && s.clips[1].frames === second.frames,
      `frames ${s.clips.map((c) => c.frames).join(', ')} (expected ${first.frames}, ${second.frames})`);
    check(near(s.clips[0].frameTime, first.frameTime) || Math.abs(s.clips[0].frameTime - first.frameTime) < 1e-5,
      `frame times ${s.clips.map((c) => c.frameTime.toFixed(5)).join(', ')}`);
    check(s.error === null && s.clips.every((c) => c.visible), 'no error, both visible');
    const backend = { webgl2: 'Gl', webgpu: 'BrowserWebGpu' }[mode];
    check(s.backend === backend, `drawn with wgpu backend ${s.backend} (expected ${backend})`);
    check(s.clips[0].offset[0] < s.clips[1].offset[0] && s.layout === 'spread', `spread along X: offsets ${JSON.stringify(s.clips.map((c) => c.offset.map((x) => +x.toFixed(2))))}`);
    check(s.clips[0].color !== s.clips[1].color, `own colours ${s.clips.map((c) => c.color).join(' ')}`);
    const names = s.clips.flatMap((c) => c.jointNames);
    check(names.every((n) => s.treeLabels.includes(n)), `hierarchy lists the joints of both (${names.length})`);

    // Both in time: one playhead, each clip on its own frame of it.
    const t = await changeAndRender(page, (v) => { v.pause(); v.seek(0); });
    const frames = t.clips[0].frames;
    const mid = await changeAndRender(page, (v, f) => v.seek(f), Math.floor(frames / 3));
    check(near(mid.time, Math.floor(frames / 3) * mid.clips[0].frameTime), `seek counts in the first clip's frames: frame ${mid.frame}, ${mid.time.toFixed(3)} s`);
    await page.mouse.move(1270, 790);
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('two') });
    check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
  });

  await step('hiding a character removes it from the view', async () => {
    const before = await view3d(page, shot('both'));
    const s = await changeAndRender(page, (v) => v.setVisible(1, false));
    const after = await view3d(page, shot('hidden'));
    check(!s.clips[1].visible && s.clips[0].visible, 'character 2 hidden');
    check(/(^|&)hide=2(&|$)/.test(s.view), `fragment has hide=2: ${s.view}`);
    check(!before.equals(after), 'the 3D view changed');
    const back = await changeAndRender(page, (v) => v.setVisible(1, true));
    check(back.clips[1].visible && !/hide=/.test(back.view), 'shown again');
  });

  await step('selecting a joint of the second character', async () => {
    const s0 = await state(page);
    const joint = s0.clips[1].jointNames[1];
    const s = await changeAndRender(page, (v, j) => v.selectJoint(j, 1), joint);
    check(s.selectedJoint === joint && s.selectedCharacter === 1, `selected ${s.selectedCharacter}:${s.selectedJoint}`);
    const encoded = encodeURIComponent(joint).replace(/[!'()*]/g, (c) => `%${c.charCodeAt(0).toString(16).toUpperCase()}`);
    check(s.view.includes(`sel=2:${encoded}`), `fragment has sel=2:${encoded}`);
    await page.screenshot({ path: shot('selected') });
  });

  await step('Shift-drop adds a third character', async () => {
    await dropFiles(page, [third], true);
    const s = await waitDropped(page, third.name);
    check(s.clips.length === 3 && s.clips[2].name === third.name && s.clips[0].name === first.name,
      `three clips: ${s.clips.map((c) => c.name).join(', ')}`);
    check(s.selectedCharacter === 1, 'the selection stays');
    await changeAndRender(page, (v) => v.seek(10));
    await page.screenshot({ path: shot('three') });
  });

  await step('overlay puts everyone in place; remove closes one', async () => {
    const o = await changeAndRender(page, (v) => v.setLayout('overlay'));
    check(o.layout === 'overlay' && o.clips.every((c) => c.offset.every((x) => x === 0)), 'overlay: all offsets zero');
    check(/layout=overlay/.test(o.view), 'fragment has layout=overlay');
    await page.screenshot({ path: shot('overlay') });
    await changeAndRender(page, (v) => v.setLayout('spread'));
    const r = await changeAndRender(page, (v) => v.remove(0));
    check(r.clips.length === 2 && r.clips[0].name === second.name && r.selectedCharacter === 0, `removed the first: ${r.clips.map((c) => c.name).join(', ')}, selection moved to 1`);
  });

  await step('a failed file in a drop is reported and keeps what is open', async () => {
    const bad = { name: 'broken.bvh', bytes: Buffer.from('HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n') };
    await dropFiles(page, [bad], true);
    const s = await waitDropped(page, 'broken.bvh');
    check(/broken\.bvh:\d+:\d+/.test(s.error) && s.clips.length === 2, `error ${s.error}; still 2 clips`);
  });

  await step('the Add… button picks several files and adds them', async () => {
    const dir = fs.mkdtempSync(path.join(outDir, 'pick-'));
    const paths = [first, second].map((f) => {
      const p = path.join(dir, f.name);
      fs.writeFileSync(p, f.bytes);
      return p;
    });
    const chooser = page.waitForEvent('filechooser', { timeout: 30000 });
    await slowClick(page, 102, 12); // the egui "Add…" button, right of "Open…"
    const fc = await chooser;
    check(fc.isMultiple(), 'the picker allows several files');
    const before = (await state(page)).clips.length;
    await page.evaluate(() => { window.mocapLastLoad = null; });
    await fc.setFiles(paths);
    const s = await waitDropped(page, second.name);
    check(s.clips.length === before + 2, `added two: ${before} -> ${s.clips.length} clips`);
    fs.rmSync(dir, { recursive: true, force: true });
  });

  await step('?url=a&url=b opens every link in order; Share keeps them all', async () => {
    const a = `${cors.origin}/${encodeURIComponent(first.name)}`;
    const b = `${cors.origin}/${encodeURIComponent(second.name)}`;
    await open(`?url=${encodeURIComponent(a)}&url=${encodeURIComponent(b)}`);
    const s = await waitState(page, (s) => s.clips.length === 2 && s.framesRendered > 2, null, 60000);
    const loads = await page.evaluate(() => window.mocapUrlLoads);
    check(s.clips[0].name === first.name && s.clips[1].name === second.name && s.error === null,
      `both links open, in order: ${s.clips.map((c) => c.name).join(', ')}`);
    check(loads.length === 2 && loads.every((l) => l.done && l.error === null && l.progressEvents > 0), 'progress and no error per link');
    await page.mouse.move(1270, 790);
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('urls') });
    await page.evaluate(() => { window.mocapLastShare = null; window.dispatchEvent(new Event('mocap-share')); });
    await page.waitForFunction(() => window.mocapLastShare, null, { timeout: 20000 });
    const shared = await page.evaluate(() => window.mocapLastShare);
    const urls = new URL(shared.link).searchParams.getAll('url');
    check(urls.length === 2 && urls[0] === a && urls[1] === b && !shared.local, `Share link carries both: ${shared.link}`);
  });

  await step('one failing link among several shows its error and opens the rest', async () => {
    const a = `${cors.origin}/${encodeURIComponent(first.name)}`;
    await open(`?url=${encodeURIComponent(`${cors.origin}/missing.bvh`)}&url=${encodeURIComponent(a)}#hide=1&layout=overlay`);
    const s = await waitState(page, (s) => s.clips.length === 1 && s.error !== null, null, 60000);
    check(/missing\.bvh: not found/.test(s.error) && s.clips[0].name === first.name, `error "${s.error}", ${s.clips[0].name} open`);
    check(!s.clips[0].visible && s.layout === 'overlay', 'the fragment applied after the links (hide=1, layout=overlay)');
  });
} finally {
  await close();
  cors.server.close();
}
finish('multi-character tests');
