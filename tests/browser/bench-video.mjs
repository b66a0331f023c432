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
  // Onion skin and trails: the frame time while playing, with and without them.
  const frameMs = async (draw) => page.evaluate(async (draw) => {
    const v = window.mocapViewer;
    v.applyViewState(`draw=${draw}&quality=full`);
    v.selectJoint('LeftHand');
    v.play();
    await new Promise((r) => setTimeout(r, 800));
    const f0 = v.state().framesRendered;
    const t0 = performance.now();
    await new Promise((r) => setTimeout(r, 3000));
    const frames = v.state().framesRendered - f0;
    v.pause();
    return (performance.now() - t0) / Math.max(1, frames);
  }, draw);
  // Alternated, four rounds each, medians: this machine's speed wanders.
  const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
  const plains = [];
  const markeds = [];
  for (let round = 0; round < 4; round++) {
    plains.push(await frameMs('joints,interp'));
    markeds.push(await frameMs('joints,interp,onion,trails'));
  }
  const [plain, marked] = [median(plains), median(markeds)];
  console.log(`onion skin (3 each side) and trails, one character, software WebGL2, playing: ${plain.toFixed(1)} ms -> ${marked.toFixed(1)} ms a frame (+${(100 * (marked / plain - 1)).toFixed(0)}%, aim < 20%)`);
} finally {
  await close();
}
