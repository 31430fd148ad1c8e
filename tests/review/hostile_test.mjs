// `rockbake review` against hostile files and pages (docs/review.md, "The
// server's promises"): a library folder written by hand with files a neighbour
// could plant (FIFOs, links to /dev/zero and out of OUT, sparse giants, a
// dangling lock link, wrong JSON types, a page in an asset folder), byte ranges
// that would amplify, and another page framing the review page in Debian's
// chromium. Each answer is waited for at most a few seconds: a server that
// blocks fails the check instead of hanging the test.
// Usage: node hostile_test.mjs ROCKBAKE SOURCE_DIR
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';
import { check, sleep, startReview, stopReview } from './library.mjs';

const [rockbake, sourceDir] = process.argv.slice(2);
const puppeteer = createRequire(path.resolve(sourceDir, 'studio', 'package.json'))('puppeteer-core');
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'rockbake-hostile-'));
const out = path.join(dir, 'out');
const elsewhere = path.join(dir, 'elsewhere');
const reviewFile = path.join(out, 'review.json');
const MOVIE_BYTES = 4 << 20;

// A library as `rockbake library` lays it out, written by hand: four baked assets.
function writeLibrary() {
  fs.rmSync(out, { recursive: true, force: true });
  const names = ['a', 'b', 'c', 'd'];
  const entry = (n) => ({ name: n, status: 'ok', input_hash: `hash-${n}`, job: { preset: 'p.yaml', seed: 1 },
    render: `${n}/render.png`, movie: `${n}/turntable.mp4`, asset: `${n}/asset.json`, manifest: `${n}/manifest.json` });
  fs.mkdirSync(out, { recursive: true });
  fs.writeFileSync(path.join(out, 'index.json'), JSON.stringify({ rockbake_index: 1, assets: names.map(entry) }));
  for (const n of names) {
    const d = path.join(out, n);
    fs.mkdirSync(d);
    fs.writeFileSync(path.join(d, 'asset.json'), JSON.stringify({ tags: ['test'], size_m: [1, 1, 1],
      lods: [{ level: 0, file: 'rock.glb', triangles: 100 }] }));
    fs.writeFileSync(path.join(d, 'manifest.json'), JSON.stringify({ inputs: { seed: 1 }, timings: { stages: { total: 1 } } }));
    fs.writeFileSync(path.join(d, 'stats.json'), JSON.stringify({ stages: { total: 1 }, preset: { name: n } }));
    fs.writeFileSync(path.join(d, 'render.png'), Buffer.alloc(2654, 7));
  }
  fs.writeFileSync(path.join(out, 'a', 'turntable.mp4'), Buffer.alloc(MOVIE_BYTES, 1));
  // Outside OUT: a library's worth of files that must never be read through it.
  fs.rmSync(elsewhere, { recursive: true, force: true });
  fs.mkdirSync(path.join(elsewhere, 'x'), { recursive: true });
  fs.writeFileSync(path.join(elsewhere, 'x', 'asset.json'), JSON.stringify({ tags: ['outside-secret'], lods: [] }));
  fs.writeFileSync(path.join(elsewhere, 'x', 'manifest.json'), '{}');
}

// An HTTP request that gives up after `seconds`: {status: 0} when no answer came.
function request(url, method, rawPath, { body, headers = {}, seconds = 5 } = {}) {
  const u = new URL(url);
  return new Promise((resolve) => {
    const req = http.request({ host: u.hostname, port: u.port, method, path: rawPath,
      headers: { ...(body !== undefined ? { 'Content-Type': 'application/json' } : {}), ...headers } }, (res) => {
      const chunks = [];
      res.on('data', (c) => chunks.push(c));
      res.on('end', () => {
        const b = Buffer.concat(chunks);
        let json = null;
        try { json = JSON.parse(b.toString()); } catch { /* not JSON */ }
        resolve({ status: res.statusCode, headers: res.headers, body: b, json });
      });
    });
    req.setTimeout(seconds * 1000, () => { req.destroy(); resolve({ status: 0, headers: {}, body: Buffer.alloc(0), json: null }); });
    req.on('error', () => resolve({ status: 0, headers: {}, body: Buffer.alloc(0), json: null }));
    if (body !== undefined) req.write(typeof body === 'string' ? body : JSON.stringify(body));
    req.end();
  });
}

const assetOf = (r, name) => (r.json && r.json.assets || []).find((a) => a.name === name);

writeLibrary();
let review = await startReview(rockbake, out);
let url = review.url;
try {
  // Headers: nothing may frame the pages, nothing is sniffed, the pages run only their own scripts.
  for (const p of ['/', '/api/assets', '/review.js', '/files/a/render.png', '/nope']) {
    const r = await request(url, 'GET', p);
    check(r.headers['x-frame-options'] === 'DENY' && /frame-ancestors 'none'/.test(r.headers['content-security-policy'] || '') &&
      r.headers['x-content-type-options'] === 'nosniff', `GET ${p}: X-Frame-Options DENY, frame-ancestors 'none', nosniff`);
  }
  let r = await request(url, 'GET', '/');
  check(/script-src 'self' 'sha256-/.test(r.headers['content-security-policy']) && !/unsafe-inline/.test(r.headers['content-security-policy']),
    `the page's policy allows its scripts and its import map by hash, no other inline script (${r.headers['content-security-policy']})`);

  // A page planted in an asset folder is a download, sandboxed, never a page of the server's origin.
  const planted = `<!doctype html><script>fetch('/api/review', {method: 'POST', headers: {'Content-Type': 'application/json'},
    body: JSON.stringify({asset: 'a', status: 'approved', note: 'planted'})});</script>`;
  fs.writeFileSync(path.join(out, 'a', 'readme.html'), planted);
  fs.writeFileSync(path.join(out, 'a', 'logo.svg'), '<svg xmlns="http://www.w3.org/2000/svg"><script>alert(1)</script></svg>');
  for (const f of ['readme.html', 'logo.svg']) {
    r = await request(url, 'GET', `/files/a/${f}`);
    check(r.status === 200 && r.headers['content-type'] === 'application/octet-stream' &&
      /attachment/.test(r.headers['content-disposition'] || '') && /sandbox/.test(r.headers['content-security-policy'] || ''),
      `/files/a/${f} is an attachment, application/octet-stream, sandboxed (${r.headers['content-type']})`);
  }
  r = await request(url, 'GET', '/files/a/render.png');
  check(r.headers['content-type'] === 'image/png' && !r.headers['content-disposition'], 'a render is still shown as image/png');

  // In chromium: a hostile page framing the review page gets nothing drawn; the planted page posts nothing.
  const hostile = http.createServer((req, res) => {
    res.writeHead(200, { 'Content-Type': 'text/html' });
    // /inner and /control: the same check on a page that allows framing, so that the check
    // below can tell "nothing in the frame" from "the frame could not be read".
    if (req.url === '/inner') res.end('<!doctype html><div id="filters">a framable page</div>');
    else if (req.url === '/control')
      res.end(`<!doctype html><iframe src="http://127.0.0.1:${hostile.address().port}/inner" width="800" height="600"></iframe>`);
    else res.end(`<!doctype html><iframe id="f" src="${url}" style="opacity:0.01" width="800" height="600"></iframe>`);
  });
  await new Promise((resolve) => hostile.listen(0, '127.0.0.1', resolve));
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'rockbake-chromium-'));
  const browser = await puppeteer.launch({
    executablePath: '/usr/bin/chromium', headless: true,
    args: ['--headless=new', '--no-sandbox', '--disable-background-networking', '--disable-component-update',
           '--no-first-run', `--user-data-dir=${profile}`],
  });
  try {
    const page = await browser.newPage();
    // "localhost" is another site than 127.0.0.1, as a web page the user visits would be.
    const framedFilters = async (where) => {
      await page.goto(`http://localhost:${hostile.address().port}${where}`, { waitUntil: 'load' });
      await sleep(1500);
      const framed = page.frames().find((f) => f !== page.mainFrame());
      return framed ? await framed.evaluate(() => !!document.querySelector('#filters')).catch(() => false) : false;
    };
    check(await framedFilters('/control'), 'the frame check reads a framable page of another site (the control)');
    check(!(await framedFilters('/')), 'a page of another site framing the review page gets no review page in its frame');

    const before = fs.existsSync(reviewFile) ? fs.readFileSync(reviewFile, 'utf8') : '';
    const visit = await browser.newPage();
    await visit.goto(`${url}files/a/readme.html`, { waitUntil: 'load' }).catch(() => { /* a download aborts the navigation */ });
    await sleep(2000);
    const after = fs.existsSync(reviewFile) ? fs.readFileSync(reviewFile, 'utf8') : '';
    check(after === before && !/planted/.test(after), 'opening the planted readme.html in chromium posts no verdict');
  } finally {
    await browser.close();
    hostile.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }

  // Byte ranges: no amplification, RFC 9110 Content-Range, odd headers ignored.
  const movie = '/files/a/turntable.mp4';
  r = await request(url, 'GET', movie, { headers: { Range: 'bytes=' + Array(400).fill('0-').join(',') }, seconds: 20 });
  check((r.status === 200 || r.status === 206) && r.body.length <= MOVIE_BYTES + 1024,
    `400 ranges "0-" of a 4 MiB file send it at most once (${r.status}, ${r.body.length} bytes)`);
  r = await request(url, 'GET', '/files/a/render.png', { headers: { Range: 'bytes=0-' } });
  check(r.status === 206 && r.headers['content-range'] === 'bytes 0-2653/2654' && r.body.length === 2654,
    `bytes=0- is a 206 with Content-Range bytes 0-2653/2654 (${r.headers['content-range']})`);
  r = await request(url, 'GET', '/files/a/render.png', { headers: { Range: 'bytes=-10' } });
  check(r.status === 206 && r.headers['content-range'] === 'bytes 2644-2653/2654' && r.body.length === 10, 'a suffix range');
  r = await request(url, 'GET', '/files/a/render.png', { headers: { Range: 'bytes=5000-' } });
  check(r.status === 416 && r.headers['content-range'] === 'bytes */2654', `an unsatisfiable range: 416 with bytes */2654 (${r.headers['content-range']})`);
  for (const h of ['items=0-1', 'bytes=5-1', 'bytes=x-y', 'bytes=', 'bytes=1-2;3']) {
    r = await request(url, 'GET', '/files/a/render.png', { headers: { Range: h } });
    check(r.status === 200 && r.body.length === 2654, `Range: ${h} is ignored: the whole file, 200 (${r.status})`);
  }
  r = await request(url, 'GET', '/files/a/render.png', { headers: { Range: 'bytes=0-9,5-19,100-109' } });
  check(r.status === 206 && /^multipart\/byteranges; boundary=/.test(r.headers['content-type']) &&
    r.body.includes('Content-Range: bytes 0-19/2654') && r.body.includes('Content-Range: bytes 100-109/2654') &&
    !r.body.includes('bytes 5-19'), 'overlapping ranges are coalesced into one part');

  // Wrong JSON types: that asset reads as absent, the grid still answers.
  fs.writeFileSync(path.join(out, 'b', 'asset.json'), JSON.stringify({ tags: 5, lods: 'many', size_m: {} }));
  fs.writeFileSync(reviewFile, JSON.stringify({ rockbake_review: 1, assets: { a: { status: 7, note: [] }, c: 'approved' } }));
  const index = JSON.parse(fs.readFileSync(path.join(out, 'index.json'), 'utf8'));
  index.assets.push({ name: 7, status: 'ok' }, { name: 'e', status: ['ok'], input_hash: 3, job: 'x' });
  fs.writeFileSync(path.join(out, 'index.json'), JSON.stringify(index));
  r = await request(url, 'GET', '/api/assets');
  check(r.status === 200 && assetOf(r, 'a') && assetOf(r, 'a').review === null && Array.isArray(assetOf(r, 'b').tags) &&
    assetOf(r, 'c').review === null && assetOf(r, 'e'), `wrong types in review.json, asset.json and index.json: 200, the grid listed (${r.status} ${r.body.toString().slice(0, 200)})`);
  r = await request(url, 'GET', '/api/assets/b');
  check(r.status === 200, `GET /api/assets/b with wrong types answers 200 (${r.status})`);
  writeLibrary();
  fs.rmSync(reviewFile, { force: true });

  // A FIFO as review.json, then as an asset's asset.json: answered at once, nothing waits.
  execFileSync('mkfifo', [reviewFile]);
  r = await request(url, 'GET', '/api/assets');
  check(r.status === 409 && /review\.json/.test(r.json?.error || ''), `review.json a FIFO: 409 naming it, at once (${r.status})`);
  r = await request(url, 'POST', '/api/review', { body: { asset: 'a', status: 'approved' } });
  check(r.status === 409, `review.json a FIFO: a save is refused at once (${r.status})`);
  r = await request(url, 'GET', '/files/a/render.png');
  check(r.status === 200, 'the files are still served');
  fs.rmSync(reviewFile);
  execFileSync('mkfifo', [path.join(out, 'b', 'asset.json.fifo')]);
  fs.rmSync(path.join(out, 'b', 'asset.json'));
  fs.renameSync(path.join(out, 'b', 'asset.json.fifo'), path.join(out, 'b', 'asset.json'));
  r = await request(url, 'GET', '/api/assets');
  check(r.status === 200 && assetOf(r, 'b').status === 'unreadable' && /asset\.json/.test(assetOf(r, 'b').message) &&
    assetOf(r, 'a').status === 'ok', `an asset.json FIFO: the list answers, that asset unreadable with why (${r.status})`);

  // review.json a link to /dev/zero, or a sparse 2 GB file; stats.json sparse: refused, not read.
  fs.symlinkSync('/dev/zero', reviewFile);
  r = await request(url, 'GET', '/api/assets');
  check(r.status === 409, `review.json a link to /dev/zero: 409 at once (${r.status})`);
  fs.rmSync(reviewFile);
  fs.writeFileSync(reviewFile, '');
  fs.truncateSync(reviewFile, 2 * 1024 * 1024 * 1024);
  r = await request(url, 'GET', '/api/assets');
  check(r.status === 409 && /bytes/.test(r.json?.error || ''), `a sparse 2 GB review.json: 409 saying its size (${r.status})`);
  fs.rmSync(reviewFile);
  fs.truncateSync(path.join(out, 'c', 'stats.json'), 2 * 1024 * 1024 * 1024);
  r = await request(url, 'GET', '/api/assets/c');
  check(r.status === 200 && r.json.status === 'unreadable' && /stats\.json/.test(r.json.message),
    `a sparse 2 GB stats.json: the asset unreadable, at once (${r.status})`);

  // A dangling .review.lock link: a save creates nothing outside OUT.
  const target = path.join(elsewhere, 'created-by-lock');
  fs.rmSync(path.join(out, '.review.lock'), { force: true });  // a save before made a real one
  fs.symlinkSync(target, path.join(out, '.review.lock'));
  r = await request(url, 'POST', '/api/review', { body: { asset: 'a', status: 'approved' } });
  check(r.status === 409 && !fs.existsSync(target) && /review\.lock/.test(r.json?.error || ''),
    `a dangling .review.lock link: 409, nothing created outside OUT (${r.status})`);
  fs.rmSync(path.join(out, '.review.lock'));
  r = await request(url, 'POST', '/api/review', { body: { asset: 'a', status: 'approved' } });
  check(r.status === 200, 'with the link gone, a save works');

  // An asset folder that is a link out of OUT, and an index entry that steps out of it.
  fs.rmSync(path.join(out, 'd'), { recursive: true });
  fs.symlinkSync(path.join(elsewhere, 'x'), path.join(out, 'd'));
  const withOutside = JSON.parse(fs.readFileSync(path.join(out, 'index.json'), 'utf8'));
  withOutside.assets.push({ name: '../elsewhere/x', status: 'ok', input_hash: 'h' });
  fs.writeFileSync(path.join(out, 'index.json'), JSON.stringify(withOutside));
  r = await request(url, 'GET', '/api/assets/d');
  check(r.status === 200 && !r.body.toString().includes('outside-secret') && r.json.status === 'unreadable',
    `an asset folder linked out of OUT: its asset.json is not read (${r.json?.status})`);
  r = await request(url, 'GET', '/api/assets');
  check(r.status === 200 && !r.body.toString().includes('outside-secret') && assetOf(r, '../elsewhere/x').status === 'unreadable',
    'an index entry ../elsewhere/x: nothing outside OUT is read, it is listed unreadable');

  // Ctrl-C still stops the server.
  check(await stopReview(review) === 0, 'review stops on Ctrl-C after all that');

  // A garbled index.json: exit 2, and the command it suggests works.
  writeLibrary();
  fs.writeFileSync(path.join(out, 'index.json'), '{"assets": 5}');
  const garbled = spawnSync(rockbake, ['review', out, '--port', '0'], { encoding: 'utf8', timeout: 20000 });
  const suggested = (garbled.stderr.match(/`(rockbake library [^`]*)`/) || [])[1];
  check(garbled.status === 2 && /index\.json/.test(garbled.stderr) && suggested,
    `a garbled index.json: exit 2 naming it, with a command (${garbled.status}: ${garbled.stderr.trim()})`);
  const args = suggested.split(' ').slice(1);
  const fixed = spawnSync(rockbake, args, { encoding: 'utf8', timeout: 60000 });
  check(fixed.status === 0 && Array.isArray(JSON.parse(fs.readFileSync(path.join(out, 'index.json'), 'utf8')).assets),
    `the suggested \`${suggested}\` runs and writes an index (${fixed.status}: ${fixed.stderr.trim().slice(-300)})`);
} finally {
  await stopReview(review).catch(() => {});
}
fs.rmSync(dir, { recursive: true, force: true });
console.log('review hostile files: all checks passed');
