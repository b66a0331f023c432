// The wasm package's JavaScript API: parseMotion in Node on the built package, its
// TypeScript types, and the Canvas 2D example page in Chromium.
// node api.mjs <url> <distDir> <outDir> <chromium>
import fs from 'node:fs';
import path from 'node:path';
import { dropFiles, launch, reporter, waitDropped } from './common.mjs';

const [base, dist, outDir, chromiumPath] = process.argv.slice(2);
const { check, step, finish } = reporter('api');

const walk = fs.readFileSync(new URL('../../data/walk.bvh', import.meta.url));

await step('parseMotion in Node on the built package', async () => {
  const pkg = await import(path.join(dist, 'pkg/mocap_web.js'));
  await pkg.default({ module_or_path: fs.readFileSync(path.join(dist, 'pkg/mocap_web_bg.wasm')) });
  const clip = pkg.parseMotion(walk, 'walk.bvh');
  check(clip.frameCount === 67 && Math.abs(clip.frameTime - 1 / 30) < 1e-6, `67 frames at 30 fps (${clip.frameCount}, ${clip.frameTime})`);
  const names = clip.jointNames;
  const parents = clip.parents;
  check(names[0] === 'Hips' && parents.length === names.length && parents[0] === -1 && parents instanceof Int32Array,
    `${names.length} joints, root ${names[0]}, parents an Int32Array`);
  // A figure standing along +Z (hips at 1, spine up, an arm along X, a leg down to 0).
  const zUp = 'HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 1\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n'
    + 'JOINT Chest\n{\nOFFSET 0 0 0.5\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT L\n{\nOFFSET 0.6 0 0.3\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 0 0.4\n}\n}\n}\n'
    + 'JOINT Leg\n{\nOFFSET 0.1 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 0 -1\n}\n}\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n'
    + `0 0 1${' 0'.repeat(12)}\n0 0.1 1${' 0'.repeat(12)}\n`;
  const standing = pkg.parseMotion(new TextEncoder().encode(zUp), 'z.bvh');
  check(clip.upAxis === 'y' && standing.upAxis === 'z', `upAxis: walk.bvh ${clip.upAxis}, a Z-up figure ${standing.upAxis}`);
  const p = clip.worldPositions(10);
  check(p instanceof Float32Array && p.length === 3 * names.length && p.every(Number.isFinite), `worldPositions(10): ${p.length} finite floats`);
  const indices = clip.bodyIndices();
  const body = clip.bodyVertices(10);
  check(indices instanceof Uint32Array && indices.length > 0 && indices.length % 3 === 0, `bodyIndices(): ${indices.length / 3} triangles`);
  check(body instanceof Float32Array && body.length % 3 === 0 && body.every(Number.isFinite) && indices.every((i) => i < body.length / 3), `bodyVertices(10): ${body.length / 3} finite vertices`);
  const moved = clip.bodyVertices(40);
  check(moved.some((v, i) => Math.abs(v - body[i]) > 1e-3), 'the body moves with the motion');
  const again = pkg.parseMotion(new TextEncoder().encode(clip.toBvh()), 'again.bvh');
  check(again.frameCount === 67 && again.worldPositions(10).every((v, i) => v === p[i]), 'toBvh() parses back to the same positions');
  let message = null;
  try {
    pkg.parseMotion(new TextEncoder().encode('HIERARCHY\nROOT a\n{\n'), 'bad.bvh');
  } catch (e) {
    message = e.message;
  }
  check(/^bad\.bvh:\d+:\d+/.test(message ?? ''), `a bad file throws with its position: ${message}`);
  // Other formats: the core decides from the content (the name says .txt).
  const bva = pkg.parseMotion(fs.readFileSync(new URL('../../data/walk.bva', import.meta.url)), 'walk.txt');
  check(bva.frameCount === 67 && bva.jointNames.includes('Hips_End'), `a BVA opens as segments (${bva.frameCount} frames)`);
  const asf = new TextEncoder().encode(':version 1.10\n:name T\n:units\n  length 1\n  angle deg\n:root\n  order TX TY TZ RX RY RZ\n  axis XYZ\n  position 0 0 0\n  orientation 0 0 0\n:bonedata\n  begin\n    id 1\n    name b\n    direction 1 0 0\n    length 2\n    axis 0 0 0 XYZ\n    dof rz\n  end\n:hierarchy\n  begin\n    root b\n  end\n');
  const amc = new TextEncoder().encode(':FULLY-SPECIFIED\n:DEGREES\n1\nroot 0 0 0 0 0 0\nb 90\n');
  const take = pkg.parseMotion(amc, 'take.amc', asf);
  const tip = take.worldPositions(0).slice(6, 9);
  check(take.frameCount === 1 && Math.abs(tip[0]) < 1e-5 && Math.abs(tip[1] - 2) < 1e-5, `an AMC with its skeleton: rz 90 turns the +X bone up (${Array.from(tip)})`);
  let missing = null;
  try {
    pkg.parseMotion(amc, 'take.amc');
  } catch (e) {
    missing = e.message;
  }
  check(/take\.amc: .*needs its skeleton/.test(missing ?? ''), `an AMC without its skeleton says so: ${missing}`);
  clip.free();
  again.free();
  bva.free();
  take.free();

  // A Quake 2 MD2 model built here: 3 vertices, 1 triangle, 2 frames (run1, run2).
  const md2 = (() => {
    const frameSize = 40 + 4 * 3;
    const ofsSt = 68, ofsTris = ofsSt + 3 * 4, ofsFrames = ofsTris + 12, ofsEnd = ofsFrames + 2 * frameSize;
    const b = new DataView(new ArrayBuffer(ofsEnd));
    [0x49, 0x44, 0x50, 0x32].forEach((c, i) => b.setUint8(i, c));
    const header = [8, 64, 64, frameSize, 0, 3, 3, 1, 0, 2, 68, ofsSt, ofsTris, ofsFrames, ofsEnd, ofsEnd];
    header.forEach((v, i) => b.setInt32(4 + 4 * i, v, true));
    [0, 0, 63, 0, 0, 63].forEach((v, i) => b.setInt16(ofsSt + 2 * i, v, true));
    [0, 1, 2, 0, 1, 2].forEach((v, i) => b.setUint16(ofsTris + 2 * i, v, true));
    for (let f = 0; f < 2; f++) {
      const at = ofsFrames + f * frameSize;
      [1, 1, 1, 0, 0, f * 10].forEach((v, i) => b.setFloat32(at + 4 * i, v, true));
      [...`run${f + 1}`].forEach((c, i) => b.setUint8(at + 24 + i, c.charCodeAt(0)));
      [[0, 0, 0], [10, 0, 0], [0, 0, 20]].forEach((p, v) => p.concat([0]).forEach((x, k) => b.setUint8(at + 40 + 4 * v + k, x)));
    }
    return new Uint8Array(b.buffer);
  })();
  const model = pkg.parseModel(md2, 'tiny.md2');
  check(model.vertexCount === 3 && model.frameCount === 2 && model.triangleCount === 1, `parseModel: counts (${model.vertexCount}, ${model.frameCount}, ${model.triangleCount})`);
  check(model.animationNames.join() === 'run' && model.animationFirst[0] === 0 && model.animationLast[0] === 1, `parseModel: one animation run 0–1 (${model.animationNames})`);
  const half = model.positions(0, 0.5);
  // Quake z → Y up: vertex 2 is at z = 20 (+ translate 0 then 10): Y = 20, then 25 halfway.
  check(half instanceof Float32Array && half.length === 9 && Math.abs(half[7] - 25) < 1e-5 && Math.abs(half[1] - 5) < 1e-5, `positions(0, 0.5) interpolates (${Array.from(half)})`);
  let broken = null;
  try {
    pkg.parseModel(md2.slice(0, 40), 'cut.md2');
  } catch (e) {
    broken = e.message;
  }
  check(/^cut\.md2:byte \d+: /.test(broken ?? ''), `a truncated model throws with its byte: ${broken}`);
  model.free();
});

await step('TypeScript types', async () => {
  const dts = fs.readFileSync(path.join(dist, 'pkg/mocap_web.d.ts'), 'utf8');
  for (const needle of ['export function parseMotion(bytes: Uint8Array | number[], file_name: string, skeleton?: Uint8Array | number[] | null): MotionClip',
    'openFiles(names: string[], contents: Uint8Array[], add: boolean): string[]',
    'openFileSet(set: FileSet, add: boolean): string[]', 'export class FileSet', 'push(chunk: Uint8Array): void',
    'export function parseModel(bytes: Uint8Array | number[], file_name: string): ModelMesh', 'positions(frame: number, t: number): Float32Array', 'jointPosition(character: number, name: string): Float32Array | undefined',
    'export function startViewer(canvas: HTMLCanvasElement, options?: ViewerOptions): Promise<MocapViewer>',
    'addClip(clip: MotionClip, file_name: string): void', 'loadClip(clip: MotionClip, file_name: string): void',
    'add(file_name: string, bytes: Uint8Array | number[]): string | undefined', 'setVisible(index: number, visible: boolean): boolean',
    'remove(index: number): boolean', "setLayout(layout: 'spread' | 'overlay'): boolean", 'setUpAxis(index: number, up: string): boolean',
    'worldPositions(frame: number): Float32Array', 'toBvh(): string', 'export interface ViewerOptions',
    'readonly jointNames: string[]', 'readonly parents: Int32Array', 'readonly upAxis: string']) {
    check(dts.includes(needle), `mocap_web.d.ts has ${needle}`);
  }
});

const { page, close, errors } = await launch(chromiumPath, 'webgl2');
try {
  await step('the Canvas 2D example page draws the skeleton', async () => {
    await page.goto(`${base}web/examples/skeleton-2d.html`);
    await page.waitForFunction(() => window.skeletonExample && window.skeletonExample.ready && window.skeletonExample.frame > 3, null, { timeout: 60000 });
    const s = await page.evaluate(() => window.skeletonExample);
    check(s.name === 'walk.bvh' && s.frames === 67 && s.error === null, `example opened walk.bvh (${s.joints} joints, ${s.frames} frames)`);
    const lit = await page.evaluate(() => {
      const c = document.getElementById('view');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] > 200 && d[i + 1] > 200) n += 1;
      return n;
    });
    check(lit > 200, `the canvas has skeleton pixels (${lit})`);
    await page.screenshot({ path: path.join(outDir, 'api-example.png') });
    check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
  });

  await step('startViewer on a canvas of another page, driven by the handle', async () => {
    await page.goto(`${base}web/examples/start-viewer.html`);
    await page.waitForFunction(() => window.exampleViewer && window.exampleViewer.state().framesRendered > 3, null, { timeout: 60000 });
    const s = await page.evaluate(() => window.exampleViewer.state());
    check(s.clips.length === 1 && s.clips[0].frames === 67 && s.embed && s.playing, `loadClip opened walk.bvh, embed layout, playing (${s.clips.length} clips)`);
    await page.click('#pause');
    await page.evaluate(() => window.exampleViewer.seek(30));
    const paused = await page.evaluate(() => window.exampleViewer.state());
    check(!paused.playing && paused.frame === 30, `pause and seek(30): frame ${paused.frame}, playing ${paused.playing}`);
    await page.click('#play');
    check(await page.evaluate(() => window.exampleViewer.state().playing), 'play resumes');
    const added = await page.evaluate(async () => {
      const { parseMotion } = await import('../../pkg/mocap_web.js');
      const bytes = new Uint8Array(await (await fetch('../../data/walk.bvh')).arrayBuffer());
      const clip = parseMotion(bytes, 'second.bvh');
      const v = window.exampleViewer;
      v.addClip(clip, 'second.bvh');
      const two = v.state().clips.map((c) => c.name);
      v.loadClip(clip, 'only.bvh');
      clip.free();
      return { two, one: v.state().clips.map((c) => c.name) };
    });
    check(added.two.join() === 'walk.bvh,second.bvh' && added.one.join() === 'only.bvh',
      `addClip adds (${added.two.join(', ')}), loadClip replaces (${added.one.join(', ')})`);
    // A FileSet filled chunk by chunk (as the page reads a drop) opens like openFiles:
    // an ASF skeleton and its AMC motion, each in uneven pieces, paired up.
    const set = await page.evaluate(async () => {
      const { FileSet } = await import('../../pkg/mocap_web.js');
      const get = async (p) => new Uint8Array(await (await fetch(p)).arrayBuffer());
      const [asf, amc] = [await get('../../corpus/asf_amc/cmu/01.asf'), await get('../../corpus/asf_amc/cmu/01_06.amc')];
      const v = window.exampleViewer;
      const files = new FileSet();
      for (const [name, bytes] of [['01.asf', asf], ['01_06.amc', amc]]) {
        files.begin(name, bytes.length);
        for (let at = 0; at < bytes.length; at += 7777) files.push(bytes.subarray(at, at + 7777));
      }
      const size = files.size;
      const errs = v.openFileSet(files, false);
      const emptied = files.size;
      // A BVH file alone is read as it arrives (its rows parsed between pushes).
      const walkBytes = await get('../../data/walk.bvh');
      const walkSet = new FileSet();
      walkSet.begin('chunked.bvh', walkBytes.length);
      for (let at = 0; at < walkBytes.length; at += 1000) walkSet.push(walkBytes.subarray(at, at + 1000));
      const walkErrs = v.openFileSet(walkSet, true);
      walkSet.free();
      const walkClip = v.state().clips.find((c) => c.name === 'chunked.bvh');
      v.remove(v.state().clips.length - 1);
      const broken = new FileSet();
      broken.begin('cut.bvh', 15);
      broken.push(new TextEncoder().encode('HIERARCHY\nJOINT'));
      const brokenErrs = v.openFileSet(broken, true);
      files.free();
      broken.free();
      const s = v.state();
      return { size, total: asf.length + amc.length, errs, emptied, brokenErrs, walkErrs, walkFrames: walkClip ? walkClip.frames : null, clips: s.clips.map((c) => `${c.name}:${c.frames}`) };
    });
    check(set.size === set.total && set.errs.length === 0 && set.emptied === 0 && set.clips.length === 1 && set.clips[0].startsWith('01_06.amc:'),
      `a FileSet read in chunks opens the pair (${set.size} of ${set.total} bytes, ${set.clips.join(', ')}, errors ${JSON.stringify(set.errs)})`);
    check(set.walkErrs.length === 0 && set.walkFrames === 67, `a BVH file pushed in 1000-byte pieces opens (${set.walkFrames} frames, errors ${JSON.stringify(set.walkErrs)})`);
    check(set.brokenErrs.length === 1 && set.brokenErrs[0].startsWith('cut.bvh') && set.clips.length === 1,
      `a broken file in a FileSet is reported and changes nothing (${set.brokenErrs[0]})`);
    await page.waitForTimeout(500);
    await page.screenshot({ path: path.join(outDir, 'api-start-viewer.png') });
    check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
  });
  await step('the up axis: guessed, set by the handle, kept in the fragment', async () => {
    await page.goto(base);
    await page.waitForFunction(() => window.mocapViewer && window.mocapViewer.state().clips.length === 1, null, { timeout: 60000 });
    const r = await page.evaluate(() => {
      const v = window.mocapViewer;
      v.pause();
      const guessed = v.state().clips[0].up;
      const set = v.setUpAxis(0, 'z');
      const after = v.state();
      const refused = [v.setUpAxis(0, 'q'), v.setUpAxis(5, 'y')];
      v.applyViewState('up=y');
      return { guessed, set, up: after.clips[0].up, view: after.view, refused, back: v.state().clips[0].up };
    });
    check(r.guessed === 'y' && r.set && r.up === 'z' && r.view.includes('up=z'), `walk.bvh is Y-up; setUpAxis(0, 'z') stands it along Z (${r.guessed}, ${r.up}, ${r.view})`);
    check(!r.refused[0] && !r.refused[1], 'an unknown axis or character is refused');
    check(r.back === 'y', `the fragment sets it back (${r.back})`);
  });

  await step('edits on the page: undo, and Save as BVH downloads the edited clip', async () => {
    await page.goto(base);
    await page.waitForFunction(() => window.mocapViewer && window.mocapViewer.state().clips.length === 1, null, { timeout: 60000 });
    const r = await page.evaluate(() => {
      const v = window.mocapViewer;
      v.pause();
      const errors = [v.edit(0, 'reverse'), v.edit(0, 'trim:0:9'), v.edit(0, 'trim:9:2') ?? null];
      const s = v.state();
      return { errors, edited: s.clips[0].edited, frames: s.clips[0].frames, undo: s.undo };
    });
    check(r.errors[0] === undefined && r.errors[1] === undefined && typeof r.errors[2] === 'string', `edits apply, a bad one says why (${r.errors[2]})`);
    check(r.edited && r.frames === 10 && r.undo === 'trim:0:9', `edited: ${r.frames} frames, undo "${r.undo}"`);
    const download = page.waitForEvent('download', { timeout: 30000 });
    await page.evaluate(() => window.dispatchEvent(new Event('mocap-save')));
    const file = await download;
    check(file.suggestedFilename() === 'walk-edited.bvh', `the file is ${file.suggestedFilename()}`);
    const saved = fs.readFileSync(await file.path());
    const pkg = await import(path.join(dist, 'pkg/mocap_web.js'));
    const a = pkg.parseMotion(saved, 'walk-edited.bvh');
    const b = pkg.parseMotion(walk, 'walk.bvh');
    const first = a.worldPositions(0);
    const last = b.worldPositions(66);
    check(a.frameCount === 10 && first.every((x, i) => Math.abs(x - last[i]) < 1e-3), 'the saved clip is the edited one (its first frame is the original last)');
    const u = await page.evaluate(() => { const v = window.mocapViewer; v.undo(); v.undo(); return v.state(); });
    check(!u.clips[0].edited && u.clips[0].frames === 67 && u.redo === 'reverse', `undo twice restores (${u.clips[0].frames} frames, redo "${u.redo}")`);
    // Drag a hand at frame 12 (metres, as drawn), key it, save: the saved file has the hand there.
    const keyed = await page.evaluate(async () => {
      const v = window.mocapViewer;
      v.seek(12);
      v.applyViewState('draw=joints,interp,pose');
      const f0 = v.state().framesRendered;
      for (let i = 0; i < 300 && v.state().framesRendered <= f0; i++) await new Promise((r) => setTimeout(r, 20));
      const p = v.jointWorldPosition(0, 'LeftHand');
      const reached = v.dragJoint(0, 'LeftHand', p[0] + 0.08, p[1] + 0.12, p[2] - 0.05);
      const error = v.setKey(2) ?? null;
      const [name, text] = v.saveBvh(0);
      return { reached, error, name, text, state: v.state() };
    });
    check(keyed.reached && keyed.error === null && keyed.state.undo === 'Key at frame 12', `dragged and keyed (${keyed.error}, undo "${keyed.state.undo}")`);
    const savedKey = pkg.parseMotion(new TextEncoder().encode(keyed.text), keyed.name);
    const hand = savedKey.jointNames.indexOf('LeftHand');
    const moved = savedKey.worldPositions(12).slice(3 * hand, 3 * hand + 3);
    const orig = b.worldPositions(12).slice(3 * hand, 3 * hand + 3);
    const delta = [moved[0] - orig[0], moved[1] - orig[1], moved[2] - orig[2]];
    check(Math.hypot(delta[0] - 8, delta[1] - 12, delta[2] + 5) < 0.3, `the saved BVH has the hand 8, 12, -5 cm away at frame 12 (${delta.map((d) => d.toFixed(2))})`);
  });
  await step('compare(i, j): an edited copy against the original', async () => {
    await page.goto(base);
    await page.waitForFunction(() => window.mocapViewer && window.mocapViewer.state().clips.length === 1, null, { timeout: 60000 });
    const r = await page.evaluate(async (text) => {
      const v = window.mocapViewer;
      v.add('walk-2.bvh', new TextEncoder().encode(text));
      const same = v.compare(0, 1);
      const error = v.edit(1, 'reverse') ?? null;
      const reversed = v.compare(0, 1, 'procrustes');
      let refused = null;
      try { v.compare(0, 1, 'sideways'); } catch (e) { refused = String(e.message || e); }
      return {
        same: same.mpjpe, frames: same.frames.length, kind: Object.prototype.toString.call(same.frames),
        error, reversed: reversed.mpjpe, joints: reversed.joints.length, worst: reversed.worstFrame, refused,
      };
    }, walk.toString());
    check(r.same === 0 && r.frames === 67 && r.kind === '[object Float32Array]', `against itself: ${r.same} over ${r.frames} frames (${r.kind})`);
    check(r.error === null && r.reversed > 1 && r.joints === 21 && r.worst >= 0, `the reversed copy: MPJPE ${r.reversed.toFixed(2)} cm over ${r.joints} joints, worst frame ${r.worst}`);
    check(typeof r.refused === 'string' && r.refused.includes('procrustes'), `a bad alignment is refused (${r.refused})`);
  });

  await step('setInterpolation: nearest, linear, cubic in the state, the fragment and the picture', async () => {
    const r = await page.evaluate(async () => {
      const v = window.mocapViewer;
      v.pause();
      const seen = {};
      // A time 0.4 of the way between two frames: each choice poses it differently.
      const time = 10.4 / 30;
      for (const name of ['nearest', 'linear', 'cubic']) {
        const error = v.setInterpolation(name) ?? null;
        await new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done)));
        const pixels = await v.renderVideoFrame(time, 320, 180, true);
        seen[name] = { error, state: v.state().interpolation, view: v.viewState(), pixels: Array.from(pixels) };
      }
      const refused = v.setInterpolation('smooth') ?? null;
      const after = v.state().interpolation;
      v.applyViewState('draw=joints,interp');
      const fromLink = v.state().interpolation;
      return { seen, refused, after, fromLink };
    });
    const differ = (a, b) => a.pixels.reduce((n, x, i) => n + (x !== b.pixels[i] ? 1 : 0), 0);
    for (const name of ['nearest', 'linear', 'cubic']) {
      const s = r.seen[name];
      const draw = s.view.split('&').find((p) => p.startsWith('draw=')) ?? '';
      const flags = draw.slice(5).split(',');
      const expected = { nearest: [false, false], linear: [true, false], cubic: [true, true] }[name];
      check(s.error === null && s.state === name && flags.includes('interp') === expected[0] && flags.includes('cubic') === expected[1], `setInterpolation('${name}'): state ${s.state}, ${draw}`);
    }
    const [nl, lc] = [differ(r.seen.nearest, r.seen.linear), differ(r.seen.linear, r.seen.cubic)];
    check(nl > 0 && lc > 0, `the picture between frames differs: nearest/linear ${nl}, linear/cubic ${lc} values`);
    check(typeof r.refused === 'string' && r.refused.includes('cubic') && r.after === 'cubic', `an unknown name is refused and changes nothing (${r.refused}; ${r.after})`);
    check(r.fromLink === 'linear', `a link with draw=…,interp opens linear (${r.fromLink})`);
  });

  await step('the creator: three joints, two keyed poses, play, save, drop the file back in', async () => {
    const made = await page.evaluate(async () => {
      const v = window.mocapViewer;
      // Waits for the next drawn frame (each call below asks for one).
      const tick = async () => {
        const f = v.state().framesRendered;
        for (let i = 0; i < 300 && v.state().framesRendered <= f; i++) await new Promise((r) => setTimeout(r, 20));
      };
      v.newCharacter();
      await tick();
      const errors = [v.edit(0, 'add:Hips:Arm:0,0.4,0'), v.edit(0, 'add:Arm:Hand:0,0.4,0')].filter((e) => e !== undefined);
      await tick();
      const poses = [];
      for (const [frame, dx] of [[10, 0.3], [40, -0.3]]) {
        v.seek(frame);
        await tick();
        const p = v.jointWorldPosition(0, 'Hand');
        const reached = v.dragJoint(0, 'Hand', p[0] + dx, p[1] - 0.2, p[2]);
        // The creator keys by default between keys (key-frame animation).
        const error = v.setKey() ?? null;
        await tick();
        poses.push({ reached, error, at: v.jointWorldPosition(0, 'Hand'), target: [p[0] + dx, p[1] - 0.2, p[2]] });
      }
      v.seek(25);
      await tick();
      const between = Array.from(v.jointWorldPosition(0, 'Hand'));
      const keys = v.state().clips[0].keys;
      v.play();
      await new Promise((r) => setTimeout(r, 600));
      const playing = v.state();
      v.pause();
      const [name, text] = v.saveBvh(0);
      return { errors, poses, playing, name, text, between, keys };
    });
    check(made.errors.length === 0, `joints added (${made.errors})`);
    for (const p of made.poses) {
      const d = Math.hypot(p.at[0] - p.target[0], p.at[1] - p.target[1], p.at[2] - p.target[2]);
      check(p.reached && p.error === null && d < 5e-3, `a keyed pose holds (${d.toFixed(4)} m)`);
    }
    const [a, b] = made.poses.map((p) => p.at[0]);
    check(made.keys.join() === '10,40' && Math.min(a, b) + 0.05 < made.between[0] && made.between[0] < Math.max(a, b) - 0.05,
      `keys ${made.keys}; halfway between them the hand is between its keyed places (x ${made.between[0].toFixed(3)} between ${a.toFixed(3)} and ${b.toFixed(3)})`);
    check(made.playing.playing && made.playing.time > 0, `it plays (${made.playing.time.toFixed(2)} s)`);
    check(made.name === 'character-edited.bvh', `saved as ${made.name}`);
    await dropFiles(page, [{ name: made.name, bytes: Buffer.from(made.text) }]);
    const s = await waitDropped(page, made.name);
    const c = s.clips[0];
    check(s.error === null && c.joints === 3 && c.frames === 60 && c.jointNames.join() === 'Hips,Arm,Hand,Hand_End', `dropped back in: ${c.joints} joints, ${c.frames} frames (${c.jointNames})`);
  });
} finally {
  await close();
}
finish('API tests');
