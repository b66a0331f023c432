// Loading a clip from a `?url=` link: only http(s), relative URLs resolve against the
// page, streamed progress, a size limit, and one specific message per failure.

/** Default size limit in bytes (override with `?maxmb=`). */
export const DEFAULT_LIMIT = 256 * 1024 * 1024;

/** An error whose message is meant for the page, as is. */
export class ClipError extends Error {}

/** Resolves `raw` against the page; throws a ClipError unless it is http or https. */
export function resolveClipUrl(raw, base = document.baseURI) {
  let url;
  try {
    url = new URL(raw, base);
  } catch {
    throw new ClipError(`"${raw}" is not a valid link.`);
  }
  if (url.protocol !== 'http:' && url.protocol !== 'https:') {
    throw new ClipError(`Only http and https links can be loaded; "${url.protocol}" links are refused.`);
  }
  return url;
}

/** The file name a URL's last path segment gives (for messages and the parser). */
export function fileNameOf(url) {
  const last = url.pathname.split('/').filter(Boolean).pop() || 'clip.bvh';
  try {
    return decodeURIComponent(last);
  } catch {
    return last;
  }
}

const mb = (n) => `${(n / 1048576).toFixed(1)} MB`;

// A fetch that throws (TypeError) means either the host is unreachable or it answered
// without CORS headers. A `no-cors` request tells the two apart: it succeeds (with an
// opaque response) when the host answered at all.
async function failureKind(url) {
  try {
    await fetch(url, { mode: 'no-cors', credentials: 'omit', cache: 'no-store' });
    return 'cors';
  } catch {
    return 'network';
  }
}

/**
 * Fetches `url` (a URL from resolveClipUrl). `onProgress(received, total|null)` runs
 * as bytes arrive. Resolves with a Uint8Array; rejects with a ClipError whose message
 * names the problem.
 */
export async function fetchClip(url, { limit = DEFAULT_LIMIT, onProgress = () => {} } = {}) {
  const where = url.href;
  let response;
  try {
    response = await fetch(url, { mode: 'cors', credentials: 'omit' });
  } catch {
    if (await failureKind(url) === 'cors') {
      throw new ClipError(`${where}: blocked by CORS. The host ${url.origin} must send ` +
        `"Access-Control-Allow-Origin: *" (or this page's origin, ${location.origin}) with the file.`);
    }
    throw new ClipError(`${where}: network failure (the host could not be reached).`);
  }
  if (response.status === 404 || response.status === 410) {
    throw new ClipError(`${where}: not found (HTTP ${response.status}).`);
  }
  if (!response.ok) {
    throw new ClipError(`${where}: the server answered HTTP ${response.status} ${response.statusText}.`);
  }
  const declared = Number(response.headers.get('Content-Length'));
  const total = Number.isFinite(declared) && declared > 0 ? declared : null;
  const tooLarge = (n) => new ClipError(`${where}: too large (${mb(n)}; the limit is ${mb(limit)}, ` +
    'raise it with ?maxmb=).');
  if (total !== null && total > limit) throw tooLarge(total);
  const chunks = [];
  let received = 0;
  onProgress(0, total);
  try {
    const reader = response.body.getReader();
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      received += value.length;
      if (received > limit) {
        reader.cancel().catch(() => {});
        throw tooLarge(received);
      }
      chunks.push(value);
      onProgress(received, total);
    }
  } catch (e) {
    if (e instanceof ClipError) throw e;
    throw new ClipError(`${where}: network failure while downloading (${received} bytes received).`);
  }
  const bytes = new Uint8Array(received);
  let at = 0;
  for (const c of chunks) {
    bytes.set(c, at);
    at += c.length;
  }
  // What the file is, the core decides (from its content), not this page.
  return bytes;
}

/**
 * The other files a `.gltf` (JSON) names by relative URI — its `.bin` buffers and
 * images — resolved against the link it came from (data URIs left out); empty for
 * anything else.
 */
export function gltfCompanions(name, bytes, base) {
  if (!/\.gltf$/i.test(name)) return [];
  let json;
  try {
    json = JSON.parse(new TextDecoder().decode(bytes));
  } catch {
    return []; // the reader reports what is wrong with it
  }
  const uris = [...(json.buffers ?? []), ...(json.images ?? [])]
    .map((x) => x && x.uri)
    .filter((u) => typeof u === 'string' && !u.startsWith('data:'));
  return [...new Set(uris)].map((u) => new URL(u, base).href);
}
