// A load test of the review server (docs/review.md, "The server's promises"),
// the twin of bench/studio_load.mjs: loopback only, bounded in count and time,
// stopping by itself (about a minute and a half a build against a server that
// keeps its promises, at most about four against one that does not): many
// concurrent clients, slow clients (half-sent and trickling requests), a Range
// header of 400 overlapping ranges on a 4 MiB file, and concurrent verdicts,
// each beside a "probe" client that asks GET /api/assets as the page does,
// twice a second. The probe is the page (127.0.0.1); the load comes from
// another loopback address (127.0.0.2), one client to the server's per-client
// limits. Prints, per phase, how long the probes waited (median and worst),
// what the load's own requests got, and the server's resident memory (peak,
// and after).
//
// The library (tests/review/library.mjs: two presets × two seeds with
// three-frame turntables, one failed job, and 4 MiB of random bytes as
// small-s1/big.bin) is baked once, with BAKER (default: the last ROCKBAKE), and
// each ROCKBAKE given reviews its own copy of it, one after the other. Every
// rockbake needs its data folder (ROCKBAKE_DATA_DIR, or an install).
// Usage: node bench/review_load.mjs ROCKBAKE... [--bake-with BAKER] [--json FILE]
import crypto from 'node:crypto';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { api, bakeLibrary, startReview, stopReview, writeLibrary } from '../tests/review/library.mjs';
import { LOAD_ADDRESS, memoryWatch, runPhase, sleep, slowClient, timed } from './load_probe.mjs';

const args = process.argv.slice(2);
const option = (name) => { const at = args.indexOf(name); return at >= 0 ? args.splice(at, 2)[1] : null; };
const jsonFile = option('--json');
const rockbakes = args;
const baker = option('--bake-with') ?? rockbakes[rockbakes.length - 1];
if (!rockbakes.length || rockbakes.some((r) => r.startsWith('--'))) {
  console.error('usage: node bench/review_load.mjs ROCKBAKE... [--bake-with BAKER] [--json FILE]');
  process.exit(2);
}

const PHASE_LIMIT_MS = 45000;   // a phase's load is abandoned after this (it says so)
const BUILD_LIMIT_MS = 240000;  // one build's whole run
const ASSETS = ['small-s1', 'small-s2', 'tall-s1', 'tall-s2'];  // the library's baked assets
const BIG_FILE = 'small-s1/big.bin';
const BIG_SIZE = 4 * 1024 * 1024;

// A request of the load (from LOAD_ADDRESS); resolves with its status.
function loadRequest(url, apiPath) {
  const u = new URL(url);
  return new Promise((resolve, reject) => {
    const request = http.request({ host: u.hostname, port: u.port, localAddress: LOAD_ADDRESS, path: apiPath }, (res) => {
      res.resume();
      res.on('end', () => resolve({ status: res.statusCode }));
    });
    request.on('error', reject);
    request.end();
  });
}

// A POST as the page's fetch sends it (same-origin: Host and Origin the
// server's own, Content-Type: application/json), from LOAD_ADDRESS.
function loadPost(url, apiPath, body) {
  const u = new URL(url);
  const text = JSON.stringify(body);
  return new Promise((resolve, reject) => {
    const request = http.request({ host: u.hostname, port: u.port, localAddress: LOAD_ADDRESS, path: apiPath, method: 'POST',
      headers: { 'Content-Type': 'application/json', 'Content-Length': Buffer.byteLength(text), Origin: `http://${u.host}` } },
    (res) => {
      res.resume();
      res.on('end', () => resolve({ status: res.statusCode }));
    });
    request.on('error', reject);
    request.end(text);
  });
}



// GET `filePath` with `range`, reading and counting what comes back (at most
// `limitMs`); resolves with a line: the status, the bytes and how long it took.
function rangeRequest(url, filePath, range, limitMs) {
  const u = new URL(url);
  const t0 = performance.now();
  return new Promise((resolve) => {
    let bytes = 0, status = 0, done = false;
    const mib = () => `${(bytes / 1048576).toFixed(1)} MiB (${bytes} bytes)`;
    const secs = () => `${((performance.now() - t0) / 1000).toFixed(1)} s`;
    const finish = (line) => { if (!done) { done = true; clearTimeout(timer); request.destroy(); resolve(line); } };
    const request = http.request({ host: u.hostname, port: u.port, localAddress: LOAD_ADDRESS, path: filePath, agent: false,
      headers: { Range: range } }, (res) => {
      status = res.statusCode;
      res.on('data', (c) => { bytes += c.length; });
      res.on('end', () => finish(`${status}, ${mib()} received in ${secs()}`));
      res.on('error', (e) => finish(`${status}, ${e.code || e.message} after ${mib()} in ${secs()}`));
    });
    request.on('error', (e) => finish(`${e.code === 'ECONNRESET' ? 'connection reset' : e.code || e.message} ` +
                                      `(status ${status || 'none'}) after ${mib()} in ${secs()}`));
    const timer = setTimeout(() => finish(`timed out after ${(limitMs / 1000).toFixed(0)} s (status ${status || 'none'}), ${mib()} received`),
                             limitMs);
    request.end();
  });
}



// Statuses counted (0: no answer, -1: error); lines (what a phase saw) as they are.
const tally = (statuses) => {
  const counts = {}, lines = [];
  for (const s of statuses) if (typeof s === 'number') counts[s] = (counts[s] || 0) + 1; else lines.push(s);
  const parts = Object.entries(counts).map(([s, n]) => `${n}×${s === '0' ? 'no answer' : s === '-1' ? 'error' : s}`);
  return [...parts, ...lines].join(', ') || '—';
};

// A phase against this server: its page's probe, its own limit and tally.
function phase(name, review, load) {
  return runPhase(name, { pid: review.child.pid, ask: () => api(review.url, '/api/assets'), load, limitMs: PHASE_LIMIT_MS,
    limitLine: `phase time limit (${PHASE_LIMIT_MS / 1000} s)`, tally });
}

async function run(rockbake, out) {
  const review = current = await startReview(rockbake, out);
  const port = Number(new URL(review.url).port);
  const guard = setTimeout(() => { console.error(`review_load: ${rockbake} over ${BUILD_LIMIT_MS / 60000} minutes; killed`);
                                   review.child.kill('SIGKILL'); }, BUILD_LIMIT_MS);
  const results = [];
  let rssStart = 0;
  try {
    await api(review.url, '/api/assets');
    await sleep(300);
    rssStart = memoryWatch(review.child.pid).stop().after;
    results.push(await phase('idle', review, () => sleep(3000).then(() => [])));

    // 64 clients at once, 8 requests each: the assets list, one asset, a file of it.
    results.push(await phase('64 concurrent clients × 8 requests', review, async () => {
      const client = async (i) => {
        const out = [];
        for (let k = 0; k < 8; ++k) {
          const asset = ASSETS[(i + k) % ASSETS.length];
          const which = (i + k) % 3;
          const target = which === 0 ? '/api/assets' : which === 1 ? `/api/assets/${asset}` : `/files/${asset}/rock.glb`;
          out.push((await timed(() => loadRequest(review.url, target))).status);
        }
        return out;
      };
      return (await Promise.all(Array.from({ length: 64 }, (_, i) => client(i)))).flat();
    }));

    // 100 requests half sent and held for 20 s.
    results.push(await phase('100 half-sent requests held 20 s', review, () =>
      Promise.all(Array.from({ length: 100 }, () =>
        slowClient(port, `GET /api/assets HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\nX-Half: `, { holdMs: 20000 })))));

    // 10 requests that trickle a byte every 2 s (each ~40 bytes: 80 s if never cut off; held at most 24 s).
    results.push(await phase('10 requests trickling a byte every 2 s', review, () =>
      Promise.all(Array.from({ length: 10 }, () =>
        slowClient(port, `GET /api/assets HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\n\r\n`, { everyMs: 2000, holdMs: 24000 })))));

    // One Range header of 400 whole-file ranges on the 4 MiB file: 1.6 GB if each is answered.
    const range = `bytes=${Array(400).fill('0-').join(',')}`;
    results.push(await phase('Range: 400 × "0-" on a 4 MiB file', review, async () =>
      [await rangeRequest(review.url, `/files/${BIG_FILE}`, range, PHASE_LIMIT_MS - 5000)]));

    // 64 verdicts at once, as the page posts them, 16 on each asset.
    const verdicts = ['approved', 'needs-work', 'rejected'];
    results.push(await phase('64 verdict POSTs at once', review, async () => {
      const statuses = await Promise.all(Array.from({ length: 64 }, (_, i) => timed(() => loadPost(review.url, '/api/review',
        { asset: ASSETS[i % ASSETS.length], status: verdicts[i % 3], note: `load ${i}: ${'n'.repeat(200)}` })).then((t) => t.status)));
      let kept = 'review.json unreadable';
      try {
        const file = JSON.parse(fs.readFileSync(path.join(out, 'review.json'), 'utf8'));
        kept = `review.json holds ${Object.keys(file.assets || {}).length} of ${ASSETS.length} verdicts`;
      } catch { /* said */ }
      return [...statuses, kept];
    }));
    results.push(await phase('idle after', review, () => sleep(3000).then(() => [])));
  } finally {
    clearTimeout(guard);
    const code = await Promise.race([stopReview(review).catch(() => 'killed'), sleep(25000).then(() => 'killed')]);
    if (code === 'killed') review.child.kill('SIGKILL');
  }
  return { rockbake, rss_start_mib: rssStart, results };
}

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'rockbake-review-load-'));
// The whole run stops by itself whatever the servers do.
let current = null;  // the review server running now
setTimeout(() => {
  console.error('review_load: over its time; stopped');
  current?.child.kill('SIGKILL');
  fs.rmSync(dir, { recursive: true, force: true });
  process.exit(1);
}, rockbakes.length * (BUILD_LIMIT_MS + 30000) + 60000).unref();

// The library, baked once; each build gets a copy (verdicts write into it).
const runs = [];
try {
  writeLibrary(dir);
  const t0 = performance.now();
  const status = bakeLibrary(baker, dir);
  const library = path.join(dir, 'out');
  const missing = ASSETS.filter((a) => !fs.existsSync(path.join(library, a, 'rock.glb')));
  if (status !== 1 || missing.length) {
    throw new Error(`review_load: the library bake with ${baker} exited ${status} without ${missing.join(', ') || 'nothing'} ` +
                    '(it should fail one job only; is ROCKBAKE_DATA_DIR set?)');
  }
  fs.writeFileSync(path.join(library, BIG_FILE), crypto.randomBytes(BIG_SIZE));
  console.log(`library baked with ${baker} in ${((performance.now() - t0) / 1000).toFixed(1)} s`);
  for (const [i, rockbake] of rockbakes.entries()) {
    const copy = path.join(dir, `review-${i}`);
    fs.cpSync(library, copy, { recursive: true });
    console.log(`== ${rockbake}`);
    const r = await run(rockbake, copy);
    console.log(`RSS idle at start ${r.rss_start_mib.toFixed(0)} MiB, peak over the run ` +
                `${Math.max(...r.results.map((p) => p.rss_peak_mib)).toFixed(0)} MiB, at the end ` +
                `${r.results[r.results.length - 1].rss_after_mib.toFixed(0)} MiB`);
    runs.push(r);
  }
} finally {
  fs.rmSync(dir, { recursive: true, force: true });
}
if (jsonFile) fs.writeFileSync(jsonFile, JSON.stringify({ baker, runs }, null, 2));
process.exit(0);  // requests a starved server never answered are still open
