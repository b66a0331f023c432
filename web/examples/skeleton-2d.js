// Example: the wasm package's parseMotion without the viewer; the skeleton is drawn
// from the front (x right, y up) with Canvas 2D and animated in real time.
import init, { parseMotion } from '../../pkg/mocap_web.js';

const canvas = document.getElementById('view');
const ctx = canvas.getContext('2d');
const info = document.getElementById('info');
let clip = null;
let bounds = null;
let startTime = 0;

// The x/y extent of every joint over a few frames, to fit the drawing to the canvas.
function extent(c) {
  const box = { minX: Infinity, minY: Infinity, maxX: -Infinity, maxY: -Infinity };
  const step = Math.max(1, Math.floor(c.frameCount / 20));
  for (let f = 0; f < c.frameCount; f += step) {
    const p = c.worldPositions(f);
    for (let i = 0; i < p.length; i += 3) {
      box.minX = Math.min(box.minX, p[i]);
      box.maxX = Math.max(box.maxX, p[i]);
      box.minY = Math.min(box.minY, p[i + 1]);
      box.maxY = Math.max(box.maxY, p[i + 1]);
    }
  }
  return box;
}

function draw(frame) {
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  if (!clip || clip.frameCount === 0) return;
  const p = clip.worldPositions(frame);
  const parents = clip.parents;
  const w = bounds.maxX - bounds.minX || 1;
  const h = bounds.maxY - bounds.minY || 1;
  const scale = 0.85 * Math.min(canvas.width / w, canvas.height / h);
  const x = (i) => canvas.width / 2 + (p[3 * i] - (bounds.minX + bounds.maxX) / 2) * scale;
  const y = (i) => canvas.height / 2 - (p[3 * i + 1] - (bounds.minY + bounds.maxY) / 2) * scale;
  ctx.strokeStyle = '#e8e8e8';
  ctx.lineWidth = 3;
  ctx.beginPath();
  parents.forEach((parent, i) => {
    if (parent < 0) return;
    ctx.moveTo(x(parent), y(parent));
    ctx.lineTo(x(i), y(i));
  });
  ctx.stroke();
  ctx.fillStyle = '#5b9bf0';
  parents.forEach((_, i) => {
    ctx.beginPath();
    ctx.arc(x(i), y(i), 4, 0, 2 * Math.PI);
    ctx.fill();
  });
}

function tick(now) {
  if (clip && clip.frameCount > 0) {
    const frame = Math.floor((now - startTime) / 1000 / clip.frameTime) % clip.frameCount;
    draw(frame);
    window.skeletonExample.frame = frame;
  }
  requestAnimationFrame(tick);
}

function open(bytes, name) {
  try {
    const next = parseMotion(bytes, name);
    if (clip) clip.free();
    clip = next;
    bounds = extent(clip);
    startTime = performance.now();
    info.textContent = `${name}: ${clip.jointNames.length} joints, ${clip.frameCount} frames at ` +
      `${(1 / clip.frameTime).toFixed(1)} fps`;
    Object.assign(window.skeletonExample, { name, joints: clip.jointNames.length, frames: clip.frameCount, error: null });
  } catch (e) {
    info.textContent = `Could not open ${name}: ${e.message}`;
    window.skeletonExample.error = e.message;
  }
}

window.skeletonExample = { ready: false, frame: 0 };
await init();
document.getElementById('file').addEventListener('change', async (e) => {
  const file = e.target.files && e.target.files[0];
  if (file) open(new Uint8Array(await file.arrayBuffer()), file.name);
});
const response = await fetch('../../data/walk.bvh').catch(() => null);
if (response && response.ok) {
  open(new Uint8Array(await response.arrayBuffer()), 'walk.bvh');
} else {
  info.textContent = 'Open a .bvh file to see its skeleton.';
}
window.skeletonExample.ready = true;
requestAnimationFrame(tick);
