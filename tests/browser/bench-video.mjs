// The page's video export against real time: node bench-video.mjs <url> <chromium> <clip.bvh>
// Software WebGL2 (SwiftShader), 640x360, a 30 fps video (GIF 25); each format exported
// whole through the JS API (exportVideo: offscreen frames at exact times, WebCodecs or
// gifenc), timed from the call to the bytes, side by side with the clip's duration.
import fs from 'node:fs';
import path from 'node:path';
import { launch, waitState, dropFile, waitDropped } from './common.mjs';

const [url, chromiumPath, clipPath] = process.argv.slice(2);
const { page, close } = await launch(chromiumPath, 'webgl2');
try {
  await page.goto(url);
  await page.waitForFunction(() => window.mocapReady === true, null, { timeout: 90000 });
  const name = path.basename(clipPath);
  await dropFile(page, name, fs.readFileSync(clipPath));
  await waitDropped(page, name);
  await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);
  await page.evaluate(() => window.mocapViewer.pause());
  const d = await page.evaluate(() => window.mocapViewer.videoDefaults());
  console.log(`video export in the page, software WebGL2, 640x360, ${name}: ${d.duration.toFixed(2)} s at ${d.fps.toFixed(1)} fps`);
  for (const format of ['webm', 'mp4', 'gif']) {
    const fps = format === 'gif' ? 25 : 30;
    const r = await page.evaluate(async ([format, fps]) => {
      const t0 = performance.now();
      try {
        const bytes = await window.mocapViewer.exportVideo({ format, width: 640, height: 360, fps });
        return { ms: performance.now() - t0, bytes: bytes.length };
      } catch (e) {
        return { error: String(e && e.message ? e.message : e) };
      }
    }, [format, fps]);
    if (r.error) {
      console.log(`  ${format.padEnd(4)} not exported: ${r.error}`);
      continue;
    }
    const seconds = r.ms / 1000;
    console.log(`  ${format.padEnd(4)} ${fps} fps ${seconds.toFixed(1).padStart(6)} s (${(Math.floor(d.duration * fps + 1e-6) + 1) / seconds | 0} frames/s)   real time ${d.duration.toFixed(1)} s   ${(d.duration / seconds).toFixed(2)}x real time (aim >= 1)   ${(r.bytes / 1e6).toFixed(1)} MB`);
  }
  // Onion skin and trails. Their cost is drawing (posing them takes about
  // 20 us natively): timed as the 3D view's picture drawn and read back
  // (renderVideoFrame at the view's size, 20 times a frame apart), with and
  // without them, as a share of the page's frame while playing. The page's own
  // frame interval is shown beside it but is no measure of a few milliseconds:
  // frames wait for the display's 60 Hz, so a 40 ms frame shows as 33 or 50 ms
  // and three runs of the same build gave +3%, +23% and +28%.
  const drawMs = async (draw) => page.evaluate(async (draw) => {
    const v = window.mocapViewer;
    v.pause();
    v.applyViewState(`draw=${draw}&quality=full&play=0`);
    v.selectJoint('LeftHand');
    const { viewWidth, viewHeight } = v.videoDefaults();
    const [w, h] = [Math.round(viewWidth), Math.round(viewHeight)];
    await v.renderVideoFrame(0.5, w, h, false);
    const t0 = performance.now();
    for (let k = 0; k < 20; k++) await v.renderVideoFrame(0.1 * k, w, h, false);
    return (performance.now() - t0) / 20;
  }, draw);
  const frameMs = async (draw) => page.evaluate(async (draw) => {
    const v = window.mocapViewer;
    v.applyViewState(`draw=${draw}&quality=full`);
    v.selectJoint('LeftHand');
    v.play();
    await new Promise((r) => setTimeout(r, 800));
    const f0 = v.state().framesRendered;
    const t0 = performance.now();
    await new Promise((r) => setTimeout(r, 2000));
    const frames = v.state().framesRendered - f0;
    v.pause();
    return (performance.now() - t0) / Math.max(1, frames);
  }, draw);
  // Alternated, eight rounds each, medians: this machine's speed wanders.
  const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
  const [plain, marked, paced, pacedMarked] = [[], [], [], []];
  for (let round = 0; round < 8; round++) {
    plain.push(await drawMs('joints,interp'));
    marked.push(await drawMs('joints,interp,onion,trails'));
    paced.push(await frameMs('joints,interp'));
    pacedMarked.push(await frameMs('joints,interp,onion,trails'));
  }
  const [a, b, frame, frameMarked] = [plain, marked, paced, pacedMarked].map(median);
  const share = (100 * (b - a)) / frame;
  console.log(`onion skin (3 each side) and trails, one character, software WebGL2: the 3D view drawn ${a.toFixed(1)} -> ${b.toFixed(1)} ms, ${share >= 0 ? '+' : ''}${share.toFixed(0)}% of the page's ${frame.toFixed(1)} ms frame while playing (aim < 20%); frame interval with them ${frameMarked.toFixed(1)} ms`);
} finally {
  await close();
}
