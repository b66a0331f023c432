// The service worker: after one visit the page works without a network. The
// page's own files are cached when the worker installs (the list and the
// version are filled in by `cargo xtask dist`); each request for one of them
// goes to the network first and falls back to the cache, so an online visit
// always gets the current page and refreshes the cache. Clips come from drops
// or links as before: requests to other origins are not touched.
const VERSION = '/*VERSION*/';
const FILES = [/*FILES*/];
const CACHE = `mocap-${VERSION}`;

self.addEventListener('install', (event) => {
  event.waitUntil(caches.open(CACHE).then((cache) => cache.addAll(FILES)).then(() => self.skipWaiting()));
});

self.addEventListener('activate', (event) => {
  event.waitUntil(
    caches.keys()
      .then((names) => Promise.all(names.filter((n) => n.startsWith('mocap-') && n !== CACHE).map((n) => caches.delete(n))))
      .then(() => self.clients.claim()),
  );
});

self.addEventListener('fetch', (event) => {
  const url = new URL(event.request.url);
  if (event.request.method !== 'GET' || url.origin !== self.location.origin) return;
  event.respondWith(
    fetch(event.request)
      .then((response) => {
        if (response.ok && response.type === 'basic') {
          const copy = response.clone();
          caches.open(CACHE).then((cache) => cache.put(event.request, copy));
        }
        return response;
      })
      .catch(() => caches.match(event.request, { ignoreSearch: true }).then((hit) => hit ?? Response.error())),
  );
});
