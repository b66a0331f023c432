// A browser with neither WebGPU nor WebGL2 gets a plain message, not a blank page.
// node nogpu.mjs <url> <outDir> <chromium>
import path from 'node:path';
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';

const [url, outDir, chromiumPath] = process.argv.slice(2);
const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'mocap-chromium-'));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath: chromiumPath, headless: true, viewport: { width: 1280, height: 800 },
  args: ['--no-sandbox', '--disable-background-networking', '--disable-component-update', '--disable-sync',
    '--no-first-run', '--disable-quic', '--disable-3d-apis', '--disable-webgpu', '--disable-features=WebGPU'],
});
let ok = false;
try {
  const page = context.pages()[0] ?? await context.newPage();
  await page.goto(url);
  await page.waitForFunction(() => /WebGPU or WebGL2/.test(document.getElementById('status').textContent), null, { timeout: 60000 });
  await page.screenshot({ path: path.join(outDir, 'nogpu.png') });
  ok = await page.evaluate(() => !document.getElementById('status').hidden);
} catch (e) {
  console.log(`error: ${e.message.split('\n')[0]}`);
} finally {
  await context.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
console.log(`${ok ? 'ok  ' : 'FAIL'} [nogpu] browser without WebGPU and WebGL2 shows a plain message`);
process.exit(ok ? 0 : 1);
