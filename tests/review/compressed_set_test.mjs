// The review page's set switch (docs/review.md) in a real browser (Debian's chromium, headless,
// driven by puppeteer-core pinned in studio/): an asset baked with delivery.compressed shows its
// compressed set — KTX2 maps through three's KTX2Loader and the Basis Universal transcoder
// (.wasm from the pinned three.js), meshopt meshes through MeshoptDecoder — drawn (pixels
// other than the background), with no page error, console error or failed request; an asset
// without one keeps the switch off.
// Usage: node compressed_set_test.mjs ROCKBAKE SOURCE_DIR
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { createRequire } from 'node:module';
import { check, coverage, sleep, startReview, stopReview, until as waitFor } from './library.mjs';

const [rockbake, sourceDir] = process.argv.slice(2);
const puppeteer = createRequire(path.resolve(sourceDir, 'studio', 'package.json'))('puppeteer-core');
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'rockbake-review-compressed-'));
const small = fs.readFileSync(path.join(sourceDir, 'tests', 'data', 'small.yaml'), 'utf8');
fs.writeFileSync(path.join(dir, 'packed.yaml'), small.replace('name: small', 'name: packed') +
  'mesh: {lods: [0.5]}\ntexture: {size: 256, ao_rays: 4, maps: [base_color, normal, orm]}\nexport: [glb]\ndelivery: {compressed: true}\n');
fs.writeFileSync(path.join(dir, 'plain.yaml'), small.replace('name: small', 'name: plain') + 'export: [glb]\n');
fs.writeFileSync(path.join(dir, 'lib.yaml'), '- {preset: packed.yaml, seeds: [1]}\n- {preset: plain.yaml, seeds: [1]}\n');
const out = path.join(dir, 'out');
const baked = spawnSync(rockbake, ['library', path.join(dir, 'lib.yaml'), '-o', out, '--jobs', '2', '--no-render'],
  { encoding: 'utf8' });
if (baked.status !== 0) throw new Error(`the library bake failed (${baked.status}): ${baked.stderr}`);
check(fs.existsSync(path.join(out, 'packed-s1', 'compressed', 'rock.glb')), 'the library bake wrote the compressed set');

const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'rockbake-chromium-'));
const review = await startReview(rockbake, out);
const url = review.url;
const until = (what, predicate, seconds = 60) => waitFor(what, predicate, seconds);


const browser = await puppeteer.launch({
  executablePath: '/usr/bin/chromium',
  headless: true,
  args: ['--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
         '--disable-background-networking', '--disable-component-update', '--no-first-run', `--user-data-dir=${profile}`],
});
try {
  const page = await browser.newPage();
  const errors = [];
  const wasm = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error' && !/favicon/.test(m.location()?.url ?? '')) errors.push(`console: ${m.text()}`); });
  page.on('requestfailed', (r) => errors.push(`request failed: ${r.url()}`));
  page.on('response', (r) => {
    if (r.status() >= 400 && !r.url().endsWith('/favicon.ico')) errors.push(`HTTP ${r.status()}: ${r.url()}`);
    if (r.url().endsWith('.wasm')) wasm.push(`${r.url()} (${r.headers()['content-type']})`);
  });
  await page.setViewport({ width: 1400, height: 900 });
  await page.goto(url, { waitUntil: 'load' });
  await until('the grid', () => page.evaluate(() => document.querySelectorAll('#grid .tile').length === 2));

  // Without a compressed set the switch is off.
  await page.click('#grid .tile[data-name="plain-s1"]');
  await until('plain drawn', () => page.evaluate(() => document.getElementById('a-canvas').dataset.drawn));
  check(await page.evaluate(() => document.getElementById('a-set').disabled), 'an asset without a compressed set has the switch off');
  await page.click('#a-close');

  // The full set first, then the compressed one.
  await page.click('#grid .tile[data-name="packed-s1"]');
  await until('the full set drawn', () => page.evaluate(() => {
    const c = document.getElementById('a-canvas');
    return c.dataset.set === 'full' && c.dataset.drawn?.endsWith('/packed-s1/rock.glb');
  }));
  check(!(await page.evaluate(() => document.getElementById('a-set').disabled)), 'the switch is on for an asset with a compressed set');
  await sleep(300);
  const full = await coverage(page);
  check(full > 0.2, `the full set draws the rock: ${(100 * full).toFixed(0)} % of its screen box`);
  await page.select('#a-set', 'compressed');
  await until('the compressed set drawn', async () => {
    const shown = await page.evaluate(() => {
      const c = document.getElementById('a-canvas');
      if (/cannot show/.test(document.getElementById('message').textContent)) return document.getElementById('message').textContent;
      return c.dataset.set === 'compressed' && c.dataset.drawn?.endsWith('/packed-s1/compressed/rock.glb');
    });
    if (typeof shown === 'string') throw new Error(`FAILED: the page says: ${shown}; errors: ${JSON.stringify(errors)}`);
    return shown;
  });
  await sleep(300);
  const packed = await coverage(page);
  check(packed > 0.2, `the compressed set draws the rock: ${(100 * packed).toFixed(0)} % of its screen box`);
  const maps = await page.evaluate(() => {
    let compressed = 0, other = 0;
    window.reviewViewers().asset.model.traverse((o) => {
      if (!o.isMesh) return;
      for (const t of [o.material.map, o.material.normalMap, o.material.roughnessMap])
        if (t) (t.isCompressedTexture ? ++compressed : ++other);
    });
    return { compressed, other };
  });
  check(maps.compressed > 0 && maps.other === 0, `the compressed set's maps are GPU-compressed textures (${JSON.stringify(maps)})`);
  check(wasm.length > 0 && wasm.every((w) => w.endsWith('(application/wasm)')),
    `the Basis Universal transcoder's .wasm was loaded, as application/wasm (${wasm})`);
  // Another LOD of the same set.
  await page.select('#a-lod', await page.evaluate(() => document.getElementById('a-lod').options[1].value));
  await until('LOD1 of the compressed set drawn', () => page.evaluate(() =>
    document.getElementById('a-canvas').dataset.drawn?.endsWith('/packed-s1/compressed/rock_lod1.glb')));
  await sleep(300);
  check(await coverage(page) > 0.2, 'LOD1 of the compressed set draws the rock');
  check(errors.length === 0, `no page errors: ${JSON.stringify(errors)}`);
  console.log('PASS: the review page shows the compressed set');
} finally {
  await browser.close();
  await stopReview(review);
  fs.rmSync(dir, { recursive: true, force: true });
  fs.rmSync(profile, { recursive: true, force: true });
}
