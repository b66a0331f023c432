// Video export from the page, in one mode: a dropped clip exported as WebM (the
// JS API's exportVideo) and as GIF (Edit ▸ Export video…'s dialog, with its
// progress bar; screenshots of both looked at). FFmpeg decodes each: the frame
// count and duration the range asks for, frames that move, and frame k within
// 26 dB PSNR of the page's own picture at k/fps (renderVideoFrame). MP4 where
// this browser's WebCodecs encodes H.264 (headless Chromium usually does not:
// then the dialog says why and offers the others).
//   node video.mjs <url> <mode> <outDir> <chromium> <walk.bvh>
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { launch, waitState, dropFile, waitDropped, reporter, slowClick } from './common.mjs';

const [base, mode, outDir, chromiumPath, clipPath] = process.argv.slice(2);
const shot = (name) => path.join(outDir, `${mode}-video-${name}.png`);
const { check, step, finish } = reporter(`${mode} video export`);
const W = 320;
const H = 180;

function probe(file) {
  const text = execFileSync('ffprobe', ['-v', 'error', '-count_frames', '-select_streams', 'v:0',
    '-show_entries', 'stream=nb_read_frames,width,height:format=duration', '-of', 'default=nw=1', file]).toString();
  const field = (n) => (text.split('\n').find((l) => l.startsWith(`${n}=`)) || '').slice(n.length + 1);
  return { frames: Number(field('nb_read_frames')), duration: Number(field('duration')), width: Number(field('width')), height: Number(field('height')) };
}

function decode(file, w, h) {
  const raw = execFileSync('ffmpeg', ['-v', 'error', '-i', file, '-f', 'rawvideo', '-pix_fmt', 'rgba', '-fps_mode', 'passthrough', '-'], { maxBuffer: 1 << 30 });
  const size = w * h * 4;
  const frames = [];
  for (let i = 0; i + size <= raw.length; i += size) frames.push(raw.subarray(i, i + size));
  return frames;
}

function psnr(a, b) {
  let sum = 0;
  let n = 0;
  for (let i = 0; i < a.length; i += 4) {
    for (let c = 0; c < 3; c++) {
      const d = a[i + c] - b[i + c];
      sum += d * d;
      n += 1;
    }
  }
  return 10 * Math.log10((255 * 255) / Math.max(sum / n, 1e-9));
}

const pageFrame = (page, t) => page.evaluate(async ([t, w, h]) => Array.from(await window.mocapViewer.renderVideoFrame(t, w, h, false)), [t, W, H]);

// Checks a written video against the range it was asked for and the page's own frames.
async function checkVideo(page, label, file, fps, from, to) {
  const expected = Math.floor((to - from) * fps + 1e-6) + 1;
  const p = probe(file);
  check(p.frames === expected, `${label}: ${p.frames} frames (expected ${expected})`);
  check(Math.abs(p.duration - expected / fps) < 0.011, `${label}: ${p.duration} s (expected ${(expected / fps).toFixed(3)})`);
  check(p.width === W && p.height === H, `${label}: ${p.width}x${p.height}`);
  const frames = decode(file, W, H);
  check(frames.length === expected, `${label}: ${frames.length} frames decoded`);
  check(psnr(frames[0], frames[Math.floor(expected / 2)]) < 30, `${label}: the figure moves`);
  for (const k of [0, Math.floor(expected / 3), expected - 1]) {
    const reference = await pageFrame(page, from + k / fps);
    const db = psnr(frames[k], reference);
    check(db >= 26, `${label}: frame ${k} is ${db.toFixed(1)} dB from the page's picture at ${(from + k / fps).toFixed(3)} s`);
  }
}

const { page, close, errors } = await launch(chromiumPath, mode);
try {
  await page.goto(base);
  await page.waitForFunction(() => window.mocapReady === true, null, { timeout: 90000 });
  await dropFile(page, 'walk.bvh', fs.readFileSync(clipPath));
  await waitDropped(page, 'walk.bvh');
  await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);
  await page.evaluate(() => window.mocapViewer.pause());

  await step('WebM through the JS API', async () => {
    const formats = await page.evaluate(async () => (await import('./web/video-export.js')).videoFormats(320, 180));
    console.log(`  formats: ${formats.map((f) => `${f.format}=${f.codec || f.reason}`).join(', ')}`);
    const bytes = await page.evaluate(async ([w, h]) => {
      const out = await window.mocapViewer.exportVideo({ format: 'webm', width: w, height: h, fps: 30, from: 0.5, to: 1.5 });
      return Array.from(out);
    }, [W, H]);
    const file = path.join(outDir, `${mode}-walk.webm`);
    fs.writeFileSync(file, Buffer.from(bytes));
    await checkVideo(page, 'WebM', file, 30, 0.5, 1.5);
  });

  await step('MP4 where WebCodecs encodes H.264', async () => {
    const formats = await page.evaluate(async () => (await import('./web/video-export.js')).videoFormats(320, 180));
    const mp4 = formats.find((f) => f.format === 'mp4');
    if (!mp4.codec) {
      console.log(`  MP4 not offered here: ${mp4.reason}`);
      check(typeof mp4.reason === 'string' && mp4.reason.length > 0, 'the reason MP4 is missing is given');
      return;
    }
    const bytes = await page.evaluate(async ([w, h]) => Array.from(await window.mocapViewer.exportVideo({ format: 'mp4', width: w, height: h, fps: 30, from: 0, to: 1 })), [W, H]);
    const file = path.join(outDir, `${mode}-walk.mp4`);
    fs.writeFileSync(file, Buffer.from(bytes));
    await checkVideo(page, 'MP4', file, 30, 0, 1);
  });

  await step('GIF through Edit ▸ Export video…, with its progress bar', async () => {
    // Edit ▸ Export video… by the page's own menu (the 1280x800 layout's toolbar).
    await slowClick(page, 950, 12);
    await page.waitForTimeout(500);
    await page.screenshot({ path: shot('menu') });
    await slowClick(page, 963, 470);
    await page.waitForSelector('#video-export[open]', { timeout: 15000 });
    await page.screenshot({ path: shot('dialog') });
    await page.selectOption('#video-export select[name=format]', 'gif');
    await page.selectOption('#video-export select[name=size]', 'custom');
    await page.fill('#video-export input[name=width]', String(W));
    await page.fill('#video-export input[name=height]', String(H));
    await page.fill('#video-export input[name=fps]', '25');
    const download = page.waitForEvent('download', { timeout: 120000 });
    await page.click('#video-export button[value=export]');
    await page.waitForSelector('#video-export progress:not([hidden])');
    await page.screenshot({ path: shot('progress') });
    const file = path.join(outDir, `${mode}-walk.gif`);
    await (await download).saveAs(file);
    check((await download).suggestedFilename() === 'walk.gif', `downloaded as ${(await download).suggestedFilename()}`);
    const status = await page.textContent('#video-export .video-status');
    check(/Saved walk\.gif/.test(status), `the dialog says: ${status}`);
    const duration = await page.evaluate(() => window.mocapViewer.videoDefaults().duration);
    await checkVideo(page, 'GIF', file, 25, 0, duration);
    await page.click('#video-export button[value=cancel]');
    check(await page.evaluate(() => !document.getElementById('video-export').open), 'Cancel closes the dialog');
  });

  await step('Cancel stops an export', async () => {
    const result = await page.evaluate(async () => {
      const controller = new AbortController();
      const run = window.mocapViewer.exportVideo({ format: 'gif', width: 160, height: 90, fps: 10 }, {
        signal: controller.signal,
        onProgress: (done) => { if (done === 2) controller.abort(); },
      });
      try {
        await run;
        return 'finished';
      } catch (e) {
        return e.name;
      }
    });
    check(result === 'AbortError', `an aborted export rejects with ${result}`);
  });

  check(errors.length === 0, `no page errors${errors.length ? ': ' + errors.join(' | ') : ''}`);
} finally {
  await close();
}
finish('video export checks');
