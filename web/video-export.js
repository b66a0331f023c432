// Video export (Edit ▸ Export video…, and the JS API's exportVideo): every frame
// is drawn offscreen at its exact time by the viewer (renderVideoFrame), then
// encoded: MP4 (H.264) and WebM (VP9, else VP8) through WebCodecs with
// mediabunny's muxers, GIF through gifenc with a palette per frame. Frame k
// shows from + k/fps. Bundled into dist/ by `cargo xtask dist` (esbuild), so
// the page keeps its CSP (scripts from 'self', no eval).
import {
  BufferTarget, Mp4OutputFormat, Output, QUALITY_HIGH, VideoSample, VideoSampleSource, WebMOutputFormat,
  canEncodeVideo,
} from 'mediabunny';
import { GIFEncoder, applyPalette, quantize } from 'gifenc';

/** The highest frame rate a GIF shows faithfully (delays are whole hundredths). */
export const GIF_MAX_FPS = 50;

/** Why WebCodecs formats are missing, or null when the browser has them. */
function webCodecsMissing() {
  if (typeof VideoEncoder === 'undefined') return 'this browser has no WebCodecs video encoder';
  return null;
}

/**
 * The formats this browser can write at `width`x`height`: `[{format, label, codec, reason}]`,
 * `codec` null (with the `reason`) where it cannot.
 */
export async function videoFormats(width, height) {
  const missing = webCodecsMissing();
  const size = { width: even(width), height: even(height) };
  const first = async (codecs) => {
    for (const codec of codecs) if (!missing && (await canEncodeVideo(codec, size).catch(() => false))) return codec;
    return null;
  };
  const mp4 = await first(['avc']);
  const webm = await first(['vp9', 'vp8']);
  return [
    { format: 'mp4', label: 'MP4 (H.264)', codec: mp4, reason: mp4 ? null : missing || 'this browser cannot encode H.264' },
    { format: 'webm', label: `WebM (${webm === 'vp8' ? 'VP8' : 'VP9'})`, codec: webm, reason: webm ? null : missing || 'this browser cannot encode VP9 or VP8' },
    { format: 'gif', label: 'GIF', codec: 'gif', reason: null },
  ];
}

function even(n) {
  return Math.max(16, Math.floor(n / 2) * 2);
}

/** Times of the frames: `count` frames `1/fps` apart from `from` (both ends shown). */
export function frameTimes(from, to, fps) {
  const count = Math.floor((to - from) * fps + 1e-6) + 1;
  return Array.from({ length: Math.max(1, count) }, (_, k) => from + k / fps);
}

/**
 * Renders and encodes a video. `options`: `{format: 'mp4'|'webm'|'gif', width, height, fps,
 * from, to, follow}` (defaults: WebM, the view's size, the clip's rate, the whole clip, the
 * view's camera); `onProgress(done, total)`; `signal` (an AbortSignal) cancels. Resolves to
 * the file's bytes (a Uint8Array).
 */
export async function exportVideo(viewer, options = {}, { onProgress, signal } = {}) {
  const d = viewer.videoDefaults() || {};
  const format = options.format || 'webm';
  const fps = Number(options.fps) || d.fps || 30;
  if (!(fps > 0 && fps <= 240)) throw new Error(`fps ${options.fps}: 0 to 240 frames a second`);
  if (format === 'gif' && fps > GIF_MAX_FPS) throw new Error(`fps ${fps}: a GIF shows at most ${GIF_MAX_FPS} frames a second`);
  const from = options.from ?? 0;
  const to = options.to ?? d.duration ?? 0;
  if (!(from >= 0 && to >= from)) throw new Error(`from ${from} to ${to}: not a range of times`);
  const ratio = window.devicePixelRatio || 1;
  let width = Math.round(options.width || (d.viewWidth || 640) * ratio);
  let height = Math.round(options.height || (d.viewHeight || 360) * ratio);
  if (format !== 'gif') [width, height] = [even(width), even(height)];
  const times = frameTimes(from, to, fps);
  const follow = !!options.follow;
  const draw = (t) => viewer.renderVideoFrame(t, width, height, follow);
  const check = () => {
    if (signal && signal.aborted) throw new DOMException('Export cancelled', 'AbortError');
  };
  if (format === 'gif') return gif(draw, times, fps, width, height, check, onProgress);
  const formats = await videoFormats(width, height);
  const entry = formats.find((f) => f.format === format);
  if (!entry) throw new Error(`format ${format}: expected mp4, webm or gif`);
  if (!entry.codec) throw new Error(`${entry.label}: ${entry.reason}`);
  const output = new Output({
    format: format === 'mp4' ? new Mp4OutputFormat({ fastStart: 'in-memory' }) : new WebMOutputFormat(),
    target: new BufferTarget(),
  });
  const source = new VideoSampleSource({ codec: entry.codec, bitrate: QUALITY_HIGH, keyFrameInterval: 2 });
  output.addVideoTrack(source, { frameRate: fps });
  await output.start();
  try {
    for (let k = 0; k < times.length; k++) {
      check();
      const pixels = await draw(times[k]);
      const sample = new VideoSample(pixels, {
        format: 'RGBA', codedWidth: width, codedHeight: height, timestamp: k / fps, duration: 1 / fps,
      });
      await source.add(sample);
      sample.close();
      if (onProgress) onProgress(k + 1, times.length);
    }
    check();
    await output.finalize();
  } catch (e) {
    await output.cancel().catch(() => {});
    throw e;
  }
  return new Uint8Array(output.target.buffer);
}

/** A looping GIF, a palette per frame, delays in hundredths that add up to the true times. */
async function gif(draw, times, fps, width, height, check, onProgress) {
  const encoder = GIFEncoder();
  const end = (k) => Math.round((k * 100) / fps);
  for (let k = 0; k < times.length; k++) {
    check();
    const rgba = await draw(times[k]);
    const palette = quantize(rgba, 256, { format: 'rgb565' });
    const index = applyPalette(rgba, palette, 'rgb565');
    const hundredths = Math.max(2, end(k + 1) - end(k));
    encoder.writeFrame(index, width, height, { palette, delay: hundredths * 10, repeat: 0 });
    if (onProgress) onProgress(k + 1, times.length);
    // Lets the page draw and answer between frames.
    await new Promise((r) => setTimeout(r, 0));
  }
  encoder.finish();
  return encoder.bytes();
}

/** `walk.webm` from the first clip's name. */
export function videoName(viewer, format) {
  const s = viewer.state();
  const name = (s && s.clips[0] && s.clips[0].name) || 'motion';
  return `${name.replace(/\.[^.]*$/, '') || 'motion'}.${format}`;
}

/**
 * Shows the export dialog (`#video-export` in index.html): format, size, frame rate, range
 * and camera; Export renders with a progress bar and Cancel, then downloads the file.
 */
export async function openExportDialog(viewer, download) {
  const dialog = document.getElementById('video-export');
  const form = dialog.querySelector('form');
  const d = viewer.videoDefaults() || {};
  const ratio = window.devicePixelRatio || 1;
  const view = [Math.round((d.viewWidth || 640) * ratio), Math.round((d.viewHeight || 360) * ratio)];
  const status = dialog.querySelector('.video-status');
  const progress = dialog.querySelector('progress');
  const exportButton = dialog.querySelector('button[value=export]');
  const sizeOf = () => {
    const choice = form.elements.size.value;
    if (choice === 'view') return view;
    if (choice === '720') return [1280, 720];
    if (choice === '1080') return [1920, 1080];
    return [Number(form.elements.width.value) || view[0], Number(form.elements.height.value) || view[1]];
  };
  form.elements.fps.value = String(Math.round((d.fps || 30) * 1000) / 1000);
  form.elements.width.value = String(view[0]);
  form.elements.height.value = String(view[1]);
  form.querySelector('option[value=view]').textContent = `The view's (${view[0]}×${view[1]})`;
  const loop = form.querySelector('option[value=loop]');
  loop.disabled = d.loopFrom == null;
  loop.textContent = d.loopFrom == null ? 'Loop range (none set)' : `Loop range (${d.loopFrom.toFixed(2)}–${d.loopTo.toFixed(2)} s)`;
  const formatSelect = form.elements.format;
  const formats = await videoFormats(...sizeOf());
  const notes = [];
  for (const f of formats) {
    const option = formatSelect.querySelector(`option[value=${f.format}]`);
    option.textContent = f.label + (f.codec ? '' : ' — not available');
    option.disabled = !f.codec;
    if (!f.codec) notes.push(`${f.label}: ${f.reason}.`);
  }
  if (formatSelect.selectedOptions[0]?.disabled) formatSelect.value = 'gif';
  status.textContent = notes.join(' ');
  progress.hidden = true;
  exportButton.disabled = false;
  let abort = null;
  form.onsubmit = async (event) => {
    event.preventDefault();
    const action = event.submitter ? event.submitter.value : 'export';
    if (action === 'cancel') {
      if (abort) abort.abort();
      else dialog.close();
      return;
    }
    const [width, height] = sizeOf();
    const range = form.elements.range.value === 'loop' && d.loopFrom != null ? [d.loopFrom, d.loopTo] : [0, d.duration || 0];
    const options = {
      format: formatSelect.value, width, height, fps: Number(form.elements.fps.value),
      from: range[0], to: range[1], follow: form.elements.camera.value === 'follow',
    };
    abort = new AbortController();
    exportButton.disabled = true;
    progress.hidden = false;
    progress.value = 0;
    status.textContent = 'Rendering…';
    try {
      const bytes = await exportVideo(viewer, options, {
        signal: abort.signal,
        onProgress: (done, total) => {
          progress.max = total;
          progress.value = done;
          status.textContent = `Frame ${done} of ${total}`;
        },
      });
      const name = videoName(viewer, options.format);
      download(name, bytes);
      status.textContent = `Saved ${name} (${(bytes.length / 1e6).toFixed(1)} MB).`;
    } catch (e) {
      status.textContent = e && e.name === 'AbortError' ? 'Cancelled.' : `Export failed: ${e && e.message ? e.message : e}`;
    } finally {
      abort = null;
      exportButton.disabled = false;
      progress.hidden = true;
    }
  };
  dialog.onclose = () => {
    if (abort) abort.abort();
  };
  if (!dialog.open) dialog.showModal();
}
