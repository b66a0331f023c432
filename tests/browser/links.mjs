// Browser tests for links: `?url=` loading from a second origin (with and without CORS),
// its error messages, the view state in the fragment, Share, `?embed=1` and the CSP.
// node links.mjs <url> <webgl2|webgpu> <outDir> <chromium>
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { launch, state, waitState, waitFrames, dropFile, view3d, waitDropped, slowClick, reporter } from './common.mjs';

const [base, mode, outDir, chromiumPath] = process.argv.slice(2);
const shot = (name) => path.join(outDir, `${mode}-link-${name}.png`);
const { check, step, finish } = reporter(`${mode}`);

const walk = fs.readFileSync(new URL('../../data/walk.bvh', import.meta.url));
// A 3 MB clip: the walk's motion rows repeated (a disagreeing Frames: count is only a warning).
const walkText = walk.toString('latin1');
const motionAt = walkText.indexOf('Frame Time:');
const rowsAt = walkText.indexOf('\n', motionAt) + 1;
const rows = walkText.slice(rowsAt);
let bigText = walkText.slice(0, rowsAt);
let bigFrames = walkText.slice(rowsAt).split('\n').filter((l) => l.trim()).length;
const perCopy = bigFrames;
while (bigText.length < 3 * 1048576) {
  bigText += rows.endsWith('\n') ? rows : `${rows}\n`;
}
bigFrames = bigText.slice(rowsAt).split('\n').filter((l) => l.trim()).length;
const big = Buffer.from(bigText, 'latin1');

const FILES = {
  '/walk.bvh': walk,
  '/big.bvh': big,
  '/slow.bvh': big,
  '/notes.html': Buffer.from('<!DOCTYPE html><script>window.pwned = true</script><p>not motion</p>'),
};

/** A static server on a free port; `cors` adds Access-Control-Allow-Origin. Big files trickle. */
function fileServer(cors) {
  const server = http.createServer(async (req, res) => {
    const body = FILES[new URL(req.url, 'http://x').pathname];
    const headers = cors ? { 'Access-Control-Allow-Origin': '*' } : {};
    if (!body) {
      res.writeHead(404, { ...headers, 'Content-Type': 'text/plain' });
      res.end('not found');
      return;
    }
    res.writeHead(200, { ...headers, 'Content-Type': 'text/plain', 'Content-Length': body.length });
    const pause = req.url.startsWith('/slow') ? 400 : 15;
    for (let at = 0; at < body.length; at += 256 * 1024) {
      res.write(body.subarray(at, at + 256 * 1024));
      await new Promise((r) => setTimeout(r, pause));
    }
    res.end();
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve({ server, origin: `http://127.0.0.1:${server.address().port}` })));
}

/** Serves dist/ under /deep/site/ (a static host with the page in a sub-path). */
function subPathServer() {
  const dist = new URL('../../dist/', import.meta.url).pathname;
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm', '.css': 'text/css' };
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://x');
    const rel = url.pathname.startsWith('/deep/site/') ? url.pathname.slice('/deep/site/'.length) || 'index.html' : null;
    const file = rel && !rel.split('/').includes('..') ? path.join(dist, rel) : null;
    if (!file || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
      res.writeHead(404);
      res.end();
      return;
    }
    res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
    res.end(fs.readFileSync(file));
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve({ server, origin: `http://127.0.0.1:${server.address().port}` })));
}

const cors = await fileServer(true);
const sub = await subPathServer();
const plain = await fileServer(false);
// A port nothing listens on: bind, note the port, close.
const closed = await fileServer(false);
const closedOrigin = closed.origin;
await new Promise((r) => closed.server.close(r));

const { context, page, close, errors } = await launch(chromiumPath, mode);
await context.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(base).origin });
const open = async (p, query, prefix = base) => {
  await p.goto(`${prefix}${query}`);
  await p.waitForFunction(() => window.mocapReady === true, null, { timeout: 90000 });
  return state(p);
};

try {
  await step('?url= loads a clip from a CORS host with progress', async () => {
    await open(page, `?url=${encodeURIComponent(`${cors.origin}/big.bvh`)}`);
    const s = await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 3);
    const load = await page.evaluate(() => window.mocapUrlLoad);
    check(s.clips[0].name === 'big.bvh' && s.clips[0].frames === bigFrames,
      `big.bvh open with ${s.clips[0].frames} frames (expected ${bigFrames}, ${perCopy} per copy)`);
    check(load.error === null && load.bytes === big.length && load.progressEvents > 2,
      `progress: ${load.progressEvents} events, ${load.bytes} of ${big.length} bytes, total ${load.total}`);
    check(s.playing && s.error === null, 'it plays, no error');
    const a = await view3d(page, shot('url-a'));
    await page.waitForTimeout(500);
    await waitFrames(page, 3);
    const b = await view3d(page, shot('url-b'));
    check(!a.equals(b), 'the linked clip animates');
  });

  await step('a large file shows a progress bar while it arrives', async () => {
    await page.goto(`${base}?url=${encodeURIComponent(`${cors.origin}/slow.bvh`)}`);
    await page.waitForFunction(() => window.mocapUrlLoad && window.mocapUrlLoad.bytes > 600000 && !window.mocapUrlLoad.done, null, { timeout: 60000 });
    const bar = await page.evaluate(() => {
      const st = document.getElementById('status');
      const p = st.querySelector('progress');
      return { hidden: st.hidden, text: st.textContent, value: p && p.value, max: p && p.max };
    });
    await page.screenshot({ path: shot('progress') });
    check(!bar.hidden && /Loading slow\.bvh: [\d.]+ \/ 3\.0 MB/.test(bar.text) && bar.value > 0 && bar.max === big.length,
      `progress shown: "${bar.text}" (${bar.value} / ${bar.max})`);
    const s = await waitState(page, (s) => s.clips.length === 1, null, 60000);
    check(s.clips[0].name === 'slow.bvh' && await page.evaluate(() => document.getElementById('status').hidden), 'loaded, progress hidden');
  });

  await step('dist/ works from a sub-path of another static host', async () => {
    await open(page, `${sub.origin}/deep/site/?url=${encodeURIComponent(`${cors.origin}/walk.bvh`)}`, '');
    const s = await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 3);
    check(s.clips[0].name === 'walk.bvh' && s.error === null, `page at /deep/site/ loads and opens a linked clip (${s.backend})`);
  });

  await step('relative ?url=data/walk.bvh resolves against the page', async () => {
    await open(page, '?url=data/walk.bvh');
    const s = await waitState(page, (s) => s.clips.length === 1);
    check(s.clips[0].name === 'walk.bvh' && s.clips[0].frames === 67 && s.error === null, `data/walk.bvh open (${s.clips[0].frames} frames)`);
  });

  const failing = [
    ['missing file', `${cors.origin}/missing.bvh`, /not found \(HTTP 404\)/],
    ['host without CORS', `${plain.origin}/walk.bvh`, /blocked by CORS.*Access-Control-Allow-Origin/],
    ['not a motion file', `${cors.origin}/notes.html`, /not a motion file or model/],
    ['javascript: URL', 'javascript:window.pwned=true', /Only http and https/],
    ['data: URL', 'data:text/plain,HIERARCHY', /Only http and https/],
    ['too large', `${cors.origin}/big.bvh`, /too large.*limit is 1\.0 MB/, '&maxmb=1'],
    ['unreachable host', `${closedOrigin}/walk.bvh`, /network failure/],
  ];
  for (const [what, link, pattern, extra = ''] of failing) {
    await step(`link to a ${what} shows its message`, async () => {
      await open(page, `?url=${encodeURIComponent(link)}${extra}`);
      const s = await waitState(page, (s) => s.error !== null, null, 30000);
      check(pattern.test(s.error) && s.clips.length === 0, `${what}: "${s.error}"`);
      check(await page.evaluate(() => window.pwned === undefined), `${what}: nothing from the link ran`);
    });
  }
  await page.screenshot({ path: shot('error') });

  await step('after a failed link the page keeps working', async () => {
    await dropFile(page, 'walk.bvh', walk);
    const s = await waitDropped(page, 'walk.bvh');
    check(s.clips.length === 1 && s.error === null, 'a dropped file opens after the error');
  });

  await step('the fragment follows the view and Share reproduces it', async () => {
    await open(page, '');
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 3);
    const historyBefore = await page.evaluate(() => history.length);
    await page.evaluate(() => {
      const v = window.mocapViewer;
      v.pause();
      v.seek(23);
      v.selectJoint('LeftForeArm') || v.selectJoint(v.state().clips[0].jointNames[5]);
      v.applyViewState('speed=0.5&range=10-40&draw=joints,axes,interp&panels=tree');
    });
    await page.mouse.click(600, 400);
    for (const key of ['j', 'j', 'z', '2', 'j']) await page.keyboard.press(key);
    await page.mouse.move(600, 300);
    await page.mouse.down({ button: 'right' });
    await page.mouse.move(640, 320, { steps: 4 });
    await page.mouse.up({ button: 'right' });
    // Paused, the viewer draws only on input: each change above came with its repaint.
    await page.waitForTimeout(900);
    const s = await state(page);
    const hash = await page.evaluate(() => location.hash);
    check(hash === `#${s.view}`, `the fragment follows the view: ${hash}`);
    check(await page.evaluate(() => history.length) === historyBefore, 'no new history entries');
    check(/speed=0\.5/.test(s.view) && /sel=/.test(s.view) && /panels=tree/.test(s.view) && /range=10-40/.test(s.view), 'fragment has speed, selection, range, panels');

    await page.evaluate(() => { window.mocapLastShare = null; });
    await slowClick(page, 161, 12); // the "Share" button, right of "Open…" and "Add…"
    await page.waitForFunction(() => window.mocapLastShare, null, { timeout: 20000 });
    const shared = await page.evaluate(() => window.mocapLastShare);
    await page.screenshot({ path: shot('share-box') });
    const clip = await page.evaluate(() => navigator.clipboard.readText().catch(() => null));
    check(shared.link.endsWith(`#${s.view}`) && !shared.local, `Share link: ${shared.link}`);
    check(!shared.copied || clip === shared.link, `clipboard (copied: ${shared.copied}) holds the link`);
    await page.click('#share-close');
    await page.mouse.move(1270, 790);
    await page.waitForTimeout(500);
    const original = await view3d(page, shot('share-original'));
    await page.screenshot({ path: shot('share-original-page') });

    const fresh = await context.newPage();
    fresh.on('console', (msg) => { if (msg.type() === 'error') errors.push(msg.text()); });
    await fresh.goto(shared.link);
    await fresh.waitForFunction(() => window.mocapReady === true, null, { timeout: 90000 });
    await fresh.mouse.move(1270, 790);
    const s2 = await waitState(fresh, (s) => s.clips.length === 1 && s.framesRendered > 1);
    await fresh.waitForTimeout(800);
    const restored = await view3d(fresh, shot('share-restored'));
    await fresh.screenshot({ path: shot('share-restored-page') });
    check(s2.view === s.view, `restored view state equals the original (${s2.view})`);
    check(s2.frame === s.frame && s2.selectedJoint === s.selectedJoint && !s2.playing, `frame ${s2.frame}, ${s2.selectedJoint}, paused`);
    check(restored.equals(original), 'screenshot of the restored view matches the original');
    await fresh.close();
  });

  await step('while playing the fragment is rewritten rarely; pausing writes it at once', async () => {
    await open(page, '');
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 3);
    const seen = await page.evaluate(async () => {
      window.mocapViewer.play();
      const hashes = new Set();
      const t0 = performance.now();
      while (performance.now() - t0 < 3000) {
        hashes.add(location.hash);
        await new Promise((r) => setTimeout(r, 50));
      }
      return [...hashes];
    });
    // The play starts one write (play=1); the time alone moving on makes no other in 3 s.
    check(seen.length <= 2, `fragments seen while playing 3 s: ${seen.length} (${seen.join(' | ')})`);
    check(seen.some((h) => /(^#|&)play=1(&|$)/.test(h)), 'the fragment says it plays');
    await page.evaluate(() => window.mocapViewer.pause());
    await page.waitForTimeout(900);
    const s = await state(page);
    const hash = await page.evaluate(() => location.hash);
    check(hash === `#${s.view}` && /play=0/.test(hash), `paused: the fragment follows the view (${hash})`);
  });

  await step('Share after dropping a local file explains hosting', async () => {
    await dropFile(page, 'local.bvh', walk);
    await waitDropped(page, 'local.bvh');
    await page.evaluate(() => { window.mocapLastShare = null; window.dispatchEvent(new Event('mocap-share')); });
    await page.waitForFunction(() => window.mocapLastShare, null, { timeout: 20000 });
    const shared = await page.evaluate(() => window.mocapLastShare);
    check(shared.local && /must|host/i.test(shared.note) && !/url=/.test(shared.link), `local file: "${shared.note}" ${shared.link}`);
  });

  await step('?embed=1 shows only the 3D view and a minimal timeline', async () => {
    await open(page, `?embed=1&url=${encodeURIComponent(`${cors.origin}/walk.bvh`)}`);
    const s = await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 5);
    await page.screenshot({ path: shot('embed') });
    check(s.embed && s.treeLabels.length === 0 && s.playing, 'embed: no hierarchy panel, clip plays');
  });

  const csp = errors.filter((e) => /Content.Security.Policy/i.test(e));
  check(csp.length === 0, `no Content-Security-Policy violations (${csp.join(' | ')})`);
} finally {
  await close();
  cors.server.close();
  plain.server.close();
  sub.server.close();
}
finish('link tests');
