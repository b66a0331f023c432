// The view state in the URL fragment (kept up to date without new history entries)
// and the Share button's link.

/** Minimum time between two fragment updates (ms). */
const UPDATE_MS = 400;

/**
 * Minimum time between two fragment updates while the clip plays (ms): each would
 * only move the time on, and every `history.replaceState` costs the browser a few
 * milliseconds of two processes (a frame's worth on a software GPU). Pausing
 * writes the fragment within UPDATE_MS again.
 */
const PLAYING_UPDATE_MS = 5000;

/** Whether a view state string says the clip plays. */
const playing = (view) => /(^|&)play=1(&|$)/.test(view);

/** A view state string without its time. */
const sansTime = (view) => view.replace(/(^|&)t=[^&]*/, '');

/**
 * Keeps `location.hash` equal to the viewer's view state; returns a stop function.
 * The viewer sends `mocap-view` after a frame that changed the state; the fragment
 * follows at most every UPDATE_MS (PLAYING_UPDATE_MS where only the playing
 * clip's time moved on). Nothing runs while nothing changes.
 */
export function followViewState(viewer) {
  let stopped = false;
  let last = '';
  let lastWrite = -Infinity;
  let timer = null;
  const update = () => {
    timer = null;
    if (stopped) return;
    const view = viewer.viewState();
    // Without a clip (e.g. a link that failed) the fragment is left as the user gave it.
    if (!view || view === last) return;
    // Only the time moved on while playing: the next frame's `mocap-view` asks again.
    const timeOnly = playing(view) && sansTime(view) === sansTime(last);
    if (timeOnly && performance.now() - lastWrite < PLAYING_UPDATE_MS) return;
    if (viewer.state().clips.length > 0) {
      last = view;
      lastWrite = performance.now();
      const url = new URL(location.href);
      url.hash = view;
      history.replaceState(history.state, '', url);
    }
  };
  const onView = () => {
    if (timer === null && !stopped) timer = setTimeout(update, UPDATE_MS);
  };
  update();
  window.addEventListener('mocap-view', onView);
  const onHash = () => {
    const hash = location.hash.slice(1);
    if (hash && hash !== last) viewer.applyViewState(hash);
  };
  window.addEventListener('hashchange', onHash);
  return () => {
    stopped = true;
    if (timer !== null) clearTimeout(timer);
    window.removeEventListener('mocap-view', onView);
    window.removeEventListener('hashchange', onHash);
  };
}

/**
 * The link that reproduces the view: this page, the clip's `url=` links (none for the
 * default clip) and the view state. `source` is {kind: 'default'|'url'|'local', urls, name}.
 */
export function shareLink(viewer, source) {
  const url = new URL(location.href);
  url.searchParams.delete('url');
  if (source.kind === 'url') source.urls.forEach((u) => url.searchParams.append('url', u));
  url.hash = viewer.viewState();
  return url.href;
}

/** Shows the share box (plain text only) with the link; copies it when allowed. */
export async function share(viewer, source) {
  const link = shareLink(viewer, source);
  let copied = false;
  try {
    await navigator.clipboard.writeText(link);
    copied = true;
  } catch {
    copied = false;
  }
  const note = source.kind === 'local'
    ? `"${source.name}" is a file on this computer, so a link cannot carry it. Put the file on a ` +
      'web host that allows CORS and add ?url=<its address> to the link. This link restores the view only:'
    : (copied ? 'Link copied to the clipboard:' : 'Copy this link:');
  const box = document.getElementById('share');
  box.querySelector('.share-note').textContent = note;
  const field = box.querySelector('input');
  field.value = link;
  box.hidden = false;
  field.focus();
  field.select();
  window.mocapLastShare = { link, copied, local: source.kind === 'local', note };
  return link;
}
