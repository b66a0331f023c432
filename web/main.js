// Page glue: feature check, start the wasm viewer, file drop / Open, loading message.
import init, { start } from '../pkg/mocap_web.js';

const status = document.getElementById('status');
const input = document.getElementById('file-input');

function showStatus(text, isError = false) {
  status.textContent = text;
  status.classList.toggle('error', isError);
  status.hidden = false;
}

function hideStatus() {
  status.hidden = true;
}

function hasWebGL2() {
  try {
    return !!document.createElement('canvas').getContext('webgl2');
  } catch {
    return false;
  }
}

const NO_GPU = 'This viewer needs WebGPU or WebGL2, and this browser offers neither.\n' +
  'Try a current Chrome, Edge, Firefox or Safari with hardware acceleration enabled.';

// Lets the browser paint (e.g. the loading message) before blocking work.
const afterPaint = () => new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve, 0)));

// Resolves with the clip frame shown once the viewer has drawn a frame after `since` frames.
function nextRenderedFrame(viewer, since) {
  return new Promise((resolve) => {
    const poll = () => {
      const s = viewer.state();
      if (s && s.framesRendered > since) resolve(s.frame); else requestAnimationFrame(poll);
    };
    requestAnimationFrame(poll);
  });
}

async function loadFile(viewer, file, t0) {
  const big = file.size > 512 * 1024;
  if (big) {
    showStatus(`Loading ${file.name} (${(file.size / 1048576).toFixed(1)} MB)…`);
    await afterPaint();
  }
  const bytes = new Uint8Array(await file.arrayBuffer());
  const tParse = performance.now();
  const error = viewer.load(file.name, bytes);
  const tLoaded = performance.now();
  const parseMs = tLoaded - tParse;
  if (big) hideStatus();
  const rendered = viewer.state().framesRendered;
  const firstFrame = await nextRenderedFrame(viewer, rendered);
  window.mocapLastLoad = {
    name: file.name, bytes: file.size, error: error ?? null, firstFrame,
    parseMs, loadMs: tLoaded - t0, dropToFrameMs: performance.now() - t0,
  };
}

function wireFiles(viewer) {
  let depth = 0;
  const isFileDrag = (e) => e.dataTransfer && Array.from(e.dataTransfer.types || []).includes('Files');
  window.addEventListener('dragenter', (e) => {
    if (!isFileDrag(e)) return;
    e.preventDefault();
    depth += 1;
    document.body.classList.add('dragging');
  }, true);
  window.addEventListener('dragleave', () => {
    depth = Math.max(0, depth - 1);
    if (depth === 0) document.body.classList.remove('dragging');
  }, true);
  window.addEventListener('dragover', (e) => {
    e.preventDefault();
    e.stopPropagation();
  }, true);
  window.addEventListener('drop', (e) => {
    const t0 = performance.now();
    e.preventDefault();
    e.stopPropagation();
    depth = 0;
    document.body.classList.remove('dragging');
    const file = e.dataTransfer && e.dataTransfer.files && e.dataTransfer.files[0];
    if (file) loadFile(viewer, file, t0);
  }, true);
  input.addEventListener('change', () => {
    const file = input.files && input.files[0];
    if (file) loadFile(viewer, file, performance.now());
    input.value = '';
  });
}

async function main() {
  if (!navigator.gpu && !hasWebGL2()) {
    showStatus(NO_GPU, true);
    return;
  }
  try {
    await init();
    const viewer = await start('viewer', 'file-input');
    window.mocapViewer = viewer;
    wireFiles(viewer);
    hideStatus();
  } catch (e) {
    console.warn('viewer failed to start:', e);
    showStatus(`${NO_GPU}\n\n(${e && e.message ? e.message : e})`, true);
  }
}

main();
