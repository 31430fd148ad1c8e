// What the servers' load tests share (bench/studio_load.mjs, bench/review_load.mjs): requests
// that give up, raw slow clients from the load's address, the server's memory, and a probe
// asking what the page asks twice a second while a phase's load runs.
import fs from 'node:fs';
import net from 'node:net';

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
export const PROBE_TIMEOUT_MS = 30000;
export const LOAD_ADDRESS = '127.0.0.2';

// A request that gives up after `ms` (status 0): a starved server must not stall the bench.
export async function timed(send, ms = PROBE_TIMEOUT_MS) {
  const t0 = performance.now();
  const status = await Promise.race([send().then((r) => r.status).catch(() => -1), sleep(ms).then(() => 0)]);
  return { status, ms: performance.now() - t0 };
}

// A raw connection from LOAD_ADDRESS that sends `bytes` now, or a byte every `everyMs`; resolves
// with the status the server answered (0: none) when it closes or after `holdMs`.
export function slowClient(port, bytes, { everyMs = 0, holdMs = 20000 } = {}) {
  const socket = net.connect({ port, host: '127.0.0.1', localAddress: LOAD_ADDRESS });
  let text = '', at = 0, timer = null;
  socket.on('error', () => {});
  socket.on('data', (c) => { text += c.toString('latin1'); });
  socket.on('connect', () => {
    if (!everyMs) { socket.write(bytes); return; }
    timer = setInterval(() => { if (at < bytes.length && !socket.destroyed) socket.write(bytes[at++]); }, everyMs);
  });
  return new Promise((resolve) => {
    const finish = () => { clearInterval(timer); socket.destroy(); resolve(Number((text.match(/^HTTP\/1\.1 (\d{3})/) || [])[1] || 0)); };
    socket.on('close', finish);
    setTimeout(finish, holdMs);
  });
}

// Samples the server's VmRSS (MiB) every 50 ms while a phase runs.
export function memoryWatch(pid) {
  const rss = () => {
    try { return Number(fs.readFileSync(`/proc/${pid}/status`, 'utf8').match(/VmRSS:\s+(\d+)/)[1]) / 1024; } catch { return 0; }
  };
  let peak = rss();
  const timer = setInterval(() => { peak = Math.max(peak, rss()); }, 50);
  return { stop: () => { clearInterval(timer); return { peak, after: rss() }; }, now: rss };
}

// Asks `ask()` (what the page asks) twice a second until `until` resolves; the waits.
export async function probeWhile(ask, until) {
  const waits = [];
  let running = true;
  until.finally(() => { running = false; });
  while (running) {
    const t = await timed(ask);
    waits.push(t);
    if (running) await Promise.race([sleep(500), until.catch(() => {})]);
  }
  return waits;
}

export const median = (xs) => { const s = [...xs].sort((a, b) => a - b); return s.length ? s[(s.length - 1) >> 1] : NaN; };

// One phase of a load test: `load()` resolves with the statuses of its requests (or lines saying
// what happened), abandoned after `limitMs` (its result then says `limitLine`); meanwhile `ask`
// probes the server as its page does, and the server's memory (process `pid`) is watched. Prints
// a line and returns the phase's figures, `tally` summing up what the load got.
export async function runPhase(name, { pid, ask, load, limitMs, limitLine, tally }) {
  const watch = memoryWatch(pid);
  const t0 = performance.now();
  const loadDone = Promise.race([load(), sleep(limitMs).then(() => [limitLine])]);
  const probes = await probeWhile(ask, loadDone);
  const statuses = await loadDone;
  const memory = watch.stop();
  const waits = probes.map((p) => p.ms);
  const result = {
    phase: name, seconds: (performance.now() - t0) / 1000, probes: probes.length,
    probe_ok: probes.filter((p) => p.status === 200).length,
    probe_median_ms: median(waits), probe_worst_ms: Math.max(...waits),
    load: tally(statuses), rss_peak_mib: memory.peak, rss_after_mib: memory.after,
  };
  console.log(`${name}: ${result.seconds.toFixed(1)} s; probes ${result.probe_ok}/${result.probes} answered, ` +
              `median ${result.probe_median_ms.toFixed(1)} ms, worst ${result.probe_worst_ms.toFixed(0)} ms; ` +
              `load got ${result.load}; RSS peak ${memory.peak.toFixed(0)} MiB, after ${memory.after.toFixed(0)} MiB`);
  return result;
}
