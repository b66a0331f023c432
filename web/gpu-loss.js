// A lost graphics device (a GPU process crash, a driver update, too many tabs
// holding contexts): the page keeps everything open, says so, and draws again on
// a new device. WebGL2 reports the loss on the canvas (`webglcontextlost`),
// WebGPU through the viewer (`mocap-gpu-lost`, from the device's lost promise).
// If no device can be had, the page says so and still offers to save the work.

const RESET = 'The graphics device was reset; redrawing…';
const NONE = 'The graphics device was lost and none can be had now. Your work is still here: save it, or try again.';
// How long to wait for the browser to restore a lost WebGL context before
// starting on a fresh canvas anyway.
const RESTORE_WAIT_MS = 1500;
// Retries when no device can be had, before asking the user.
const RETRIES = [500, 1500, 4000];

/**
 * Watches for losses of the viewer's device. `canvasId` names the canvas it draws
 * on, `noticeId` an element for the notice (a text and buttons); `save(kind)` saves
 * the work as `'bvh'` or `'glb'`.
 */
export function watchGpu(viewer, canvasId, noticeId, save) {
  const notice = noticeOn(document.getElementById(noticeId));
  let recovering = false;
  const record = { losses: 0, restarts: 0, failures: 0, lastError: null, state: 'running' };
  window.mocapGpu = record;

  const canvas = () => document.getElementById(canvasId);
  const listenCanvas = (c) => {
    c.addEventListener('webglcontextlost', (e) => {
      // Without this the browser never restores the context.
      e.preventDefault();
      setTimeout(() => lost(c, 'WebGL context lost', true), 0);
    });
  };
  listenCanvas(canvas());
  // The device-lost callback runs inside a graphics call: act after it returns.
  window.addEventListener('mocap-gpu-lost', (e) => setTimeout(() => lost(canvas(), e.detail, false), 0));

  async function lost(old, reason, webgl) {
    if (recovering || !old.isConnected) return;
    recovering = true;
    record.losses += 1;
    record.lastError = String(reason);
    record.state = 'lost';
    viewer.stopGraphics();
    // A lost canvas shows the browser's broken-content mark: the page behind instead.
    old.style.visibility = 'hidden';
    notice.show(RESET);
    if (webgl) await restored(old);
    await recover(old);
  }

  async function recover(old) {
    record.state = 'recovering';
    for (let attempt = 0; ; attempt += 1) {
      if (await restart(old)) break;
      if (attempt >= RETRIES.length) {
        record.state = 'failed';
        notice.show(NONE, [
          { label: 'Try again', action: () => { notice.show(RESET); recover(canvas()); } },
          { label: 'Save as BVH', action: () => save('bvh') },
          { label: 'Save as glTF', action: () => save('glb') },
        ]);
        return;
      }
      await new Promise((r) => setTimeout(r, RETRIES[attempt]));
    }
    record.state = 'running';
    record.restarts += 1;
    notice.hide();
    recovering = false;
  }

  // Starts the viewer again on a fresh canvas in the old one's place (a canvas keeps
  // the context it had, lost or not); true when it draws.
  async function restart(old) {
    const fresh = old.cloneNode(false);
    fresh.style.visibility = '';
    old.replaceWith(fresh);
    listenCanvas(fresh);
    try {
      await viewer.restartGraphics(fresh);
      fresh.focus();
      return true;
    } catch (e) {
      record.failures += 1;
      record.lastError = e && e.message ? e.message : String(e);
      console.warn('graphics restart failed:', record.lastError);
      return false;
    }
  }
}

// Resolves when `c`'s WebGL context is restored, or after RESTORE_WAIT_MS.
function restored(c) {
  return new Promise((resolve) => {
    const done = () => { clearTimeout(timer); resolve(); };
    const timer = setTimeout(done, RESTORE_WAIT_MS);
    c.addEventListener('webglcontextrestored', done, { once: true });
  });
}

// The notice: a line of text and optional buttons, over the page.
function noticeOn(element) {
  return {
    show(text, buttons = []) {
      const line = document.createElement('div');
      line.textContent = text;
      const row = document.createElement('div');
      row.className = 'gpu-notice-buttons';
      for (const { label, action } of buttons) {
        const b = document.createElement('button');
        b.type = 'button';
        b.textContent = label;
        b.addEventListener('click', action);
        row.append(b);
      }
      element.replaceChildren(line, ...(buttons.length ? [row] : []));
      element.hidden = false;
    },
    hide() {
      element.hidden = true;
      element.replaceChildren();
    },
  };
}
