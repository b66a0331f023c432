// Autosave: the work open in the viewer (its characters with their edits, the
// edit history, what is saved, the view) is kept in the browser's storage
// (IndexedDB) a moment after each change, so that a crashed tab, a killed browser
// or a "Leave" clicked by mistake loses nothing. Opening the page again without
// a `?url=` restores it; with one, the link opens and the earlier session stays
// one click away ("Restore previous session"). The viewer gives the session as a
// small manifest and its assets by content key; an asset already stored is never
// stored again. No storage (a private window) or a full one gives a one-line
// notice; the viewer goes on as before.

const DB_NAME = 'mocap-autosave';
const SESSIONS = 'sessions';
const ASSETS = 'assets';
// How often the page looks for changes, and how long it waits after one before storing.
const POLL_MS = 700;
const QUIET_MS = 600;

function request(r) {
  return new Promise((resolve, reject) => {
    r.onsuccess = () => resolve(r.result);
    r.onerror = () => reject(r.error);
  });
}

// How long the page waits for its storage before going on without autosave.
const OPEN_MS = 4000;

function openDb() {
  return new Promise((resolve, reject) => {
    let r;
    try {
      r = indexedDB.open(DB_NAME, 1);
    } catch (e) {
      reject(e);
      return;
    }
    // Storage that does not answer (another tab deleting or upgrading it) must
    // not hold the page: autosave is off for this visit instead.
    const timer = setTimeout(() => reject(new Error('the storage did not answer')), OPEN_MS);
    r.onupgradeneeded = () => {
      r.result.createObjectStore(SESSIONS);
      r.result.createObjectStore(ASSETS);
    };
    r.onsuccess = () => {
      clearTimeout(timer);
      const db = r.result;
      // Another tab deleting or upgrading the database is not kept waiting.
      db.onversionchange = () => db.close();
      resolve(db);
    };
    r.onerror = () => { clearTimeout(timer); reject(r.error); };
    r.onblocked = () => { clearTimeout(timer); reject(new Error('storage blocked')); };
  });
}

// Runs `fn(stores)` in one transaction over `names`; resolves when it commits.
function transaction(db, names, mode, fn) {
  return new Promise((resolve, reject) => {
    const tx = db.transaction(names, mode);
    const stores = Object.fromEntries(names.map((n) => [n, tx.objectStore(n)]));
    let result;
    Promise.resolve(fn(stores)).then((r) => { result = r; }, reject);
    tx.oncomplete = () => resolve(result);
    tx.onerror = () => reject(tx.error);
    tx.onabort = () => reject(tx.error ?? new Error('storage transaction aborted'));
  });
}

function isQuota(e) {
  return e && (e.name === 'QuotaExceededError' || /quota/i.test(String(e.message ?? e)));
}

/**
 * Starts autosave for `viewer`. With `restore` (no `?url=`) a stored session is
 * opened first and `banner` says so; otherwise a stored session becomes the
 * previous one. `banner.show(text, actions)` / `banner.hide()` show page notices.
 */
export async function startAutosave(viewer, { restore, banner, notice }) {
  const record = { saves: 0, storedAssets: 0, restored: null, error: null, off: null };
  window.mocapAutosave = record;
  let db;
  try {
    db = await openDb();
  } catch (e) {
    record.off = String(e && e.message ? e.message : e);
    notice(`Autosave is off: this browser keeps no storage for this page (${record.off}).`);
    return record;
  }
  const get = (store, key) => transaction(db, [store], 'readonly', (s) => request(s[store].get(key)));
  const known = new Set(await transaction(db, [ASSETS], 'readonly', (s) => request(s[ASSETS].getAllKeys())));

  async function open(session, what) {
    const keys = session.keys;
    const assets = await transaction(db, [ASSETS], 'readonly', (s) => Promise.all(keys.map((k) => request(s[ASSETS].get(k)))));
    if (assets.some((a) => !a)) return 'the saved session lacks some of its files';
    return viewer.restoreSession(session.manifest, session.view, keys, assets) ?? null;
  }

  let current = null;
  let previous = null;
  try {
    current = await get(SESSIONS, 'current');
    previous = await get(SESSIONS, 'previous');
  } catch (e) {
    record.error = String(e);
  }
  if (current && restore) {
    const error = await open(current);
    record.restored = error ?? (current.unsaved ? 'unsaved' : 'session');
    if (error) {
      viewer.showError(`Could not restore your last session: ${error}`);
    } else {
      const text = current.unsaved ? 'Restored your unsaved work' : 'Restored your last session';
      banner.show(text, [{ label: 'Discard', action: () => discard(current) }]);
    }
  } else if (current) {
    // A link opens: what was open before stays one click away.
    previous = current;
    await transaction(db, [SESSIONS], 'readwrite', (s) => { s[SESSIONS].put(current, 'previous'); s[SESSIONS].delete('current'); }).catch(() => {});
  }
  viewer.setPreviousSession(!!previous);

  // Discard: the restored work becomes the previous session (one click away) and
  // the page starts as new.
  async function discard(session) {
    banner.hide();
    previous = session;
    await transaction(db, [SESSIONS], 'readwrite', (s) => s[SESSIONS].put(session, 'previous')).catch(() => {});
    viewer.openDefault();
    viewer.setPreviousSession(true);
  }

  window.addEventListener('mocap-restore-previous', async () => {
    if (!previous) return;
    const error = await open(previous);
    if (error) viewer.showError(`Could not restore the previous session: ${error}`);
  });

  let stamp = null;
  let view = null;
  let changedAt = 0;
  let busy = false;
  let full = false;

  async function store() {
    const nowStamp = viewer.sessionStamp();
    const nowView = viewer.viewState();
    if (nowStamp === stamp && nowView === view) return;
    const session = viewer.storeSession([...known]);
    if (!session) return;
    if (!session.worth) {
      // Nothing worth keeping (the untouched default clip): nothing to restore next time.
      await transaction(db, [SESSIONS], 'readwrite', (s) => s[SESSIONS].delete('current'));
      [stamp, view] = [nowStamp, nowView];
      return;
    }
    const entry = { manifest: session.manifest, view: session.view, keys: session.keys, unsaved: session.unsaved, at: Date.now() };
    await transaction(db, [SESSIONS, ASSETS], 'readwrite', (s) => {
      for (const [key, bytes] of session.fresh) s[ASSETS].put(bytes, key);
      s[SESSIONS].put(entry, 'current');
    });
    for (const [key] of session.fresh) known.add(key);
    record.storedAssets += session.fresh.length;
    record.saves += 1;
    [stamp, view] = [nowStamp, nowView];
    if (full) {
      full = false;
      notice(null);
    }
    await collect(entry);
  }

  // Forgets assets neither the current nor the previous session names.
  async function collect(entry) {
    const wanted = new Set([...entry.keys, ...(previous ? previous.keys : [])]);
    const stale = [...known].filter((k) => !wanted.has(k));
    if (stale.length === 0) return;
    await transaction(db, [ASSETS], 'readwrite', (s) => stale.forEach((k) => s[ASSETS].delete(k)));
    stale.forEach((k) => known.delete(k));
  }

  let lastStamp = viewer.sessionStamp();
  let lastView = viewer.viewState();
  setInterval(async () => {
    const nowStamp = viewer.sessionStamp();
    const nowView = viewer.viewState();
    if (nowStamp !== lastStamp || nowView !== lastView) {
      [lastStamp, lastView] = [nowStamp, nowView];
      changedAt = performance.now();
    }
    if (busy || (nowStamp === stamp && nowView === view) || performance.now() - changedAt < QUIET_MS) return;
    busy = true;
    try {
      await store();
    } catch (e) {
      record.error = String(e && e.message ? e.message : e);
      if (isQuota(e)) {
        full = true;
        notice("Autosave is paused: the browser's storage for this page is full. Save your work as BVH or glTF.");
        // Tried again on the next change only.
        [stamp, view] = [nowStamp, nowView];
      } else {
        notice(`Autosave failed: ${record.error}`);
      }
    } finally {
      busy = false;
    }
  }, POLL_MS);
  return record;
}
