// Autosave: a tab closed after an edit, without saving, then a new tab of the
// same origin shows the edited clip (its frame and camera, and undo still takes
// the edit back), saying so with Discard; a `?url=` link opens the link and
// keeps the earlier session one click away; saving marks the work saved; a full
// storage quota gives a one-line notice and nothing else.
//   node autosave.mjs <url> <webgl2|webgpu> <outDir> <chromium>
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { launch, state, waitState, changeAndRender, reporter } from './common.mjs';

const [base, mode, outDir, chromiumPath] = process.argv.slice(2);
const shot = (name) => path.join(outDir, `${mode}-autosave-${name}.png`);
const { check, step, finish } = reporter(`${mode} autosave`);
const walk = fs.readFileSync(new URL('../../data/walk.bvh', import.meta.url));

// A second origin serving one clip, for the ?url= link.
const server = http.createServer((req, res) => {
  res.writeHead(200, { 'Access-Control-Allow-Origin': '*', 'Content-Type': 'text/plain', 'Content-Length': walk.length });
  res.end(walk);
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const linked = `http://127.0.0.1:${server.address().port}/linked.bvh`;

const ready = (page) => page.waitForFunction(() => window.mocapReady === true, null, { timeout: 90000 });
const saves = (page) => page.evaluate(() => (window.mocapAutosave ? window.mocapAutosave.saves : -1));
// Waits for the autosave after a change made now.
async function stored(page, before) {
  await page.waitForFunction((n) => window.mocapAutosave && window.mocapAutosave.saves > n, before, { timeout: 20000 });
}
// Waits until the session stored in the page's IndexedDB says `unsaved` is
// `want` (and, given `view`, its view holds that text): a store started before a
// change may finish after it, so a count of stores alone does not say the latest
// state is the one kept. Polled from here: `waitForFunction` does not await a
// predicate's promise (a promise is truthy, so it would return at once).
async function storedUnsaved(page, want, view = '') {
  const deadline = Date.now() + 20000;
  let last = null;
  for (;;) {
    last = await page.evaluate(async () => {
      const db = await new Promise((ok, no) => { const r = indexedDB.open('mocap-autosave', 1); r.onsuccess = () => ok(r.result); r.onerror = () => no(r.error); });
      try {
        const current = await new Promise((ok, no) => {
          const r = db.transaction(['sessions'], 'readonly').objectStore('sessions').get('current');
          r.onsuccess = () => ok(r.result); r.onerror = () => no(r.error);
        });
        return current ? { unsaved: current.unsaved, view: String(current.view) } : null;
      } finally {
        db.close();
      }
    });
    if (last && last.unsaved === want && last.view.includes(view)) return;
    if (Date.now() > deadline) throw new Error(`the stored session is not unsaved=${want} with "${view}": ${JSON.stringify(last)}`);
    await new Promise((r) => setTimeout(r, 200));
  }
}

const { context, page: first, close, errors } = await launch(chromiumPath, mode, { keepStorage: true });
try {
  await step('an edit is stored a moment after it is made', async () => {
    await first.goto(base);
    await ready(first);
    await waitState(first, (s) => s.clips.length === 1 && s.framesRendered > 2);
    const before = await saves(first);
    const error = await first.evaluate(() => window.mocapViewer.edit(0, 'trim:0:40'));
    check(error === undefined, `edit: ${error ?? 'done'}`);
    await changeAndRender(first, (v) => { v.pause(); v.seek(25); v.applyViewState('t=0.8333&cam=1.2,0.5,4,0,0.9,0'); });
    await stored(first, before);
    await storedUnsaved(first, true, 'cam=1.2,0.5,4,');
    const s = await state(first);
    check(s.clips[0].unsaved && s.clips[0].edited, 'the edit is unsaved');
  });

  let page;
  await step('the tab closed without saving: a new tab shows the edited clip', async () => {
    page = await context.newPage();
    page.on('pageerror', (err) => errors.push(String(err)));
    await first.close({ runBeforeUnload: false });
    await page.goto(base);
    await ready(page);
    const s = await waitState(page, (s) => s.clips.length === 1 && s.clips[0].frames === 41 && s.framesRendered > 2);
    check(s.clips[0].edited && s.clips[0].unsaved, `edited and unsaved: ${s.clips[0].edited} ${s.clips[0].unsaved}`);
    check(s.frame === 25 && /cam=1.2,0.5,4,/.test(s.view), `the frame and camera: ${s.frame} ${s.view}`);
    const banner = await page.evaluate(() => { const b = document.getElementById('session-banner'); return b.hidden ? '' : b.textContent; });
    check(/Restored your unsaved work/.test(banner) && /Discard/.test(banner), `the banner: ${banner}`);
    await page.screenshot({ path: shot('restored') });
    await page.evaluate(() => window.mocapViewer.undo());
    const undone = await state(page);
    check(undone.clips[0].frames === 67, `undo takes the edit back: ${undone.clips[0].frames} frames`);
    await page.evaluate(() => window.mocapViewer.redo());
    check((await state(page)).clips[0].frames === 41, 'and redo makes it again');
  });

  await step('saving marks the work saved; the next visit says "last session"', async () => {
    const before = await saves(page);
    const saved = await page.evaluate(() => window.mocapViewer.saveBvh(0));
    check(saved && saved[0] === 'walk-edited.bvh', `saved ${saved && saved[0]}`);
    const s = await state(page);
    check(s.clips[0].edited && !s.clips[0].unsaved, 'edited but saved');
    await stored(page, before);
    await storedUnsaved(page, false);
    await page.reload();
    await ready(page);
    await waitState(page, (s) => s.clips.length === 1 && s.clips[0].frames === 41);
    const banner = await page.evaluate(() => document.getElementById('session-banner').textContent);
    check(/Restored your last session/.test(banner), `the banner: ${banner}`);
    check(!(await state(page)).clips[0].unsaved, 'still saved');
  });

  await step('a ?url= link opens the link; the earlier session is one click away', async () => {
    await page.goto(`${base}?url=${encodeURIComponent(linked)}`);
    await ready(page);
    let s = await waitState(page, (s) => s.clips.length === 1 && s.clips[0].name === 'linked.bvh');
    check(s.clips[0].frames === 67 && !s.clips[0].edited, `the link: ${s.clips[0].name} ${s.clips[0].frames}`);
    check(s.previousSession === true, 'a previous session is held');
    const banner = await page.evaluate(() => document.getElementById('session-banner').hidden);
    check(banner, 'no restore banner over a link');
    const before = await saves(page);
    await page.evaluate(() => window.mocapViewer.restorePreviousSession());
    s = await waitState(page, (s) => s.clips.length === 1 && s.clips[0].name === 'walk.bvh' && s.clips[0].frames === 41);
    check(s.clips[0].edited, 'the previous session, with its edit');
    await stored(page, before);
  });

  await step('Discard starts afresh and keeps the work as the previous session', async () => {
    await page.goto(base);
    await ready(page);
    await waitState(page, (s) => s.clips.length === 1 && s.clips[0].frames === 41);
    await page.click('#session-banner button:text("Discard")');
    const s = await waitState(page, (s) => s.clips.length === 1 && s.clips[0].frames === 67);
    check(!s.clips[0].edited && s.previousSession, `the default clip, the work one click away (${s.previousSession})`);
  });

  await step('a full storage quota: a one-line notice, and the viewer goes on', async () => {
    // The test's hook: every write fails as a full origin quota makes it fail.
    await page.evaluate(() => {
      window.__testPut = IDBObjectStore.prototype.put;
      IDBObjectStore.prototype.put = function () { throw new DOMException('The quota has been exceeded.', 'QuotaExceededError'); };
    });
    const error = await page.evaluate(() => window.mocapViewer.edit(0, 'reverse'));
    check(error === undefined, `edit: ${error ?? 'done'}`);
    await page.waitForFunction(() => { const n = document.getElementById('autosave-notice'); return !n.hidden && /full/.test(n.textContent); }, null, { timeout: 20000 });
    const notice = await page.evaluate(() => document.getElementById('autosave-notice').textContent);
    check(/storage for this page is full/.test(notice), `the notice: ${notice}`);
    const s = await changeAndRender(page, (v) => v.seek(10));
    check(s.frame === 10 && s.error === null, `the viewer goes on (frame ${s.frame}, banner ${s.error})`);
    await page.screenshot({ path: shot('full') });
    // Room again: the next change is stored and the notice goes.
    const before = await saves(page);
    await page.evaluate(() => { IDBObjectStore.prototype.put = window.__testPut; });
    await page.evaluate(() => window.mocapViewer.edit(0, 'reverse'));
    await stored(page, before);
    check(await page.evaluate(() => document.getElementById('autosave-notice').hidden), 'stored again: the notice is gone');
  });

  await step('after one visit the page opens without a network', async () => {
    await page.goto(base);
    await ready(page);
    await page.evaluate(() => navigator.serviceWorker.ready);
    await page.waitForFunction(() => navigator.serviceWorker.controller !== null, null, { timeout: 20000 });
    await context.setOffline(true);
    await page.reload();
    await ready(page);
    const s = await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);
    check(s.clips.length === 1, `offline: ${s.clips.map((c) => c.name)} drawn (${s.framesRendered} frames)`);
    await page.screenshot({ path: shot('offline') });
    await context.setOffline(false);
  });
  check(errors.length === 0, `no page errors: ${errors.slice(0, 3).join(' | ')}`);
} finally {
  await close();
  server.close();
}
finish('autosave checks');
