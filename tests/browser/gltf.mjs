// glTF written by `mocap` (the core's writer, files made by `cargo xtask test`):
// the Khronos glTF-Validator finds no error in any of them, and three.js's
// GLTFLoader, in headless Chromium, plays each animation to the joint positions
// we computed (metres, Y up) at the frames listed, and each MD2 model's morph
// animation (models.json) to the vertices we computed at a time between frames.
//
//   node gltf.mjs DIR CHROMIUM     (DIR holds expected.json and the .glb/.gltf files)
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import validator from 'gltf-validator';
import { launch } from './common.mjs';

const [dir, chromium] = process.argv.slice(2);
const here = path.dirname(fileURLToPath(import.meta.url));
const expected = JSON.parse(fs.readFileSync(path.join(dir, 'expected.json'), 'utf8'));
const models = JSON.parse(fs.readFileSync(path.join(dir, 'models.json'), 'utf8'));
let failed = 0;
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} [gltf] ${what}`);
  if (!ok) failed += 1;
};

for (const entry of [...expected, ...models]) {
  const bytes = fs.readFileSync(path.join(dir, entry.file));
  const report = await validator.validateBytes(new Uint8Array(bytes), { maxIssues: 50 });
  const { numErrors, numWarnings } = report.issues;
  const first = report.issues.messages.filter((m) => m.severity <= 1).slice(0, 3).map((m) => `${m.code} ${m.pointer ?? ''}`).join('; ');
  check(numErrors === 0, `${entry.file}: glTF-Validator ${report.validatorVersion}: ${numErrors} errors, ${numWarnings} warnings ${first}`);
}

const { page, close, errors } = await launch(chromium, 'webgl2');
const types = { '.js': 'text/javascript', '.html': 'text/html', '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json' };
await page.route('http://gltf.test/**', (route) => {
  const url = new URL(route.request().url());
  let file;
  if (url.pathname.startsWith('/three/')) file = path.join(here, 'node_modules/three', url.pathname.slice(7));
  else if (url.pathname.startsWith('/files/')) file = path.join(dir, path.basename(url.pathname));
  else if (url.pathname === '/') {
    return route.fulfill({
      contentType: 'text/html',
      body: '<!doctype html><script type="importmap">{"imports":{"three":"/three/build/three.module.js","three/addons/":"/three/examples/jsm/"}}</script><body></body>',
    });
  }
  if (!file || !fs.existsSync(file)) return route.fulfill({ status: 404, body: 'not found' });
  return route.fulfill({ contentType: types[path.extname(file)] ?? 'application/octet-stream', body: fs.readFileSync(file) });
});
await page.goto('http://gltf.test/');

for (const entry of expected) {
  const result = await page.evaluate(async ({ file, frames, joints }) => {
    const THREE = await import('three');
    const { GLTFLoader } = await import('three/addons/loaders/GLTFLoader.js');
    const gltf = await new GLTFLoader().loadAsync(`/files/${file}`);
    const nodes = [];
    for (let i = 0; i < joints; i += 1) nodes.push(await gltf.parser.getDependency('node', i));
    const mixer = new THREE.AnimationMixer(gltf.scene);
    if (gltf.animations.length > 0) {
      // Played once and held, so the last key is the last frame (looping, the end is frame 0).
      const action = mixer.clipAction(gltf.animations[0]);
      action.setLoop(THREE.LoopOnce, 1);
      action.clampWhenFinished = true;
      action.play();
    }
    let worst = 0;
    const v = new THREE.Vector3();
    for (const { time, positions } of frames) {
      mixer.setTime(time);
      gltf.scene.updateMatrixWorld(true);
      nodes.forEach((node, j) => {
        node.getWorldPosition(v);
        const [x, y, z] = positions[j];
        worst = Math.max(worst, Math.hypot(v.x - x, v.y - y, v.z - z));
      });
    }
    let skinned = 0;
    gltf.scene.traverse((o) => { if (o.isSkinnedMesh) skinned += 1; });
    return { worst, skinned, names: nodes.map((n) => n.name), animations: gltf.animations.length };
  }, entry);
  check(result.worst <= entry.tolerance,
    `${entry.file}: three.js puts every joint where we do (worst ${result.worst.toExponential(2)} m, tolerance ${entry.tolerance.toExponential(2)}) at ${entry.frames.length} frames`);
  check(result.skinned === (entry.body ? 1 : 0), `${entry.file}: ${result.skinned} skinned mesh (the body)`);
  check(result.animations === (entry.animated ? 1 : 0), `${entry.file}: ${result.animations} animation`);
}
for (const entry of models) {
  const result = await page.evaluate(async ({ file, animation, time, vertices }) => {
    const THREE = await import('three');
    const { GLTFLoader } = await import('three/addons/loaders/GLTFLoader.js');
    const gltf = await new GLTFLoader().loadAsync(`/files/${file}`);
    let mesh = null;
    gltf.scene.traverse((o) => { if (o.isMesh && !mesh) mesh = o; });
    const clip = gltf.animations.find((a) => a.name === animation);
    if (!mesh || !clip) return { error: `mesh ${!!mesh}, animation ${animation} ${!!clip}` };
    const mixer = new THREE.AnimationMixer(gltf.scene);
    const action = mixer.clipAction(clip);
    action.setLoop(THREE.LoopOnce, 1);
    action.clampWhenFinished = true;
    action.play();
    mixer.setTime(time);
    gltf.scene.updateMatrixWorld(true);
    const v = new THREE.Vector3();
    let worst = 0;
    vertices.forEach(([x, y, z], i) => {
      mesh.getVertexPosition(i, v);
      v.applyMatrix4(mesh.matrixWorld);
      worst = Math.max(worst, Math.hypot(v.x - x, v.y - y, v.z - z));
    });
    const textured = !!(mesh.material && mesh.material.map);
    return { worst, textured, animations: gltf.animations.length, targets: mesh.morphTargetInfluences?.length ?? 0 };
  }, entry);
  check(!result.error, `${entry.file}: ${result.error ?? 'loaded'}`);
  check(result.worst <= entry.tolerance,
    `${entry.file}: three.js plays \`${entry.animation}\` at ${entry.time} s to our vertices (worst ${result.worst?.toExponential(2)} m, tolerance ${entry.tolerance.toExponential(2)}; ${result.targets} morph targets, ${result.animations} animations)`);
  check(result.textured, `${entry.file}: textured with its skin`);
}
check(errors.length === 0, `no page errors ${errors.slice(0, 3).join(' | ')}`);
await close();
if (failed > 0) {
  console.error(`${failed} glTF checks failed`);
  process.exit(1);
}
