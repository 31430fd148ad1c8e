// Shared by the review tests: a small baked library (two presets × two seeds
// with three-frame turntables, and one job that fails), a review server on a
// free port, and raw HTTP requests.
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

export { api, check, raw, sleep, until } from '../studio/harness.mjs';

// The C++ tests' small preset (tests/data/small.yaml), tagged, with small renders.
const SMALL = fs.readFileSync(new URL('../data/small.yaml', import.meta.url), 'utf8') +
  'tags: [test]\nrender: {width: 96, height: 72, antialias: 0, turntable: {frames: 3}}\n';

// Writes the presets and the library file into `dir`; `time` changes the
// presets' inputs (a re-bake with another input hash).
export function writeLibrary(dir, time = 0.5) {
  const small = SMALL.replace('time: 0.5', `time: ${time}`);
  fs.writeFileSync(path.join(dir, 'small.yaml'), small);
  fs.writeFileSync(path.join(dir, 'tall.yaml'),
    small.replace('name: small', 'name: tall').replace('[1.5, 1.5, 1.5]', '[1.0, 1.0, 1.8]').replace('[test]', '[test, tall]') +
    'texture: {size: 256}\n');  // a texture set: the viewer's maps and the texel density
  fs.writeFileSync(path.join(dir, 'broken.yaml'),
    small.replace('name: small', 'name: broken').replace('box: {size: [1.5, 1.5, 1.5]}', 'image: {path: missing.png, mode: extrude, height: 1.0}'));
  fs.writeFileSync(path.join(dir, 'lib.yaml'),
    '- {preset: small.yaml, seeds: [1, 2]}\n- {preset: tall.yaml, seeds: [1, 2]}\n- {preset: broken.yaml, seeds: [1]}\n');
}

export function bakeLibrary(rockbake, dir) {
  const r = spawnSync(rockbake, ['library', path.join(dir, 'lib.yaml'), '-o', path.join(dir, 'out'), '--jobs', '2'],
    { encoding: 'utf8' });
  return r.status;
}

export function makeLibrary(rockbake) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'rockbake-review-'));
  writeLibrary(dir);
  const status = bakeLibrary(rockbake, dir);
  if (status !== 1) throw new Error(`the library bake should fail one job and exit 1, got ${status}`);
  return dir;
}

export async function startReview(rockbake, out, extra = []) {
  const child = spawn(rockbake, ['review', out, '--port', '0', ...extra], { stdio: ['ignore', 'pipe', 'pipe'] });
  let stderr = '';
  child.stderr.on('data', (d) => { stderr += d; });
  const url = await new Promise((resolve, reject) => {
    let text = '';
    const timer = setTimeout(() => reject(new Error(`no review URL within 30 s; stderr: ${stderr}`)), 30000);
    child.stdout.on('data', (d) => {
      text += d;
      const m = text.match(/review: (http:\/\/127\.0\.0\.1:\d+\/)/);
      if (m) { clearTimeout(timer); resolve(m[1]); }
    });
    child.on('exit', (code) => reject(new Error(`review exited (${code}) before listening: ${stderr}`)));
  });
  return { child, url, stderr: () => stderr };
}

export function stopReview(review) {
  return new Promise((resolve, reject) => {
    if (review.child.exitCode !== null) { resolve(review.child.exitCode); return; }
    const timer = setTimeout(() => { review.child.kill('SIGKILL'); reject(new Error('review did not stop on SIGINT')); }, 20000);
    review.child.on('exit', (code, signal) => { clearTimeout(timer); resolve(code ?? signal); });
    review.child.kill('SIGINT');
  });
}

// The share of pixels in a viewer's model screen box that differ from the page's background:
// `which` is 'asset' (the asset's view) or 'left' / 'right' (the comparison's two views).
export function coverage(page, which = 'asset') {
  return page.evaluate((which) => {
    const views = window.reviewViewers();
    const viewer = which === 'asset' ? views.asset : views.compare[which === 'left' ? 0 : 1];
    const box = viewer.screenBox();
    const c = document.createElement('canvas');
    c.width = viewer.canvas.width; c.height = viewer.canvas.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(viewer.canvas, 0, 0);
    const w = box.x1 - box.x0, h = box.y1 - box.y0;
    if (w < 4 || h < 4) return 0;
    const px = ctx.getImageData(box.x0, box.y0, w, h).data;
    let differ = 0;
    for (let i = 0; i < px.length; i += 4)
      if (Math.abs(px[i] - 0x2e) + Math.abs(px[i + 1] - 0x2e) + Math.abs(px[i + 2] - 0x2e) > 12) ++differ;
    return differ / (w * h);
  }, which);
}
