// Page glue: feature check, start the wasm viewer, `?url=` links with progress (each
// motion one character; an Acclaim skeleton and its motions pair up), the view state in the fragment, Share, `?embed=1`, file drop
// (several files replace what is open; with Shift held they are added) / Open… / Add…,
// loading message.
import init, { FileSet, start } from '../pkg/mocap_web.js';
import { ClipError, DEFAULT_LIMIT, fetchClip, fileNameOf, gltfCompanions, resolveClipUrl } from './fetch-clip.js';
import { followViewState, share } from './view-link.js';
import { watchGpu } from './gpu-loss.js';
import { startAutosave } from './autosave.js';

const status = document.getElementById('status');
const input = document.getElementById('file-input');

function showStatus(text, isError = false) {
  status.classList.remove('starting');
  status.textContent = text;
  status.classList.toggle('error', isError);
  status.hidden = false;
}

function hideStatus() {
  status.hidden = true;
}

// Where the open clips came from, for the Share link: the default clip, `url=` links
// (every one that loaded, in order), or local files (which a link cannot carry).
let source = { kind: 'default', urls: [], name: 'walk.bvh' };

// Shows "Loading name: x / y MB" with a progress bar (indeterminate without a length).
function showProgress(name, received, total) {
  const mb = (n) => (n / 1048576).toFixed(1);
  status.replaceChildren();
  status.classList.remove('error', 'starting');
  const text = document.createElement('div');
  text.textContent = total ? `Loading ${name}: ${mb(received)} / ${mb(total)} MB` : `Loading ${name}: ${mb(received)} MB`;
  const bar = document.createElement('progress');
  if (total) {
    bar.max = total;
    bar.value = received;
  }
  status.append(text, bar);
  status.hidden = false;
}

// Downloads the file of one `?url=` link with its progress bar. Resolves with
// { name, bytes }, or with null after reporting the error (record and banner).
async function fetchUrl(viewer, raw, limit) {
  const t0 = performance.now();
  const record = { url: raw, name: null, bytes: 0, progressEvents: 0, error: null };
  window.mocapUrlLoad = record;
  window.mocapUrlLoads.push(record);
  let fetched = null;
  try {
    const url = resolveClipUrl(raw);
    const name = fileNameOf(url);
    record.name = name;
    showProgress(name, 0, null);
    let lastPaint = 0;
    const bytes = await fetchClip(url, {
      limit,
      onProgress: (received, total) => {
        record.progressEvents += 1;
        record.bytes = received;
        record.total = total;
        const now = performance.now();
        if (now - lastPaint > 100) {
          lastPaint = now;
          showProgress(name, received, total);
        }
      },
    });
    hideStatus();
    fetched = { name, bytes, raw, record };
  } catch (e) {
    hideStatus();
    const message = e instanceof ClipError ? e.message : `${raw}: ${e && e.message ? e.message : e}`;
    record.error = message;
    viewer.showError(message);
  }
  record.ms = performance.now() - t0;
  return fetched;
}

// Loads every `?url=` link: downloads them in order, then hands all of them to the
// viewer at once, so that an Acclaim skeleton and its motions (url=a.asf&url=b.amc)
// pair up; the core decides what each file is. Each link records its own error; with
// several failures the banner lists them all.
async function loadUrls(viewer, urls, limit) {
  source = { kind: 'url', urls: [], name: null };
  const errors = [];
  const fetched = [];
  for (const raw of urls) {
    const f = await fetchUrl(viewer, raw, limit);
    if (f) fetched.push(f); else errors.push(window.mocapUrlLoad.error);
    // A .gltf's buffers and images are fetched from beside it.
    for (const companion of f ? gltfCompanions(f.name, f.bytes, resolveClipUrl(raw)) : []) {
      const c = await fetchUrl(viewer, companion, limit);
      if (c) fetched.push({ ...c, companion: true }); else errors.push(window.mocapUrlLoad.error);
    }
  }
  if (fetched.length > 0) {
    const failures = viewer.openFiles(fetched.map((f) => f.name), fetched.map((f) => f.bytes), true);
    for (const f of fetched) {
      const error = failures.find((m) => m.startsWith(`${f.name}:`));
      if (error) {
        f.record.error = error;
        errors.push(error);
      } else if (!f.companion) {
        source = { kind: 'url', urls: [...source.urls, f.raw], name: f.name };
      }
    }
  }
  for (const record of window.mocapUrlLoads) record.done = true;
  // The banner says whether any link opened (it then replaced what was open).
  if (errors.length > 0) viewer.showError(errors.join('\n'), source.urls.length > 0);
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

// Runs `task` once the page is idle (or after `ms` at the latest).
const whenIdle = (task, ms) => (window.requestIdleCallback
  ? window.requestIdleCallback(task, { timeout: ms })
  : setTimeout(task, ms));

// The page's start, for performance tools: the performance mark
// `mocap-first-frame` (time since the page opened) right after the viewer's
// first drawn frame. The viewer draws its first frame in its canvas's resize
// observer; this one, made after it, runs right after it in the same update.
// Then, once idle, the glTF reader's and writer's code is made ready
// (`warmUp`; the mark `mocap-warm-up`, its detail whether it ran): the browser
// compiles WebAssembly a function at a time on first use, which the first
// glTF file opened or saved would otherwise wait for.
function markFirstFrame(viewer, canvas) {
  let marked = false;
  const mark = () => {
    if (marked || viewer.state().framesRendered === 0) return;
    marked = true;
    observer.disconnect();
    performance.mark('mocap-first-frame');
    whenIdle(() => performance.mark('mocap-warm-up', { detail: viewer.warmUp() }), 1000);
  };
  const observer = new ResizeObserver(mark);
  observer.observe(canvas);
  nextRenderedFrame(viewer, 0).then(mark);
}

// Reads `file` into `set` chunk by chunk, straight into the module's memory
// (no whole-file ArrayBuffer and no second copy of it).
async function readInto(set, file) {
  set.begin(file.name, file.size);
  if (typeof file.stream !== 'function') {
    set.push(new Uint8Array(await file.arrayBuffer()));
    return;
  }
  const reader = file.stream().getReader();
  for (;;) {
    const { done, value } = await reader.read();
    if (done) return;
    set.push(value);
  }
}

// Opens dropped or picked files, all at once (the core pairs an Acclaim skeleton
// with its motions and decides each file's format from its content): with `add` they
// join what is open, else what opens replaces it. What fails is reported (all of it)
// and changes nothing.
async function loadFiles(viewer, files, add, t0) {
  const size = files.reduce((n, f) => n + f.size, 0);
  // Files that take a while to read (about a second per 64 MB on a slow
  // machine) show a message first; waiting for it to be painted costs a frame,
  // which on a software GPU is a good part of reading a smaller file.
  const big = size > 64 * 1024 * 1024;
  const names = files.map((f) => f.name);
  if (big) {
    showStatus(`Loading ${names.join(', ')} (${(size / 1048576).toFixed(1)} MB)…`);
    await afterPaint();
  }
  // Playback holds while the files are read and opened: on a software GPU the
  // frames drawn meanwhile would take the processor from the read.
  viewer.holdFrames(true);
  let errors = null;
  let parseMs = 0;
  const set = new FileSet();
  try {
    for (const file of files) {
      try {
        await readInto(set, file);
      } catch (e) {
        // The browser could not read it (moved, deleted, no permission): what is open stays.
        errors = [`${file.name}: could not be read (${e && e.message ? e.message : e})`];
        viewer.showError(errors[0]);
        break;
      }
    }
    if (!errors) {
      const tParse = performance.now();
      errors = viewer.openFileSet(set, add);
      parseMs = performance.now() - tParse;
    }
  } finally {
    set.free();
    viewer.holdFrames(false);
  }
  if (errors.length < files.length) {
    // A link cannot carry a local file; the links of clips still open are kept for the record.
    source = { kind: 'local', urls: add ? source.urls : [], name: names[names.length - 1] };
  }
  const tLoaded = performance.now();
  if (big) hideStatus();
  const rendered = viewer.state().framesRendered;
  const firstFrame = await nextRenderedFrame(viewer, rendered);
  window.mocapLastLoad = {
    name: names[names.length - 1], names, add, errors, error: errors[0] ?? null, firstFrame,
    bytes: size, parseMs, loadMs: tLoaded - t0, dropToFrameMs: performance.now() - t0,
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
    const files = Array.from((e.dataTransfer && e.dataTransfer.files) || []);
    if (files.length > 0) loadFiles(viewer, files, e.shiftKey, t0);
  }, true);
  input.addEventListener('change', () => {
    const files = Array.from(input.files || []);
    if (files.length > 0) loadFiles(viewer, files, input.dataset.mode === 'add', performance.now());
    input.value = '';
  });
}

// Downloads the file the viewer asked to save (Save as BVH or glTF, Save rig): the
// bytes come from the viewer; the page only hands them to the browser as a file.
function saveFile(viewer) {
  // A file the viewer asked for, else the current character as BVH.
  const saved = viewer.takeDownload() ?? viewer.saveBvh();
  if (saved) download(saved[0], saved[1]);
}

// Saves the selected character (else the first) as `kind` ('bvh' or 'glb') without
// the viewer's menus: what the page offers when the graphics device is gone.
function saveWork(viewer, kind) {
  const s = viewer.state();
  const index = s.selectedCharacter ?? 0;
  if (kind === 'bvh') {
    const saved = viewer.saveBvh(index);
    if (saved) download(saved[0], saved[1]);
    return;
  }
  try {
    const [name, bytes] = viewer.saveGltfFile(index);
    download(name, bytes);
  } catch (e) {
    viewer.showError(`Save as glTF: ${e && e.message ? e.message : e}`);
  }
}

function download(name, text) {
  const types = { glb: 'model/gltf-binary', mp4: 'video/mp4', webm: 'video/webm', gif: 'image/gif' };
  const type = types[name.split('.').pop()] || 'text/plain';
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
  window.mocapLastSave = { name, bytes: text.length };
}

// The line under the toolbar after a restore: "Restored your unsaved work · Discard".
function sessionBanner() {
  const element = document.getElementById('session-banner');
  return {
    show(text, actions) {
      const line = document.createElement('span');
      line.textContent = text;
      element.replaceChildren(line);
      for (const { label, action } of actions) {
        element.append(' · ');
        const b = document.createElement('button');
        b.type = 'button';
        b.textContent = label;
        b.addEventListener('click', action);
        element.append(b);
      }
      const close = document.createElement('button');
      close.type = 'button';
      close.className = 'close';
      close.textContent = '×';
      close.title = 'Close';
      close.addEventListener('click', () => { element.hidden = true; });
      element.append(close);
      element.hidden = false;
    },
    hide() {
      element.hidden = true;
    },
  };
}

// A one-line notice about autosave (`null` hides it).
function autosaveNotice(text) {
  const element = document.getElementById('autosave-notice');
  element.textContent = text ?? '';
  element.hidden = !text;
}

// After one visit the page works offline (sw.js caches the page's own files).
function registerServiceWorker() {
  if (!('serviceWorker' in navigator) || !window.isSecureContext) return;
  navigator.serviceWorker.register('sw.js').catch((e) => console.warn('offline copy unavailable:', e));
}

async function main() {
  if (!navigator.gpu && !hasWebGL2()) {
    showStatus(NO_GPU, true);
    return;
  }
  const params = new URLSearchParams(location.search);
  const urls = params.getAll('url').filter((u) => u.trim() !== '');
  const maxMb = Number(params.get('maxmb'));
  const limit = maxMb > 0 ? maxMb * 1048576 : DEFAULT_LIMIT;
  const embed = params.get('embed') === '1';
  if (embed) document.body.classList.add('embed');
  // ?demo=tentacle[&bones=N] opens a demo instead of the default clip.
  const demo = urls.length === 0 ? params.get('demo') : null;
  // The canvas's style as the viewer sets it, set before the page's first
  // paint: a change to the page while the viewer starts makes the browser
  // composite a frame of it, which on a software rasteriser holds the GPU
  // process (and the graphics context the viewer waits for) for ~100 ms.
  const canvas = document.getElementById('viewer');
  canvas.style.setProperty('outline', 'none');
  canvas.style.setProperty('cursor', 'default');
  const loading = init(); // the module's download and compilation start
  // A WebGPU adapter, asked for once the module is ready, is answered while
  // the viewer starts; the viewer takes the answer (without one it goes
  // straight to WebGL2). Not asked earlier: the first request waits for the
  // browser's GPU process, which without a GPU is busy with the page's first
  // frame, and would hold the module's compilation up meanwhile.
  const webgpuAdapter = navigator.gpu ? loading.then(() => navigator.gpu.requestAdapter()).catch(() => null) : undefined;
  let viewer;
  try {
    await loading;
    viewer = await start('viewer', 'file-input', urls.length === 0 && !demo, webgpuAdapter);
    window.mocapViewer = viewer;
    markFirstFrame(viewer, document.getElementById('viewer'));
    viewer.setEmbed(embed);
    wireFiles(viewer);
    watchGpu(viewer, 'viewer', 'gpu-notice', (kind) => saveWork(viewer, kind));
    hideStatus();
  } catch (e) {
    console.warn('viewer failed to start:', e);
    showStatus(`${NO_GPU}\n\n(${e && e.message ? e.message : e})`, true);
    return;
  }
  window.mocapUrlLoads = [];
  if (urls.length > 0) await loadUrls(viewer, urls, limit);
  if (demo && !viewer.openDemo(demo, Number(params.get('bones')) || undefined)) viewer.showError(`?demo=${demo}: no such demo (try ?demo=tentacle)`);
  // The page's answers to the viewer's requests, before autosave opens its storage.
  window.addEventListener('mocap-share', () => share(viewer, source));
  window.addEventListener('mocap-save', () => saveFile(viewer));
  // Edit ▸ Export video…: the exporter (and its encoders) load on first use.
  window.addEventListener('mocap-export-video', () => {
    import('./video-export.js')
      .then((m) => m.openExportDialog(viewer, download))
      .catch((e) => viewer.showError(`Video export could not start: ${e && e.message ? e.message : e}`));
  });
  // JS API: exportVideo({format, width, height, fps, from, to, follow}) resolves to the bytes.
  viewer.exportVideo = (options, callbacks) => import('./video-export.js').then((m) => m.exportVideo(viewer, options, callbacks));
  // Edits not saved are not lost by accident: the browser asks before leaving.
  window.addEventListener('beforeunload', (e) => {
    const s = viewer.state();
    if (s && s.clips.some((c) => c.unsaved)) e.preventDefault();
  });
  const hash = location.hash.length > 1 ? location.hash.slice(1) : null;
  if (hash) viewer.applyViewState(hash);
  // Without a link the work stored last time comes back (the fragment, the page's
  // own record of the view, then applies over it again).
  const saved = await startAutosave(viewer, { restore: urls.length === 0 && !demo, banner: sessionBanner(viewer), notice: autosaveNotice });
  if (hash && saved.restored) viewer.applyViewState(hash);
  followViewState(viewer);
  document.getElementById('share-close').addEventListener('click', () => {
    document.getElementById('share').hidden = true;
  });
  registerServiceWorker();
  window.mocapReady = true;
}

main();
