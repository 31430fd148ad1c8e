// Shared by the studio tests: a scratch copy of a preset folder, a studio
// server on a free port, raw HTTP requests (paths sent exactly as written),
// and a bake to compare with.
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// Polls `predicate` every 100 ms until it returns something truthy, which it returns; throws
// naming `what` after `seconds`.
export async function until(what, predicate, seconds) {
  const end = Date.now() + seconds * 1000;
  for (;;) {
    const value = await predicate();
    if (value) return value;
    if (Date.now() > end) throw new Error(`FAILED: timed out waiting for ${what}`);
    await sleep(100);
  }
}

export function check(condition, message) {
  if (!condition) throw new Error(`FAILED: ${message}`);
  console.log(`ok: ${message}`);
}

// presets/goblin.yaml with base.yaml and its shape, in a fresh folder (save writes beside the preset).
// `time` (optional) replaces the preset's time, for a run long enough to edit while it plays.
export function presetFolder(sourceDir, time) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'rockbake-studio-'));
  for (const f of ['goblin.yaml', 'base.yaml']) fs.copyFileSync(path.join(sourceDir, 'presets', f), path.join(dir, f));
  if (time !== undefined) {
    const file = path.join(dir, 'goblin.yaml');
    const text = fs.readFileSync(file, 'utf8');
    if (!/^time: .*$/m.test(text)) throw new Error('goblin.yaml has no time line to replace');
    fs.writeFileSync(file, text.replace(/^time: .*$/m, `time: ${time}`));
  }
  fs.mkdirSync(path.join(dir, 'shapes'));
  fs.copyFileSync(path.join(sourceDir, 'presets', 'shapes', 'goblin.png'), path.join(dir, 'shapes', 'goblin.png'));
  return dir;
}

export async function startStudio(rockbake, args) {
  const child = spawn(rockbake, ['studio', ...args, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  let stderr = '';
  child.stderr.on('data', (d) => { stderr += d; });
  const url = await new Promise((resolve, reject) => {
    let out = '';
    const timer = setTimeout(() => reject(new Error(`no studio URL within 60 s; stderr: ${stderr}`)), 60000);
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/studio: (http:\/\/127\.0\.0\.1:\d+\/)/);
      if (m) { clearTimeout(timer); resolve(m[1]); }
    });
    child.on('exit', (code) => reject(new Error(`studio exited (${code}) before listening: ${stderr}`)));
  });
  return { child, url, stderr: () => stderr };
}

// Ctrl-C; resolves with the exit code (rejects if it does not stop within 20 s).
export function stopStudio(studio) {
  return new Promise((resolve, reject) => {
    if (studio.child.exitCode !== null) { resolve(studio.child.exitCode); return; }
    const timer = setTimeout(() => { studio.child.kill('SIGKILL'); reject(new Error('studio did not stop on SIGINT')); }, 20000);
    studio.child.on('exit', (code, signal) => { clearTimeout(timer); resolve(code ?? signal); });
    studio.child.kill('SIGINT');
  });
}

// An HTTP request with the path sent byte for byte (no URL normalisation).
export function raw(url, method, rawPath, body, headers = {}) {
  const u = new URL(url);
  return new Promise((resolve, reject) => {
    const req = http.request({ host: u.hostname, port: u.port, method, path: rawPath, headers }, (res) => {
      const chunks = [];
      res.on('data', (c) => chunks.push(c));
      res.on('end', () => resolve({ status: res.statusCode, headers: res.headers, body: Buffer.concat(chunks) }));
    });
    req.on('error', reject);
    if (body !== undefined) req.write(body);
    req.end();
  });
}

export async function api(url, apiPath, body) {
  const r = await raw(url, body === undefined ? 'GET' : 'POST', apiPath,
    body === undefined ? undefined : JSON.stringify(body), { 'Content-Type': 'application/json' });
  const text = r.body.toString();
  let json = null;
  try { json = JSON.parse(text); } catch { /* binary */ }
  return { status: r.status, json, body: r.body };
}

// `rockbake bake PRESET --no-mesh --resolution R`; the rock.vdb bytes.
export function bakeVdb(rockbake, preset, resolution, outDir) {
  const r = spawnSync(rockbake, ['bake', preset, '--no-mesh', '--resolution', String(resolution), '-o', outDir],
    { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`bake failed (${r.status}): ${r.stderr}`);
  const name = path.basename(preset, '.yaml');
  return fs.readFileSync(path.join(outDir, name, 'rock.vdb'));
}

// A POST over a bare socket that keeps whatever the server answers even when it
// closes the connection before reading the whole body (as it may for a body
// over its limit); resolves with {status, body}.
export function rawPost(url, rawPath, body) {
  const u = new URL(url);
  return new Promise((resolve) => {
    const socket = net.connect(Number(u.port), u.hostname);
    const chunks = [];
    socket.on('data', (c) => chunks.push(c));
    socket.on('error', () => {});  // EPIPE / ECONNRESET once the server has answered and closed
    socket.on('close', () => {
      const text = Buffer.concat(chunks).toString();
      const status = Number((text.match(/^HTTP\/1\.[01] (\d{3})/) || [])[1] || 0);
      resolve({ status, body: text.slice(text.indexOf('\r\n\r\n') + 4) });
    });
    socket.write(`POST ${rawPath} HTTP/1.1\r\nHost: ${u.host}\r\nContent-Type: application/json\r\n` +
                 `Content-Length: ${Buffer.byteLength(body)}\r\nConnection: close\r\n\r\n`);
    // Not end(): a half-closed socket reads to the server as a client that left, and it would not answer.
    socket.write(body);
  });
}
