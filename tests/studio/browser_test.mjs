// The studio page in a real browser (Debian's chromium, headless, driven by
// puppeteer-core): the 3-D view draws the rock, a durability point dragged
// while the rock weathers becomes a keyframe, run to a time, save from the
// page; then `bake --no-mesh` of the saved preset equals GET /api/rock.vdb; Bake final from the
// page, and the final view draws its LOD0 with its maps and the look's History.
// Usage: node browser_test.mjs ROCKBAKE SOURCE_DIR [SCREENSHOT.png] [RESOLUTION]
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';
import { api, bakeVdb, check, presetFolder, sleep, startStudio, stopStudio, until as waitFor } from './harness.mjs';

const [rockbake, sourceDir, screenshotArg, resolutionArg] = process.argv.slice(2);
// puppeteer-core is pinned by studio/package-lock.json and installed there by scripts/setup.sh.
const puppeteer = createRequire(path.join(sourceDir, 'studio', 'package.json'))('puppeteer-core');
const resolution = Number(resolutionArg || 32);
const dir = presetFolder(sourceDir, 12);  // long enough to edit while it plays
const screenshot = screenshotArg || path.join(dir, 'studio.png');
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'rockbake-chromium-'));
const studio = await startStudio(rockbake, [path.join(dir, 'goblin.yaml'), '--resolution', String(resolution), '-o', path.join(dir, 'final')]);
const url = studio.url;
let passed = 0;
let failure = null;
const ok = (condition, message) => { check(condition, message); ++passed; };
const until = (what, predicate, seconds = 60) => waitFor(what, predicate, seconds);

// The share of the view's pixels that differ from its background in the rock's screen box
// (`rock`: the final bake's when it is shown) or in a strip of sky along the view's top (`sky`).
const differing = (page, region) => page.evaluate((region) => {
  const box = window.studio.rockScreenBox();
  const gl = document.querySelector('#view canvas');
  const r = gl.getBoundingClientRect();
  const c = document.createElement('canvas');
  c.width = gl.width; c.height = gl.height;
  const ctx = c.getContext('2d');
  ctx.drawImage(gl, 0, 0);
  const sx = gl.width / r.width, sy = gl.height / r.height;
  const bg = [parseInt(box.background.slice(1, 3), 16), parseInt(box.background.slice(3, 5), 16), parseInt(box.background.slice(5, 7), 16)];
  const [x0, y0, x1, y1] = region === 'sky' ? [r.left, r.top, r.right, r.top + 30] : [box.x0, box.y0, box.x1, box.y1];
  const X0 = Math.max(0, Math.round((x0 - r.left) * sx)), Y0 = Math.max(0, Math.round((y0 - r.top) * sy));
  const X1 = Math.min(gl.width, Math.round((x1 - r.left) * sx)), Y1 = Math.min(gl.height, Math.round((y1 - r.top) * sy));
  const d = ctx.getImageData(X0, Y0, X1 - X0, Y1 - Y0).data;
  let differ = 0;
  for (let i = 0; i < d.length; i += 4)
    if (Math.abs(d[i] - bg[0]) + Math.abs(d[i + 1] - bg[1]) + Math.abs(d[i + 2] - bg[2]) > 30) ++differ;
  return differ / (d.length / 4);
}, region);

const browser = await puppeteer.launch({
  executablePath: '/usr/bin/chromium',
  headless: true,
  args: ['--headless=new', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
         '--disable-component-update', '--no-first-run', `--user-data-dir=${profile}`],
});
try {
  const page = await browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('requestfailed', (r) => errors.push(`request failed: ${r.url()}`));
  page.on('request', (r) => { if (!r.url().startsWith(url) && !r.url().startsWith('data:')) errors.push(`outside request: ${r.url()}`); });
  await page.setViewport({ width: 1400, height: 860 });
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForFunction(() => window.studio && window.studio.ready && window.studio.rockTriangles > 0, { timeout: 60000 });
  await sleep(300);
  ok(errors.length === 0, `the page loads with no errors and no request outside the studio (${errors.join('; ')})`);

  // The 3-D view draws the rock: inside the rock's screen box most pixels differ from the background.
  const coverage = { rock: await differing(page, 'rock'), sky: await differing(page, 'sky') };
  ok(coverage.rock > 0.3 && coverage.sky < 0.05,
    `the 3-D view draws the rock (${(100 * coverage.rock).toFixed(0)}% of its box differs from the background, sky ${(100 * coverage.sky).toFixed(0)}%)`);

  // The default pace leaves time to steer: play plays the preset's whole run in 30 s.
  ok(await page.$eval('#rate', (e) => e.value) === 'steer', 'the rate menu starts at the steering pace');
  await page.click('#play');
  const steering = await until('play at the default pace', async () => {
    const s = (await api(url, '/api/state')).json;
    return s.playing ? s : null;
  }, 20);
  const runCycles = Math.round(steering.end_time / steering.h);
  ok(Math.abs(steering.rate - Math.max(0.5, Math.round((100 * runCycles) / 30) / 100)) < 1e-9,
    `the default pace runs the ${runCycles} cycles in about 30 s (${steering.rate} cycles/s)`);

  // Then at 5 cycles a second, drag a durability point while it runs.
  await page.waitForFunction(() => document.querySelector('#play').textContent === 'pause', { timeout: 20000 });
  await page.select('#rate', '5');  // slow enough that the drag lands while it plays, on a busy machine too
  await until('a few cycles', async () => (await api(url, '/api/state')).json.cycle >= 3);
  const before = (await api(url, '/api/state')).json;
  ok(before.playing, 'play runs the simulation');
  const p = await page.evaluate(() => window.studio.durabilityPointPage(1));
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  for (let i = 1; i <= 8; ++i) { await page.mouse.move(p.x - 3 * i, p.y + 2 * i); await sleep(30); }
  await page.mouse.up();
  const edited = await until('the drag to reach the server', async () => {
    const s = (await api(url, '/api/state')).json;
    return s.preset.durability.keyframes.length >= 1 ? s : null;
  }, 20);
  const keyframe = edited.preset.durability.keyframes[0];
  ok(keyframe.at > 0 && keyframe.points[1][1] < before.active.durability.points[1][1],
    `dragging point 1 left while running made a keyframe at t = ${keyframe.at} with durability ${keyframe.points[1][1]} (was ${before.active.durability.points[1][1]})`);
  ok(edited.playing, 'the simulation carries on after the edit');

  // Run to a time from the page.
  const target = Math.round((keyframe.at + 0.5) * 100) / 100;
  await page.$eval('#run-until', (e, t) => { e.value = String(t); }, target);
  await page.click('#run-until-go');
  const reached = await until('run until', async () => {
    const s = (await api(url, '/api/state')).json;
    return !s.playing && s.time >= target - 1e-9 ? s : null;
  });
  ok(reached.time < target + reached.h, `run until ${target} stops at t = ${reached.time}`);
  await page.waitForFunction((v) => window.studio.meshVersion === v, { timeout: 30000 }, reached.mesh_version);

  // Save from the page.
  await page.$eval('#save-name', (e) => { e.value = 'goblin-studio'; });
  await page.click('#save');
  await page.waitForFunction(() => document.querySelector('#message').textContent.startsWith('saved'), { timeout: 30000 });
  const savedFile = path.join(dir, 'goblin-studio.yaml');
  ok(fs.existsSync(savedFile), 'save from the page writes goblin-studio.yaml beside the preset');
  await sleep(400);
  await page.screenshot({ path: screenshot });
  ok(fs.statSync(screenshot).size > 10000, `screenshot written to ${screenshot}`);

  const studioVdb = (await api(url, '/api/rock.vdb')).body;
  const baked = bakeVdb(rockbake, savedFile, resolution, path.join(dir, 'out'));
  ok(studioVdb.length > 1000 && Buffer.compare(studioVdb, baked) === 0,
    `bake --no-mesh --resolution ${resolution} of the saved preset equals GET /api/rock.vdb byte for byte (${baked.length} bytes)`);

  // The final view: unavailable until a bake finishes, then the bake's LOD0 with its look.
  ok(await page.$eval('#view-mode option[value="final"]', (e) => e.disabled), 'the final view waits for a final bake');
  await page.click('#bake');
  await page.waitForFunction(() => document.querySelector('#bake-status').textContent.startsWith('done'), { timeout: 240000 });
  await page.waitForFunction(() => !document.querySelector('#view-mode option[value="final"]').disabled, { timeout: 10000 });
  const live = await page.evaluate(() => window.studio.rockScreenBox());
  await page.select('#view-mode', 'final');
  await page.waitForFunction(() => window.studio.finalView.shown > 0, { timeout: 60000 });
  await sleep(300);
  const view = await page.evaluate(() => window.studio.finalView);
  ok(view.triangles > 10000 && view.textured && view.history,
    `the final view shows the bake's LOD0 (${view.triangles} triangles) with its maps (${view.textured}) and the look's History (${view.history})`);
  await page.screenshot({ path: screenshot.replace(/\.png$/, '-final.png') });
  const finalBox = await page.evaluate(() => window.studio.rockScreenBox());
  const overlap = Math.max(0, Math.min(live.x1, finalBox.x1) - Math.max(live.x0, finalBox.x0)) *
    Math.max(0, Math.min(live.y1, finalBox.y1) - Math.max(live.y0, finalBox.y0));
  const area = (b) => (b.x1 - b.x0) * (b.y1 - b.y0);
  // The view stands the bake's rock on the live rock's footprint, so this checks what the GLB
  // brings: its size in metres back in world units, and y-up turned to z-up.
  ok(overlap > 0.6 * Math.max(area(live), area(finalBox)),
    `the final bake shows at the live rock's size and upright (screen boxes overlap ${(100 * overlap / Math.max(area(live), area(finalBox))).toFixed(0)}%)`);
  const drawn = await differing(page, 'rock');
  ok(drawn > 0.3, `the final view draws the rock (${(100 * drawn).toFixed(0)}% of its box differs from the background)`);
  ok(errors.length === 0, `the final view loads with no errors and no request outside the studio (${errors.join('; ')})`);
} catch (e) {
  failure = e;
}
await browser.close();
const code = await stopStudio(studio);
fs.rmSync(profile, { recursive: true, force: true });
if (failure) {
  console.error(failure.stack);
  console.error(`studio's log:\n${studio.stderr()}`);
  process.exit(1);
}
check(code === 0, `Ctrl-C stops the studio cleanly (exit ${code})`);
fs.rmSync(dir, { recursive: true, force: true });
console.log(`${passed + 1} passed, 0 failed`);
