// The review page in a real browser (Debian's chromium, headless, driven by
// puppeteer-core pinned in studio/): the grid shows every asset, a filter
// narrows it, the 3-D view draws the rock, the compare view draws both, a
// verdict set on the page is in review.json. The library's presets have a look:
// the history channels draw the History map (tall, with a texture set) or the
// _HISTORY attribute (small, without), in colours other than the base colour's.
// Usage: node browser_test.mjs ROCKBAKE SOURCE_DIR [SCREENSHOT_DIR]
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';
import { bakeLibrary, check, coverage, sleep, startReview, stopReview, until as waitFor, writeLibrary } from './library.mjs';

const [rockbake, sourceDir, screenshotDir] = process.argv.slice(2);
const puppeteer = createRequire(path.resolve(sourceDir, 'studio', 'package.json'))('puppeteer-core');
// The review tests' library, with a look (docs/textures.md) on both presets that bake.
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'rockbake-review-'));
writeLibrary(dir);
for (const preset of ['small.yaml', 'tall.yaml'])
  fs.appendFileSync(path.join(dir, preset), 'look: {stain: 1, varnish: 1, dust: 1, moisture: 1}\n');
const baked = bakeLibrary(rockbake, dir);
if (baked !== 1) throw new Error(`the library bake should fail one job and exit 1, got ${baked}`);
const out = path.join(dir, 'out');
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'rockbake-chromium-'));
const review = await startReview(rockbake, out);
const url = review.url;
const until = (what, predicate, seconds = 30) => waitFor(what, predicate, seconds);

// The asset view's pixels in the model's screen box, kept in the page as `name`:
// the share drawn (not the background), and of those the share neither near
// black nor grey (coloured) and the share grey (r = g = b within 6).
function snapshot(page, name) {
  return page.evaluate((name) => {
    const viewer = window.reviewViewers().asset;
    const box = viewer.screenBox();
    const c = document.createElement('canvas');
    c.width = viewer.canvas.width; c.height = viewer.canvas.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(viewer.canvas, 0, 0);
    const px = ctx.getImageData(box.x0, box.y0, Math.max(1, box.x1 - box.x0), Math.max(1, box.y1 - box.y0)).data;
    (window.snapshots ??= {})[name] = px;
    let drawn = 0, bright = 0, grey = 0;
    for (let i = 0; i < px.length; i += 4) {
      const [r, g, b] = [px[i], px[i + 1], px[i + 2]];
      if (Math.abs(r - 0x2e) + Math.abs(g - 0x2e) + Math.abs(b - 0x2e) <= 12) continue;
      ++drawn;
      if (r + g + b > 30) ++bright;
      if (Math.abs(r - g) <= 6 && Math.abs(g - b) <= 6) ++grey;
    }
    const n = px.length / 4;
    return { drawn: drawn / n, bright: bright / n, grey: drawn ? grey / drawn : 0 };
  }, name);
}

// Of the pixels drawn in either snapshot, the share that differ by more than 24 (of 255) in some channel.
function differ(page, a, b) {
  return page.evaluate((a, b) => {
    const p = window.snapshots[a], q = window.snapshots[b];
    const bg = (s, i) => Math.abs(s[i] - 0x2e) + Math.abs(s[i + 1] - 0x2e) + Math.abs(s[i + 2] - 0x2e) <= 12;
    let drawn = 0, changed = 0;
    for (let i = 0; i < p.length; i += 4) {
      if (bg(p, i) && bg(q, i)) continue;
      ++drawn;
      if (Math.max(Math.abs(p[i] - q[i]), Math.abs(p[i + 1] - q[i + 1]), Math.abs(p[i + 2] - q[i + 2])) > 24) ++changed;
    }
    return drawn ? changed / drawn : 0;
  }, a, b);
}

// What the asset view's meshes draw the history channel from: the number of meshes
// with the History map, with the vertex attribute, and the others (black).
function historySources(page) {
  return page.evaluate(() => {
    const n = { map: 0, vertex: 0, none: 0 };
    window.reviewViewers().asset.model.traverse((o) => {
      if (!o.isMesh) return;
      if (o.material.map?.name?.endsWith('_History.png')) ++n.map;
      else if (o.geometry.attributes.historyRgba && o.material.vertexColors) ++n.vertex;
      else ++n.none;
    });
    return n;
  });
}

// Checks the history channels of the asset shown against its base colour channel.
async function checkHistory(page, asset, source) {
  await page.select('#a-channel', 'base');
  await sleep(100);
  await snapshot(page, 'base');
  await page.select('#a-channel', 'history');
  await sleep(100);
  const history = await snapshot(page, 'history');
  const from = await historySources(page);
  check(from[source] > 0 && from[source === 'map' ? 'vertex' : 'map'] === 0,
    `${asset}: the history channel draws from the ${source === 'map' ? 'History map' : '_HISTORY attribute'} (${JSON.stringify(from)})`);
  const changed = await differ(page, 'base', 'history');
  check(history.drawn > 0.2 && history.bright > 0.1 && changed > 0.3,
    `${asset}: the history channel draws the rock in colours of its own: ${(100 * history.drawn).toFixed(0)} % drawn, ` +
    `${(100 * history.bright).toFixed(0)} % not black, ${(100 * changed).toFixed(0)} % other than the base colour's`);
  await page.select('#a-channel', 'history-dust');
  await sleep(100);
  const dust = await snapshot(page, 'dust');
  const apart = await differ(page, 'history', 'dust');
  check(dust.drawn > 0.2 && dust.grey > 0.95 && apart > 0.3,
    `${asset}: the dust channel draws the rock in greys (${(100 * dust.grey).toFixed(0)} % grey), ` +
    `${(100 * apart).toFixed(0)} % other than the history colours`);
}

const browser = await puppeteer.launch({
  executablePath: '/usr/bin/chromium',
  headless: true,
  args: ['--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
         '--disable-background-networking', '--disable-component-update', '--no-first-run',
         '--autoplay-policy=no-user-gesture-required', `--user-data-dir=${profile}`],
});
try {
  const page = await browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('requestfailed', (r) => { if (!/turntable\.mp4/.test(r.url())) errors.push(`request failed: ${r.url()}`); });
  page.on('request', (r) => { if (!r.url().startsWith(url) && !r.url().startsWith('data:')) errors.push(`outside request: ${r.url()}`); });
  await page.setViewport({ width: 1400, height: 900 });
  await page.goto(url, { waitUntil: 'load' });

  // The grid: every asset, and the failed job with its message.
  await until('the grid', () => page.evaluate(() => document.querySelectorAll('#grid .tile').length === 4));
  const names = await page.evaluate(() => [...document.querySelectorAll('#grid .tile')].map((t) => t.dataset.name));
  check(['small-s1', 'small-s2', 'tall-s1', 'tall-s2'].every((n) => names.includes(n)), `the grid shows every asset (${names})`);
  check(await page.evaluate(() => /broken-s1 \(failed\): .*missing\.png/.test(document.querySelector('#failed .job')?.textContent)),
    'the failed job is shown with its message');

  // A filter narrows it; a sort orders it.
  await page.select('#f-preset', 'tall.yaml');
  const tall = await page.evaluate(() => [...document.querySelectorAll('#grid .tile')].map((t) => t.dataset.name));
  check(tall.length === 2 && tall.every((n) => n.startsWith('tall')), `the preset filter narrows the grid to ${tall}`);
  await page.select('#f-preset', '');
  await page.select('#f-tag', 'tall');
  check(await page.evaluate(() => document.querySelectorAll('#grid .tile').length) === 2, 'the tag filter narrows the grid');
  await page.select('#f-tag', '');
  await page.select('#sort', 'triangles');
  const tris = await page.evaluate(() => [...document.querySelectorAll('#grid .tile')].map((t) =>
    window.reviewState.assets.find((a) => a.name === t.dataset.name).triangles));
  check(tris.every((t, i) => i === 0 || tris[i - 1] >= t), `sort by triangles orders the grid (${tris})`);

  // The asset view: the movie, the 3-D view drawing the rock.
  await page.click('#grid .tile[data-name="small-s1"] img');
  await until('the asset view', () => page.evaluate(() => document.getElementById('a-canvas').dataset.drawn));
  await sleep(300);
  const drawn = await coverage(page, 'asset');
  check(drawn > 0.2, `the 3-D view draws the rock: ${(100 * drawn).toFixed(0)} % of its screen box differs from the background`);
  check(await page.evaluate(() => document.getElementById('a-movie').src.endsWith('/files/small-s1/turntable.mp4')),
    'the asset view shows the turntable movie');
  const video = await until('the movie decoding', () => page.evaluate(() => {
    const v = document.getElementById('a-movie');
    return v.readyState >= 2 && v.videoWidth > 0 ? { width: v.videoWidth, height: v.videoHeight } : null;
  }), 20);
  check(video.width === 96 && video.height === 72, `chromium decodes the movie (${video.width} x ${video.height})`);
  for (const channel of ['normals', 'mask', 'base']) {
    await page.select('#a-channel', channel);
    await sleep(100);
    check(await coverage(page, 'asset') > 0.2, `the ${channel} channel draws the rock`);
  }
  // small has no texture set: its history channels read the _HISTORY attribute.
  await checkHistory(page, 'small-s1', 'vertex');
  await page.select('#a-channel', 'base');
  await page.click('#a-wire');
  check(await coverage(page, 'asset') > 0.05, 'the wireframe draws the rock');
  await page.click('#a-wire');

  // A verdict and a note set on the page are in review.json.
  await page.click('#a-verdict button[data-status="needs-work"]');
  await until('the verdict saved', () => fs.existsSync(path.join(out, 'review.json')));
  // The note opens once the page has the server's answer, which may come after the file is written.
  await until('the note open for typing', () => page.evaluate(() => !document.getElementById('a-note').disabled));
  await page.type('#a-note', 'the base is too sharp');
  const stored = await until('the note saved', () => {
    const f = JSON.parse(fs.readFileSync(path.join(out, 'review.json'), 'utf8'));
    return f.assets['small-s1']?.note === 'the base is too sharp' ? f.assets['small-s1'] : null;
  });
  check(stored.status === 'needs-work', 'a verdict and a note set on the page are in review.json');
  if (screenshotDir) await page.screenshot({ path: path.join(screenshotDir, 'review-asset.png') });
  await page.click('#a-close');
  check(await page.evaluate(() => document.querySelector('#grid .tile[data-name="small-s1"] .badge').dataset.verdict === 'needs-work'),
    'the grid shows the verdict');
  if (screenshotDir) await page.screenshot({ path: path.join(screenshotDir, 'review-grid.png') });

  // A textured rock: tall has a texture set, and the view draws it with its glTF material's maps.
  await page.click('#grid .tile[data-name="tall-s1"] img');
  const maps = await until('the textured rock', () => page.evaluate(() => {
    const model = window.reviewViewers().asset.model;
    if (!model || !document.getElementById('a-name').textContent.includes('tall-s1')) return null;
    let n = 0;
    model.traverse((o) => { if (o.isMesh && o.material.map && o.material.map.image) ++n; });
    return n || null;
  }), 20);
  await sleep(300);
  const textured = await coverage(page, 'asset');
  check(maps > 0 && textured > 0.2,
    `the 3-D view draws a textured rock: ${maps} mesh(es) with a base colour map, ${(100 * textured).toFixed(0)} % of its screen box drawn`);
  // tall has a texture set: its history channels draw the History map through TEXCOORD_0.
  await checkHistory(page, 'tall-s1', 'map');
  await page.select('#a-channel', 'lit');
  await page.click('#a-close');

  // Compare: two assets, both drawn, cameras in step.
  await page.click('#grid .tile[data-name="small-s1"] input');
  await page.click('#grid .tile[data-name="tall-s1"] input');
  await page.click('#compare');
  await until('both compare views', () => page.evaluate(() => ['c-left', 'c-right'].every((id) => document.getElementById(id).dataset.drawn)));
  await sleep(300);
  const left = await coverage(page, 'left');
  const right = await coverage(page, 'right');
  check(left > 0.2 && right > 0.2, `the compare view draws both (${(100 * left).toFixed(0)} %, ${(100 * right).toFixed(0)} %)`);
  check(await page.evaluate(() => {
    const [a, b] = window.reviewViewers().compare;
    return a.camera.position.distanceTo(b.camera.position) < 1e-9;
  }), 'the compare views share one camera');
  check(errors.length === 0, `no page errors and no request outside the server (${errors.join('; ')})`);
} finally {
  await browser.close();
  await stopReview(review);
  fs.rmSync(profile, { recursive: true, force: true });
}
fs.rmSync(dir, { recursive: true, force: true });
console.log('review browser: all checks passed');
