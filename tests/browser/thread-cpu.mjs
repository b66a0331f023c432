// CPU time of Chromium's threads read from /proc (Linux), for the performance tools
// frame-cpu.mjs and cold-cpu.mjs (not tests).
import fs from 'node:fs';

const TICKS_PER_S = 100;

/** CPU milliseconds so far of every thread of every process of `chromium` (its path), by pid/tid. */
export function threads(chromium) {
  const out = new Map();
  for (const pid of fs.readdirSync('/proc')) {
    if (!/^\d+$/.test(pid)) continue;
    let cmd;
    try { cmd = fs.readFileSync(`/proc/${pid}/cmdline`, 'latin1'); } catch { continue; }
    if (!cmd.startsWith(chromium.replace('/usr/bin/', '/usr/lib/')) && !cmd.startsWith(chromium)) continue;
    const type = (cmd.match(/--type=([a-z-]+)/) || [null, 'browser'])[1];
    let tids;
    try { tids = fs.readdirSync(`/proc/${pid}/task`); } catch { continue; }
    for (const tid of tids) {
      try {
        const stat = fs.readFileSync(`/proc/${pid}/task/${tid}/stat`, 'latin1');
        const name = stat.slice(stat.indexOf('(') + 1, stat.lastIndexOf(')')).replace(/\d+$/, '#');
        const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
        out.set(`${pid}/${tid}`, { key: `${type}:${name}`, ms: (Number(fields[11]) + Number(fields[12])) * 1000 / TICKS_PER_S });
      } catch { /* the thread ended */ }
    }
  }
  return out;
}

/** Milliseconds spent between two `threads()` readings, summed by process type and thread name. */
export function spentByThread(before, after) {
  const byThread = new Map();
  for (const [id, t] of after) {
    const spent = t.ms - (before.get(id)?.ms ?? 0);
    if (spent > 0) byThread.set(t.key, (byThread.get(t.key) ?? 0) + spent);
  }
  return byThread;
}
