// A lost graphics device, in one mode: WebGL2 (WEBGL_lose_context: lose, then
// restore) or WebGPU (GPUDevice.destroy(), the device caught by a hook this test
// installs in the page before it starts, not one in the product). The page shows
// the notice, starts again on a new device and draws the same clips, edits, frame
// and camera. With no device to be had (the hook refuses adapters and contexts),
// the page says so and still saves the work as BVH and glTF; "Try again" draws
// again once a device can be had.
//   node gpu-loss.mjs <url> <mode> <outDir> <chromium>
import path from 'node:path';
import { launch, state, waitState, changeAndRender, view3d, decodePng, reporter } from './common.mjs';

const [base, mode, outDir, chromiumPath] = process.argv.slice(2);
const shot = (name) => path.join(outDir, `${mode}-gpu-loss-${name}.png`);
const { check, step, finish } = reporter(`${mode} gpu loss`);

// Pixels of the 3D view unlike the background: the figure and the floor's lines.
async function drawn(context, png) {
  const { data } = await decodePng(context, png);
  let unlike = 0;
  for (let i = 0; i < data.length; i += 4) {
    const [r, g, b] = [data[i], data[i + 1], data[i + 2]];
    if (Math.abs(r - data[0]) + Math.abs(g - data[1]) + Math.abs(b - data[2]) > 40) unlike += 1;
  }
  return unlike;
}

const { context, page, close, errors } = await launch(chromiumPath, mode);
// The test's hook: every WebGPU device the page gets, so that the test can destroy one;
// and a switch that makes adapters and contexts unavailable.
await page.addInitScript(() => {
  window.__testDevices = [];
  window.__testNoDevice = false;
  if (window.GPUAdapter) {
    const requestDevice = GPUAdapter.prototype.requestDevice;
    GPUAdapter.prototype.requestDevice = async function (...args) {
      const device = await requestDevice.apply(this, args);
      window.__testDevices.push(device);
      return device;
    };
  }
  if (navigator.gpu) {
    const requestAdapter = navigator.gpu.requestAdapter.bind(navigator.gpu);
    navigator.gpu.requestAdapter = (...args) => (window.__testNoDevice ? Promise.resolve(null) : requestAdapter(...args));
  }
  const getContext = HTMLCanvasElement.prototype.getContext;
  window.__testGetContext = (canvas, ...args) => getContext.apply(canvas, args);
  HTMLCanvasElement.prototype.getContext = function (...args) {
    return window.__testNoDevice ? null : getContext.apply(this, args);
  };
});

// Loses the device the way the mode does it.
const loseDevice = () => page.evaluate((m) => {
  if (m === 'webgpu') {
    window.__testDevices.at(-1).destroy();
    return;
  }
  const gl = window.__testGetContext(document.getElementById('viewer'), 'webgl2');
  const ext = gl.getExtension('WEBGL_lose_context');
  ext.loseContext();
  setTimeout(() => ext.restoreContext(), 300);
}, mode);

try {
  let before;
  await step('an edited clip on a chosen frame and camera', async () => {
    await page.goto(base);
    await page.waitForFunction(() => window.mocapReady === true, null, { timeout: 90000 });
    await waitState(page, (s) => s.clips.length === 1 && s.framesRendered > 2);
    const error = await page.evaluate(() => window.mocapViewer.edit(0, 'trim:0:40'));
    check(error === undefined, `edit: ${error ?? 'done'}`);
    before = await changeAndRender(page, (v) => { v.pause(); v.seek(25); v.applyViewState('t=0.8333&cam=1.2,0.5,4,0,0.9,0'); });
    check(before.clips[0].frames === 41 && before.clips[0].edited, `edited: ${before.clips[0].frames} frames`);
    const png = await view3d(page, shot('before'));
    check(await drawn(context, png) > 2000, 'the view is drawn before');
  });

  await step('a lost device: the notice, then the same view drawn again', async () => {
    await loseDevice();
    await page.waitForFunction(() => window.mocapGpu && window.mocapGpu.losses === 1, null, { timeout: 10000 });
    const text = await page.evaluate(() => document.getElementById('gpu-notice').textContent);
    check(/graphics device was reset/.test(text), `the notice: ${text}`);
    await page.screenshot({ path: shot('notice') });
    await page.waitForFunction(() => window.mocapGpu.state === 'running' && window.mocapGpu.restarts === 1, null, { timeout: 30000 });
    const s = await waitState(page, (s, a) => s.framesRendered > a + 2, before.framesRendered);
    check(s.clips.length === 1 && s.clips[0].frames === 41 && s.clips[0].edited, `the edited clip is open: ${s.clips.map((c) => `${c.name} ${c.frames}`)}`);
    check(s.frame === before.frame && s.view === before.view, `same frame and camera: ${s.frame} ${s.view}`);
    check(await page.evaluate(() => document.getElementById('gpu-notice').hidden), 'the notice is gone');
    const png = await view3d(page, shot('after'));
    check(await drawn(context, png) > 2000, 'the view is drawn again');
    // Still a working viewer: it plays on and takes commands.
    const played = await changeAndRender(page, (v) => v.seek(30));
    check(played.frame === 30, `seek after the restart: frame ${played.frame}`);
  });

  await step('no device to be had: the page says so and still saves the work', async () => {
    await page.evaluate(() => { window.__testNoDevice = true; });
    await loseDevice();
    await page.waitForFunction(() => window.mocapGpu.state === 'failed', null, { timeout: 30000 });
    const text = await page.evaluate(() => document.getElementById('gpu-notice').textContent);
    check(/none can be had/.test(text), `the notice: ${text}`);
    await page.screenshot({ path: shot('failed') });
    await page.click('#gpu-notice button:text("Save as BVH")');
    const bvh = await page.evaluate(() => window.mocapLastSave);
    check(bvh && bvh.name.endsWith('.bvh') && bvh.bytes > 1000, `Save as BVH: ${JSON.stringify(bvh)}`);
    await page.click('#gpu-notice button:text("Save as glTF")');
    const glb = await page.evaluate(() => window.mocapLastSave);
    check(glb && glb.name.endsWith('.glb') && glb.bytes > 1000, `Save as glTF: ${JSON.stringify(glb)}`);
    const s = await state(page);
    check(s.clips[0].frames === 41 && s.clips[0].edited, 'the edited clip is still open');
    await page.evaluate(() => { window.__testNoDevice = false; });
    const rendered = s.framesRendered;
    await page.click('#gpu-notice button:text("Try again")');
    await page.waitForFunction(() => window.mocapGpu.state === 'running', null, { timeout: 30000 });
    const again = await waitState(page, (s, a) => s.framesRendered > a + 2, rendered);
    check(again.frame === 30 && again.clips[0].frames === 41, `drawn again after Try again: frame ${again.frame}`);
    const png = await view3d(page, shot('again'));
    check(await drawn(context, png) > 2000, 'the view is drawn after Try again');
  });
  const unexpected = errors.filter((e) => !/graphics|context|WebGL|GPU|device/i.test(e));
  check(unexpected.length === 0, `no other page errors: ${unexpected.slice(0, 3).join(' | ')}`);
} finally {
  await close();
}
finish('gpu-loss checks');
