// Web performance figures: node bench.mjs <url> <distDir> <chromium> [largest.bvh]
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { launch, state, waitState, dropFile } from './common.mjs';

const [url, distDir, chromiumPath, bigFile] = process.argv.slice(2);

function walk(dir) {
  return fs.readdirSync(dir, { withFileTypes: true }).flatMap((e) => e.isDirectory() ? walk(path.join(dir, e.name)) : [path.join(dir, e.name)]);
}
let raw = 0;
let gz = 0;
for (const f of walk(distDir).filter((f) => /\.(wasm|js|html|css)$/.test(f))) {
  const b = fs.readFileSync(f);
  raw += b.length;
  gz += zlib.gzipSync(b, { level: 9 }).length;
}
console.log(`transfer size: ${(raw / 1048576).toFixed(2)} MiB raw, ${(gz / 1048576).toFixed(2)} MiB gzipped (wasm + js + html + css; target <= 2.5 MB)`);

for (const mode of ['webgl2', 'webgpu']) {
  const { page, close } = await launch(chromiumPath, mode);
  try {
    await page.goto(url);
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 3);
    const frameStats = async (label) => {
      const r = await page.evaluate(async () => {
        const v = window.mocapViewer;
        v.play();
        const f0 = v.state().framesRendered;
        const t0 = performance.now();
        await new Promise((res) => setTimeout(res, 3000));
        return { frames: v.state().framesRendered - f0, ms: performance.now() - t0 };
      });
      console.log(`[${mode}] ${label}: ${(r.ms / Math.max(1, r.frames)).toFixed(1)} ms/frame (${r.frames} frames in ${(r.ms / 1000).toFixed(1)} s, software GPU)`);
    };
    await frameStats('frame time while playing walk.bvh');
    if (bigFile) {
      const bytes = fs.readFileSync(bigFile);
      await dropFile(page, path.basename(bigFile), bytes);
      await page.waitForFunction(() => window.mocapLastLoad && window.mocapLastLoad.dropToFrameMs, null, { timeout: 60000 });
      const l = await page.evaluate(() => window.mocapLastLoad);
      const s = await state(page);
      console.log(`[${mode}] drop-to-first-frame ${path.basename(bigFile)} (${(bytes.length / 1048576).toFixed(1)} MB, ${s.clips[0].frames} frames): ${l.dropToFrameMs.toFixed(0)} ms (drop to clip ready ${l.loadMs.toFixed(0)} ms, of which parse + bounds ${l.parseMs.toFixed(0)} ms; the rest is waiting for the next software-rendered frame; target <= 400 ms)`);
      await frameStats(`frame time while playing ${path.basename(bigFile)}`);
    }
  } finally {
    await close();
  }
}
