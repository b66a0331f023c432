// The bendy-tentacle demo in the browser: ?demo=tentacle opens it, dragging the
// red target sphere with the mouse moves it under the pointer and the tip follows
// it; the rigid skin and the CCD solver can be chosen from JavaScript.
// Usage: node demo.mjs URL MODE OUT_DIR CHROMIUM
import path from 'node:path';
import { changeAndRender, launch, reporter, waitState } from './common.mjs';

const [base, mode, outDir, chromiumPath] = process.argv.slice(2);
const { check, step, finish } = reporter(`demo ${mode}`);
const shot = (name) => path.join(outDir, `demo-${mode}-${name}.png`);
const near = (a, b, tol) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) < tol;

const { page, close, errors } = await launch(chromiumPath, mode);
try {
  await step('?demo=tentacle opens the demo', async () => {
    await page.goto(`${base}?demo=tentacle`);
    const s = await waitState(page, (s) => s.demo !== null && s.clips.length === 1 && s.framesRendered > 2);
    check(s.clips[0].name === 'tentacle' && s.demo.bones === 2 && s.drawMode === 'body', `a two-bone tentacle in body mode (${s.clips[0].name}, ${s.demo.bones}, ${s.drawMode})`);
    check(s.demo.follow && near(s.demo.tip, s.demo.target, 1e-3), `the tip is on the target (${s.demo.tip} vs ${s.demo.target})`);
    await page.screenshot({ path: shot('open') });
  });

  await step('dragging the red sphere moves it under the pointer; the tip follows', async () => {
    const start = await page.evaluate(() => window.mocapViewer.demoTargetScreenPosition());
    check(start && start.length === 2, `the sphere is on screen at ${start}`);
    const [x, y] = start;
    const end = [x - 70, y + 30];
    await page.mouse.move(x, y);
    await page.mouse.down();
    for (let k = 1; k <= 8; k++) {
      await page.mouse.move(x + (end[0] - x) * k / 8, y + (end[1] - y) * k / 8);
      await page.waitForTimeout(60);
    }
    await page.mouse.up();
    const s = await changeAndRender(page, (v) => v.pause());
    const now = await page.evaluate(() => window.mocapViewer.demoTargetScreenPosition());
    const d = Math.hypot(now[0] - end[0], now[1] - end[1]);
    check(d < 4, `the sphere is under the pointer (${now} vs ${end}, ${d.toFixed(1)} px)`);
    check(near(s.demo.tip, s.demo.target, 1e-3), `the tip follows (${s.demo.tip} vs ${s.demo.target})`);
    await page.screenshot({ path: shot('dragged') });
  });

  await step('rigid skin and CCD from JavaScript', async () => {
    const ok = await page.evaluate(() => window.mocapViewer.setDemo([0.5, 0.5, 0.2], true, 'ccd', false));
    const s = await waitState(page, (s) => s.demo.solver === 'ccd' && s.demo.soft === false);
    await changeAndRender(page, (v) => v.pause());
    const s2 = await waitState(page, (s) => Math.hypot(s.demo.tip[0] - 0.5, s.demo.tip[1] - 0.5, s.demo.tip[2] - 0.2) < 1e-2);
    check(ok && s.demo.soft === false && s2.demo.solver === 'ccd', 'setDemo changes solver, skin and target');
    check(!(await page.evaluate(() => window.mocapViewer.setDemo(null, null, 'magic', null))), 'an unknown solver is refused');
    await page.screenshot({ path: shot('rigid') });
  });
  check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
} finally {
  await close();
}
finish('demo');
