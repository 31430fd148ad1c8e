// The studio's server against other web pages and unlucky clients (docs/studio.md,
// "The server's promises"), through the real rockbake and real sockets: who may
// call, nesting, client errors, header and body limits, slow and many clients,
// bounded checkpoints, running out of memory, no temporary folder, and presets
// that are FIFOs, devices or huge sparse files. Each check names the promise it
// holds the server to; a server without that promise fails it.
// Usage: node hardening_test.mjs ROCKBAKE SOURCE_DIR
import fs from 'node:fs';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { api, check, presetFolder, raw, rawPost, startStudio, stopStudio } from './harness.mjs';

const [rockbake, sourceDir] = process.argv.slice(2);
const dir = presetFolder(sourceDir, 6);
const preset = path.join(dir, 'goblin.yaml');
let passed = 0;
const ok = (condition, message) => { check(condition, message); ++passed; };
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const rssMiB = (pid) => Number(fs.readFileSync(`/proc/${pid}/status`, 'utf8').match(/VmRSS:\s+(\d+)/)[1]) / 1024;
const vmSizeKiB = (pid) => Number(fs.readFileSync(`/proc/${pid}/status`, 'utf8').match(/VmSize:\s+(\d+)/)[1]);

// A connection that sends `bytes` (now, or a byte at a time every `everyMs`) and
// collects whatever comes back; `answer` resolves when the server closes it.
function slowClient(url, bytes, everyMs = 0) {
  const u = new URL(url);
  const socket = net.connect(Number(u.port), u.hostname);
  const chunks = [];
  let at = 0, timer = null, answeredAt = null;
  socket.on('error', () => {});
  socket.on('data', (c) => { chunks.push(c); answeredAt ??= Date.now(); });
  const answer = new Promise((resolve) => socket.on('close', () => {
    clearInterval(timer);
    const text = Buffer.concat(chunks).toString();
    resolve({ status: Number((text.match(/^HTTP\/1\.1 (\d{3})/) || [])[1] || 0), body: text.slice(text.indexOf('\r\n\r\n') + 4) });
  }));
  socket.on('connect', () => {
    if (!everyMs) { socket.write(bytes); return; }
    timer = setInterval(() => { if (at < bytes.length && !socket.destroyed) socket.write(bytes[at++]); }, everyMs);
  });
  return { socket, answer, answered: () => answeredAt !== null, close: () => { clearInterval(timer); socket.destroy(); } };
}

// ---- special files: refused at once, as lint refuses them
// Under a 2 GB address-space limit and killed after 30 s, so that a studio
// without the check fails this test instead of hanging on the FIFO or taking
// the machine's memory on /dev/zero.
function studioOn(file) {
  return spawnSync('bash', ['-c', 'ulimit -v 2000000; exec "$0" studio "$1" --port 0', rockbake, file],
    { encoding: 'utf8', timeout: 30000, killSignal: 'SIGKILL' });
}
const fifo = path.join(dir, 'fifo.yaml');
spawnSync('mkfifo', [fifo]);
const sparse = path.join(dir, 'sparse.yaml');
fs.closeSync(fs.openSync(sparse, 'w'));
fs.truncateSync(sparse, 2 * 1024 ** 3);
for (const [what, file] of [['a FIFO', fifo], ['/dev/zero', '/dev/zero'], ['a 2 GB sparse file', sparse]]) {
  const r = studioOn(file);
  ok(r.status === 2 && r.stderr.includes(file) && !r.error,
    `rockbake studio on ${what} exits 2 at once naming it (${r.error ? 'timed out' : r.status}: ${r.stderr.trim()})`);
}

const studio = await startStudio(rockbake, [preset, '--resolution', '24', '-o', path.join(dir, 'out')]);
const url = studio.url, port = new URL(url).port, pid = studio.child.pid;
let failure = null;
try {
  const cycle = async () => (await api(url, '/api/state')).json.cycle;
  const start = await cycle();

  // ---- who may call
  const json = { 'Content-Type': 'application/json' };
  const step = JSON.stringify({ action: 'step' });
  let r = await raw(url, 'POST', '/api/control', step, { ...json, Origin: 'http://evil.example' });
  ok(r.status === 403 && (await cycle()) === start, `a POST from another page's Origin is refused (${r.status}) and runs nothing`);
  r = await raw(url, 'POST', '/api/control', step, { 'Content-Type': 'text/plain' });
  ok(r.status === 415 && (await cycle()) === start, `a text/plain POST (what a page may send unasked) is refused (${r.status})`);
  r = await raw(url, 'POST', '/api/control', step, {});
  ok(r.status === 415, `a POST without Content-Type is refused (${r.status})`);
  r = await raw(url, 'GET', '/api/state', undefined, { Host: `rebound.example:${port}` });
  ok(r.status === 403 && !r.body.toString().includes('"preset"'), `a foreign Host (DNS rebinding) reads nothing (${r.status})`);
  r = await raw(url, 'OPTIONS', '/api/edit', undefined, { Origin: 'http://evil.example', 'Access-Control-Request-Method': 'POST' });
  ok(r.status === 403 && !r.headers['access-control-allow-origin'], `a CORS preflight from another page is refused (${r.status})`);
  r = await raw(url, 'POST', '/api/control', step, { ...json, Origin: url.replace(/\/$/, '') });
  ok(r.status === 200 && (await cycle()) === start + 1, 'the studio\'s own page may POST');
  r = await raw(url, 'GET', '/api/state', undefined, { Host: `localhost:${port}` });
  ok(r.status === 200, 'localhost with the port is the studio too');

  // ---- one request must not kill it
  // A bare array, and a bubble graph (the previous build's edit recursed into it: SIGSEGV).
  for (const deep of ['['.repeat(100000) + ']'.repeat(100000), `{"bubbles": ${'['.repeat(100000)}${']'.repeat(100000)}}`]) {
    r = await raw(url, 'POST', '/api/edit', deep, json);
    ok(r.status === 400 && r.body.toString() === '{"error":"the request body nests deeper than 64 levels"}',
      `a well-formed ${(deep.length / 1024).toFixed(0)} KiB body nested 100 000 levels deep gets 400 without its text (${r.status} ${r.body.toString().slice(0, 80)})`);
    ok((await api(url, '/api/state')).status === 200, 'still serving after the nested body');
  }

  // ---- client errors are 4xx with a message, never 500 or raw library text
  const refusals = [
    ['invalid UTF-8 in the path', () => raw(url, 'GET', '/%ff%fe'), 404],
    ['a wrong JSON type', () => api(url, '/api/save', { name: 'x', overwrite: 'yes' }), 400],
    ['a seek to a string', () => api(url, '/api/control', { seek: '5' }), 400],
    ['a play rate that is not a number', () => api(url, '/api/control', { action: 'play', rate: 'fast' }), 400],
    ['a NUL in a save name', () => api(url, '/api/save', { name: 'a\u0000b' }), 400],
    ['a NUL in an edited key', () => api(url, '/api/edit', { 'dura\u0000bility': {} }), 400],
    ['a save name starting with -', () => api(url, '/api/save', { name: '-rf' }), 400],
    ['a name of invalid UTF-8', () => raw(url, 'POST', '/api/save', Buffer.from([...Buffer.from('{"name": "'), 0xff, ...Buffer.from('"}')]), json), 400],
  ];
  for (const [what, send, status] of refusals) {
    const answer = await send();
    const text = answer.body.toString();
    let message = '';
    try { message = JSON.parse(text).error; } catch { /* checked below */ }
    ok(answer.status === status && message && !/json\.exception|std::|basic_string/.test(message) && !text.includes('\u0000'),
      `${what}: ${answer.status} ${JSON.stringify(message)}`);
  }
  ok(!fs.existsSync(path.join(dir, '-rf.yaml')), 'nothing named -rf.yaml was written');

  // ---- headers: bounded in count and size, refused before they are kept
  let many = `GET /api/state HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\n`;
  for (let i = 0; i < 100; ++i) many += `X-${i}: 1\r\n`;
  r = await slowClient(url, `${many}\r\n`).answer;
  ok(r.status === 431, `100 headers get 431 (${r.status} ${r.body})`);
  const before = rssMiB(pid);
  const flood = slowClient(url, '');
  flood.socket.write(`GET /api/state HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\n`);
  const line = `X-Pad: ${'a'.repeat(1000)}\r\n`;
  let sent = 0;
  for (; sent < 60 * 1024 ** 2 && !flood.socket.destroyed && !flood.answered(); sent += line.length) {
    flood.socket.write(line);
    await new Promise((res) => setImmediate(res));  // let the answer in as soon as it comes
  }
  r = await flood.answer;
  ok(r.status === 431 && sent < 60 * 1024 ** 2, `60 MB of headers are cut off with 431 after ${(sent / 1024).toFixed(0)} KiB (${r.status})`);
  ok(rssMiB(pid) - before < 20, `and keep no memory (${before.toFixed(0)} → ${rssMiB(pid).toFixed(0)} MiB)`);
  r = await rawPost(url, '/api/edit', 'x'.repeat(2 * 1024 * 1024));
  ok(r.status === 413 && r.body.includes('at most 1 MiB'), `a 2 MB body gets 413, read by the client (${r.status})`);

  // ---- slow clients hold no worker: 12 trickle a byte every 2 s, 40 more stall half-sent
  const request = `GET /api/state HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\nX-Slow: ${'s'.repeat(40)}\r\n\r\n`;
  const tricklers = Array.from({ length: 12 }, () => slowClient(url, request, 2000));
  await sleep(2500);
  r = await api(url, '/api/state');
  ok(r.status === 200 && tricklers.every((t) => !t.answered()),
    'a request is answered while 12 clients trickle theirs a byte every 2 s');
  const cut = await Promise.all(tricklers.map((t) => t.answer));
  ok(cut.every((a) => a.status === 408 && a.body.includes('did not arrive whole within 10 s')),
    `each trickling request is cut off with 408 when its time is up (${[...new Set(cut.map((a) => a.status))]})`);

  // ---- connections per client: its unfinished requests make way for its new ones
  const stalled = Array.from({ length: 40 }, () => slowClient(url, 'GET /api/state HTTP/1.1\r\nHo'));
  await sleep(500);
  r = await api(url, '/api/state');
  ok(r.status === 200, 'a request is answered beside 40 stalled ones from the same client');
  await sleep(200);
  const dropped = stalled.filter((s) => s.answered()).length;
  ok(dropped >= 40 - 16, `the oldest stalled requests past 16 per client were dropped (${dropped} of 40)`);
  for (const s of stalled) s.close();

  // ---- checkpoints stay bounded however far a seek goes, and reset frees them
  const s0 = (await api(url, '/api/state')).json;
  const far = (s0.planned_cycles + 10000) * s0.h;
  const rssBefore = rssMiB(pid);
  const sought = (await api(url, '/api/control', { seek: far })).json;
  ok(sought.cycle === s0.planned_cycles + 10000 && sought.checkpoints.length <= 32,
    `a seek 10 000 cycles past the end keeps ${sought.checkpoints.length} checkpoints (${(sought.checkpoint_bytes / 1024 ** 2).toFixed(1)} MiB), not one a cycle`);
  ok(rssMiB(pid) - rssBefore < 64, `its memory grew by ${(rssMiB(pid) - rssBefore).toFixed(0)} MiB`);
  const reset = (await api(url, '/api/control', { action: 'reset' })).json;
  ok(reset.cycle === 0 && reset.checkpoints.length === 1, `reset keeps time 0's checkpoint alone (${reset.checkpoints.length})`);

  // ---- no temporary folder: rock.vdb is written from memory
  r = await api(url, '/api/rock.vdb');
  ok(r.status === 200 && !fs.existsSync(path.join(os.tmpdir(), `rockbake-studio-${pid}`)),
    'GET /api/rock.vdb leaves no temporary folder');

  // ---- out of memory: said to the page, and the session carries on
  await api(url, '/api/control', { run_until: 4 * s0.h });
  const soft = (vmSizeKiB(pid) + 40 * 1024) * 1024;  // 40 MiB above its size now: less than a preview may need
  const limited = spawnSync('prlimit', ['--pid', String(pid), `--as=${soft}:`], { encoding: 'utf8' });
  ok(limited.status === 0, `prlimit set the studio's address-space limit (${limited.stderr})`);
  r = await api(url, '/api/mesh?palette=curvature');
  ok(r.status === 503 && /memory/.test(r.json?.error ?? ''), `short of memory, the preview mesh is a 503 that says so (${r.json?.error})`);
  r = await api(url, '/api/state');
  ok(r.status === 200 && r.json.cycle === 4, 'and the session is as it was');
  spawnSync('prlimit', ['--pid', String(pid), '--as=unlimited:']);
  r = await api(url, '/api/mesh?palette=curvature');
  ok(r.status === 200 && r.body.subarray(0, 4).toString() === 'RBPM', 'with memory back, the preview mesh is served');
} catch (e) {
  failure = e;
}
const code = await stopStudio(studio);
if (failure) {
  console.error(failure.stack);
  console.error(`studio's log:\n${studio.stderr()}`);
  process.exit(1);
}
check(code === 0, `Ctrl-C stops the studio cleanly (exit ${code})`);
fs.rmSync(dir, { recursive: true, force: true });
console.log(`${passed + 1} passed, 0 failed`);
