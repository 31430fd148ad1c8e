// `rockbake review` without a browser (docs/review.md): the assets listed with
// their files, a verdict and a note stored in review.json and still there after
// a restart, a stale verdict after a re-bake, two writers at once (one server,
// and two servers) both kept, traversal (plain, encoded, a link out) refused,
// bad requests answered 4xx while the server keeps serving.
// Usage: node api_test.mjs ROCKBAKE SOURCE_DIR
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { api, bakeLibrary, check, makeLibrary, raw, startReview, stopReview, writeLibrary } from './library.mjs';

const [rockbake] = process.argv.slice(2);
const dir = makeLibrary(rockbake);
const out = path.join(dir, 'out');
const reviewFile = path.join(out, 'review.json');
const names = ['small-s1', 'small-s2', 'tall-s1', 'tall-s2'];

let review = await startReview(rockbake, out);
let url = review.url;
try {
  // Every asset, with its status and links; the failed job with its message.
  let r = await api(url, '/api/assets');
  check(r.status === 200, 'GET /api/assets answers');
  const listed = r.json.assets;
  check(names.every((n) => listed.some((a) => a.name === n && a.status === 'ok')), 'the four baked assets are listed as ok');
  const broken = listed.find((a) => a.name === 'broken-s1');
  check(broken && broken.status === 'failed' && /missing\.png/.test(broken.message), 'the failed job is listed with its message');
  const small = listed.find((a) => a.name === 'small-s1');
  check(small.preset === 'small.yaml' && small.seed === 1 && small.tags.includes('test') && small.triangles > 0,
    'an asset carries its preset, seed, tags and triangles');
  const tall = listed.find((a) => a.preset === 'tall.yaml');
  check(tall && tall.texel_density > 0 && small.texel_density === null,
    `LOD0's texel density where the bake made a texture set, null where not (${tall?.texel_density}, ${small.texel_density})`);
  check(small.files.movie === '/files/small-s1/turntable.mp4' && small.files.render === '/files/small-s1/render.png',
    'an asset links its movie and render');
  const movie = await raw(url, 'GET', small.files.movie);
  check(movie.status === 200 && movie.headers['content-type'] === 'video/mp4' && movie.body.length > 1000,
    'the movie is served as video/mp4');
  const part = await raw(url, 'GET', small.files.movie, undefined, { Range: 'bytes=0-99' });
  check(part.status === 206 && part.body.length === 100 && part.headers['content-range'] === `bytes 0-99/${movie.body.length}`,
    `a range of the movie is a 206 with its Content-Range (${part.status}, ${part.headers['content-range']})`);
  const glb = await raw(url, 'GET', small.files.lods[0].file);
  check(glb.status === 200 && glb.body.subarray(0, 4).toString() === 'glTF', 'the LOD0 GLB is served');

  r = await api(url, '/api/assets/small-s1');
  check(r.status === 200 && r.json.bake_preset && r.json.bake_preset.name === 'small-s1' && r.json.bake_preset.seed === 1 && r.json.stages && r.json.lods.length >= 1,
    'GET /api/assets/<name> gives the preset as the bake ran it, stage times and LODs');
  r = await api(url, '/api/assets/nope');
  check(r.status === 404 && /no asset 'nope'/.test(r.json.error), 'an unknown asset is a 404 with a message');

  // A verdict and a note, stored at once.
  r = await api(url, '/api/review', { asset: 'small-s1', status: 'needs-work', note: 'soften the ledge' });
  check(r.status === 200 && r.json.review.status === 'needs-work', 'POST /api/review stores a verdict');
  let file = JSON.parse(fs.readFileSync(reviewFile, 'utf8'));
  check(file.assets['small-s1'].status === 'needs-work' && file.assets['small-s1'].note === 'soften the ledge',
    'review.json holds the verdict and the note');

  // Bad requests: 4xx with a message, and the server carries on.
  for (const [body, status, what] of [
    [{ asset: 'small-s1', status: 'great' }, 400, 'a status that is not a verdict'],
    [{ asset: 'nope', status: 'approved' }, 404, 'an unknown asset'],
    [{ status: 'approved' }, 400, 'a body without asset'],
    [{ asset: 'small-s1', status: 'approved', note: 'x'.repeat(20000) }, 413, 'a note too long'],
  ]) {
    r = await api(url, '/api/review', body);
    check(r.status === status && typeof r.json.error === 'string' && r.json.error.length > 10, `${what}: ${status} with a message`);
  }
  r = await raw(url, 'POST', '/api/review', '{"asset": ', { 'Content-Type': 'application/json' });
  check(r.status === 400, 'a body that is not JSON: 400');
  r = await raw(url, 'POST', '/api/review', JSON.stringify({ asset: 'small-s1', status: 'approved' }),
    { 'Content-Type': 'application/json', Origin: 'http://elsewhere.example' });
  check(r.status === 403 && !JSON.parse(fs.readFileSync(reviewFile, 'utf8')).assets['small-s1'].status.startsWith('approved'),
    'a POST from another page is refused (403) and changes nothing');

  // Traversal: plain, encoded, doubly encoded, and a link out of OUT.
  fs.symlinkSync('/etc/passwd', path.join(out, 'small-s1', 'passwd'));
  fs.symlinkSync('/etc', path.join(out, 'etc'));
  for (const p of ['/files/../small.yaml', '/files/%2e%2e/small.yaml', '/files/..%2fsmall.yaml',
    '/files/%252e%252e/small.yaml', '/files/small-s1/../../small.yaml', '/files//etc/passwd',
    '/files/small-s1/passwd', '/files/etc/passwd', '/files/small-s1']) {
    r = await raw(url, 'GET', p);
    check(r.status >= 400 && r.status < 500 && !r.body.toString().includes('root:'), `${p} is refused (${r.status})`);
  }
  r = await api(url, '/api/assets');
  check(r.status === 200, 'the server still serves after the refusals');

  // Two writers at once on one server: every verdict kept.
  await Promise.all(names.map((n, i) => api(url, '/api/review', { asset: n, status: i % 2 ? 'approved' : 'rejected', note: `note ${n}` })));
  file = JSON.parse(fs.readFileSync(reviewFile, 'utf8'));
  check(names.every((n, i) => file.assets[n] && file.assets[n].note === `note ${n}` &&
    file.assets[n].status === (i % 2 ? 'approved' : 'rejected')), 'concurrent saves on one server are all kept');

  // Two servers on one library, saving at once: both kept (the file lock).
  const second = await startReview(rockbake, out);
  try {
    const saves = [];
    for (let k = 0; k < 10; ++k) {
      saves.push(api(url, '/api/review', { asset: 'small-s2', status: 'approved', note: `first ${k}` }));
      saves.push(api(second.url, '/api/review', { asset: 'tall-s2', status: 'rejected', note: `second ${k}` }));
    }
    await Promise.all(saves);
    file = JSON.parse(fs.readFileSync(reviewFile, 'utf8'));
    check(/^first \d$/.test(file.assets['small-s2'].note) && /^second \d$/.test(file.assets['tall-s2'].note) &&
      file.assets['small-s1'].note === 'note small-s1', 'two servers saving at once both keep their verdicts');
  } finally {
    await stopReview(second);
  }
  await api(url, '/api/review', { asset: 'small-s1', status: 'needs-work', note: 'soften the ledge' });

  // A review.json that is not one is refused with what to do, and left as it is.
  const kept = fs.readFileSync(reviewFile);
  fs.writeFileSync(reviewFile, 'not json');
  r = await api(url, '/api/review', { asset: 'small-s1', status: 'approved' });
  check(r.status === 409 && /is not a review file/.test(r.json.error) && fs.readFileSync(reviewFile, 'utf8') === 'not json',
    'a damaged review.json: 409 with what to do, the file left as it is');
  fs.writeFileSync(reviewFile, kept);

  // A restart: the verdict is still there.
  check(await stopReview(review) === 0, 'review stops cleanly on Ctrl-C');
  review = await startReview(rockbake, out);
  url = review.url;
  r = await api(url, '/api/assets');
  let s1 = r.json.assets.find((a) => a.name === 'small-s1');
  check(s1.review && s1.review.status === 'needs-work' && s1.review.note === 'soften the ledge' && !s1.review.stale,
    'after a restart the verdict and note are still there, not stale');

  // A re-bake with other inputs: the verdict shows as stale.
  writeLibrary(dir, 0.4);
  check(bakeLibrary(rockbake, dir) === 1, 'the library bakes again with another time');
  r = await api(url, '/api/assets');
  s1 = r.json.assets.find((a) => a.name === 'small-s1');
  check(s1.review && s1.review.status === 'needs-work' && s1.review.stale === true, 'after a re-bake with new inputs the verdict is stale');

  // A folder that is not a library: exit 2, naming index.json, before listening.
  const notLibrary = spawnSync(rockbake, ['review', dir, '--port', '0'], { encoding: 'utf8', timeout: 20000 });
  check(notLibrary.status === 2 && /index\.json/.test(notLibrary.stderr) && /rockbake library/.test(notLibrary.stderr),
    `a folder without index.json: exit 2 with what to do (${notLibrary.status})`);

  // Only this machine by default.
  check(/^http:\/\/127\.0\.0\.1:/.test(url), 'it listens on 127.0.0.1');
} finally {
  await stopReview(review).catch(() => {});
}
fs.rmSync(dir, { recursive: true, force: true });
console.log('review API: all checks passed');
