// A load test of the studio's server (docs/studio.md, "The server's promises"),
// loopback only, bounded in count and time, stopping by itself (about a minute
// against a server that keeps its promises, at most about three against one
// that does not): many concurrent clients, slow clients (half-sent and
// trickling requests), oversized headers and large bodies, each beside a
// "probe" client that asks GET /api/state as the page does, twice a second.
// The probe is the page (127.0.0.1); the load comes from another loopback
// address (127.0.0.2), one client to the server's per-client limits. Prints, per phase, how long the probes waited (median and worst), what the
// load's own requests got, and the studio's resident memory (peak, and after).
// Usage: node bench/studio_load.mjs ROCKBAKE [SOURCE_DIR] [--json FILE]
import fs from 'node:fs';
import http from 'node:http';
import net from 'node:net';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { api, presetFolder, startStudio, stopStudio } from '../tests/studio/harness.mjs';
import { LOAD_ADDRESS, runPhase, sleep, slowClient, timed } from './load_probe.mjs';

const args = process.argv.slice(2);
const jsonAt = args.indexOf('--json');
const jsonFile = jsonAt >= 0 ? args.splice(jsonAt, 2)[1] : null;
const [rockbake, sourceDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..')] = args;
if (!rockbake) {
  console.error('usage: node bench/studio_load.mjs ROCKBAKE [SOURCE_DIR] [--json FILE]');
  process.exit(2);
}


// A request of the load (from LOAD_ADDRESS); resolves with its status.
function loadRequest(url, apiPath, body) {
  const u = new URL(url);
  return new Promise((resolve, reject) => {
    const request = http.request({ host: u.hostname, port: u.port, localAddress: LOAD_ADDRESS, path: apiPath,
      method: body === undefined ? 'GET' : 'POST', headers: { 'Content-Type': 'application/json' } }, (res) => {
      res.resume();
      res.on('end', () => resolve({ status: res.statusCode }));
    });
    request.on('error', reject);
    if (body !== undefined) request.write(JSON.stringify(body));
    request.end();
  });
}

// A POST of `body` over a bare socket from LOAD_ADDRESS, keeping the answer of a
// server that closes before reading it all (as it may past its body limit).
function loadPost(port, apiPath, body) {
  return new Promise((resolve) => {
    const socket = net.connect({ port, host: '127.0.0.1', localAddress: LOAD_ADDRESS });
    let text = '';
    socket.on('data', (c) => { text += c.toString('latin1'); });
    socket.on('error', () => {});
    socket.on('close', () => resolve({ status: Number((text.match(/^HTTP\/1\.[01] (\d{3})/) || [])[1] || 0) }));
    socket.write(`POST ${apiPath} HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\nContent-Type: application/json\r\n` +
                 `Content-Length: ${Buffer.byteLength(body)}\r\nConnection: close\r\n\r\n`);
    socket.write(body);
  });
}
const PHASE_LIMIT_MS = 60000;  // a phase's load is abandoned after this (it says so)





const tally = (statuses) => {
  const counts = {};
  for (const s of statuses) counts[s] = (counts[s] || 0) + 1;
  return Object.entries(counts).map(([s, n]) => `${n}×${s === '0' ? 'no answer' : s === '-1' ? 'error' : s}`).join(' ');
};

// A phase against this server: its page's probe, its own limit and tally.
function phase(name, studio, load) {
  return runPhase(name, { pid: studio.child.pid, ask: () => api(studio.url, '/api/state'), load, limitMs: PHASE_LIMIT_MS,
    limitLine: 'phase time limit', tally });
}

const dir = presetFolder(sourceDir);
const studio = await startStudio(rockbake, [path.join(dir, 'goblin.yaml'), '--resolution', '24', '-o', path.join(dir, 'out')]);
const port = Number(new URL(studio.url).port);
// The whole run stops by itself whatever the server does.
setTimeout(() => { console.error('studio_load: over 6 minutes; stopped'); studio.child.kill('SIGKILL'); process.exit(1); }, 360000).unref();
const results = [];
try {
  await api(studio.url, '/api/control', { action: 'step' });
  await sleep(300);
  results.push(await phase('idle', studio, () => sleep(3000).then(() => [])));

  // 64 clients at once, 8 requests each: state, mesh and small edits-free controls.
  results.push(await phase('64 concurrent clients × 8 requests', studio, async () => {
    const client = async (i) => {
      const out = [];
      for (let k = 0; k < 8; ++k) {
        const which = (i + k) % 4;
        const send = which === 0 ? () => loadRequest(studio.url, '/api/mesh?palette=natural')
                   : which === 1 ? () => loadRequest(studio.url, '/api/control', { seek: 0.0625 * (1 + ((i + k) % 3)) })
                   : () => loadRequest(studio.url, '/api/state');
        out.push((await timed(send)).status);
      }
      return out;
    };
    return (await Promise.all(Array.from({ length: 64 }, (_, i) => client(i)))).flat();
  }));

  // 100 requests half sent and held for 20 s.
  results.push(await phase('100 half-sent requests held 20 s', studio, () =>
    Promise.all(Array.from({ length: 100 }, () =>
      slowClient(port, `GET /api/state HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\nX-Half: `, { holdMs: 20000 })))));

  // 10 requests that trickle a byte every 2 s (each ~40 bytes: 80 s if never cut off; held at most 24 s).
  results.push(await phase('10 requests trickling a byte every 2 s', studio, () =>
    Promise.all(Array.from({ length: 10 }, () =>
      slowClient(port, `GET /api/state HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\n\r\n`, { everyMs: 2000, holdMs: 24000 })))));

  // One client sending 60 MB of headers (a line of 1 KB at a time, stopping when answered).
  results.push(await phase('60 MB of headers', studio, () => new Promise((resolve) => {
    const socket = net.connect({ port, host: '127.0.0.1', localAddress: LOAD_ADDRESS });
    let text = '', sent = 0;
    socket.on('error', () => {});
    socket.on('data', (c) => { text += c.toString('latin1'); });
    const line = `X-Pad: ${'a'.repeat(1000)}\r\n`;
    let finished = false;
    const finish = () => {
      if (finished) return;
      finished = true;
      const status = Number((text.match(/^HTTP\/1\.1 (\d{3})/) || [])[1] || 0);
      const cut = `closed after ${(sent / 1024).toFixed(0)} KiB`;
      setTimeout(() => { socket.destroy(); resolve([status ? `${status} (${cut})` : cut]); }, 2000);
    };
    socket.on('close', finish);  // a server that refuses closes it: no 'drain' comes after that
    const pump = () => {
      while (sent < 60e6 && !text && !socket.destroyed) {
        sent += line.length;
        if (!socket.write(line)) { socket.once('drain', pump); return; }
      }
      if (!socket.destroyed && !text && sent >= 60e6) socket.write('\r\n');
      finish();
    };
    socket.on('connect', () => { socket.write(`GET /api/state HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\n`); pump(); });
  })));

  // 16 clients at once, 4 bodies each: 2 MB (over the limit) and 900 KB of JSON the edit refuses.
  results.push(await phase('64 large bodies (2 MB and 900 KB), 16 at a time', studio, async () => {
    const big = 'x'.repeat(2 * 1024 * 1024);
    const json = JSON.stringify({ pad: 'y'.repeat(900 * 1024) });
    const client = async (i) => {
      const out = [];
      for (let k = 0; k < 4; ++k)
        out.push((await timed(() => loadPost(port, '/api/edit', (i + k) % 2 ? big : json))).status);
      return out;
    };
    return (await Promise.all(Array.from({ length: 16 }, (_, i) => client(i)))).flat();
  }));
  results.push(await phase('idle after', studio, () => sleep(3000).then(() => [])));
} finally {
  const code = await Promise.race([stopStudio(studio).catch(() => 'killed'), sleep(25000).then(() => 'killed')]);
  if (code === 'killed') studio.child.kill('SIGKILL');
  fs.rmSync(dir, { recursive: true, force: true });
}
if (jsonFile) fs.writeFileSync(jsonFile, JSON.stringify({ rockbake, results }, null, 2));
process.exit(0);  // requests a starved server never answered are still open
