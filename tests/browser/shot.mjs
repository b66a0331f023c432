// Takes a screenshot of the page in one GPU mode: node shot.mjs URL MODE OUT.png CHROMIUM [fragment]
import { launch, waitState, waitFrames } from './common.mjs';

const [url, mode, out, chromium] = process.argv.slice(2);
const { page, close, errors } = await launch(chromium, mode);
try {
  await page.goto(url);
  await waitState(page, (s) => s.clips.length > 0 && s.framesRendered > 2);
  await waitFrames(page, 3);
  await page.screenshot({ path: out });
  const s = await page.evaluate(() => window.mocapViewer.state());
  console.log(mode, 'backend', s.backend, 'frame', s.frame, 'errors', JSON.stringify(errors));
} finally {
  await close();
}
