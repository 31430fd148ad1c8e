// The studio's JSON API without a browser (docs/studio.md): edits at time 0
// and later, seek back and branch, save and the byte-for-byte contract with
// `bake --no-mesh`, and bad requests answered 4xx while the server keeps serving.
// Usage: node api_test.mjs ROCKBAKE SOURCE_DIR
import fs from 'node:fs';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { api, bakeVdb, check, presetFolder, raw, rawPost, startStudio, stopStudio } from './harness.mjs';

const [rockbake, sourceDir] = process.argv.slice(2);
const resolution = 24;
const dir = presetFolder(sourceDir, 6);  // 24 cycles at resolution 24
const finalOut = path.join(dir, 'final');
const studio = await startStudio(rockbake, [path.join(dir, 'goblin.yaml'), '--resolution', String(resolution), '-o', finalOut]);
const url = studio.url;
let passed = 0;
let failure = null;
const ok = (condition, message) => { check(condition, message); ++passed; };

try {
  let s = (await api(url, '/api/state')).json;
  ok(s.cycle === 0 && s.time === 0 && s.resolution === resolution, 'starts at cycle 0 at the preview resolution');
  ok(s.rock > 0 && s.rock === s.initial_rock, 'state counts the initial rock');
  const h = s.h;

  // Time 0: the base graph changes, no keyframe.
  s = (await api(url, '/api/edit', { durability: { points: [[0, 2.5], [0.5, 0.7], [1, 1.5]] } })).json;
  ok(JSON.stringify(s.preset.durability.points) === '[[0,2.5],[0.5,0.7],[1,1.5]]', 'an edit at time 0 changes the base graph');
  ok(s.preset.durability.keyframes.length === 0, 'an edit at time 0 adds no keyframe');

  // Later: a keyframe at the current time.
  s = (await api(url, '/api/control', { action: 'step' })).json;
  s = (await api(url, '/api/control', { action: 'step' })).json;
  s = (await api(url, '/api/control', { action: 'step' })).json;
  ok(s.cycle === 3, 'step runs one cycle each');
  s = (await api(url, '/api/edit', { durability: { points: [[0, 2.5], [0.5, 0.3], [1, 1.5]] } })).json;
  ok(s.preset.durability.keyframes.length === 1 && Math.abs(s.preset.durability.keyframes[0].at - 3 * h) < 1e-12,
    'an edit at cycle 3 becomes a keyframe at 3h');
  s = (await api(url, '/api/edit', { response: { power: 1.5 } })).json;
  ok(s.preset.durability.keyframes.length === 1 && s.preset.durability.keyframes[0].response.power === 1.5,
    'a second edit at the same time merges into that keyframe');
  const curve = s.response_curve;
  ok(curve.length === 65 && curve[0][0] === 0 && curve[64][0] === 1 &&
     curve.every(([x, y]) => Math.abs(y - x ** 1.5) < 1e-12),
    'the state samples the active response f = x^1.5 at 65 points (the page draws them)');
  s = (await api(url, '/api/edit', { response: { curve: [[0, 0.1], [0.5, 0.3], [1, 0.9]] } })).json;
  ok(Math.abs(s.response_curve[16][1] - 0.2) < 1e-12 && Math.abs(s.response_curve[48][1] - 0.6) < 1e-12,
    'a curve response is sampled through its points');
  s = (await api(url, '/api/edit', { response: { power: 1.5 } })).json;
  s = (await api(url, '/api/control', { run_until: 8 * h })).json;
  ok(s.cycle === 8, 'run_until runs to the cycle of that time');
  const straight = (await api(url, '/api/rock.vdb')).body;

  // Seek back and forth without editing: the same rock.
  s = (await api(url, '/api/control', { seek: 2 * h })).json;
  ok(s.cycle === 2 && s.preset.durability.keyframes.length === 1, 'seek back keeps the keyframes');
  s = (await api(url, '/api/control', { seek: 8 * h })).json;
  ok(Buffer.compare((await api(url, '/api/rock.vdb')).body, straight) === 0, 'seek back then forward gives the same rock.vdb');

  // Branch: an edit after seeking back drops the later keyframe.
  s = (await api(url, '/api/control', { seek: 2 * h })).json;
  const bands = s.active.bubbles.map((b) => ({ ...b, spheroidal: 0.5 }));
  s = (await api(url, '/api/edit', { bubbles: bands })).json;
  ok(s.preset.durability.keyframes.length === 1 && Math.abs(s.preset.durability.keyframes[0].at - 2 * h) < 1e-12 &&
     s.preset.durability.keyframes[0].bubbles[0].spheroidal === 0.5 && !('points' in s.preset.durability.keyframes[0]),
    'an edit after seeking back starts a branch: the later keyframe is gone, a bubbles keyframe at 2h');
  s = (await api(url, '/api/control', { run_until: 7 * h })).json;
  ok(s.cycle === 7, 'runs on along the new branch');

  // Save, then bake the saved preset: byte-identical rock.vdb.
  const saved = await api(url, '/api/save', { name: 'goblin-branch' });
  ok(saved.status === 200 && fs.existsSync(path.join(dir, 'goblin-branch.yaml')), 'save writes beside the preset');
  const studioVdb = (await api(url, '/api/rock.vdb')).body;
  const baked = bakeVdb(rockbake, path.join(dir, 'goblin-branch.yaml'), resolution, path.join(dir, 'out'));
  ok(studioVdb.length > 1000 && Buffer.compare(studioVdb, baked) === 0,
    'bake --no-mesh of the saved preset gives a rock.vdb byte-identical to GET /api/rock.vdb');
  ok((await api(url, '/api/save', { name: 'goblin-branch' })).status === 409, 'save does not overwrite unless asked');
  ok((await api(url, '/api/save', { name: 'goblin' })).status === 409, 'save never replaces the studio\'s own preset');
  ok((await api(url, '/api/save', { name: 'base', overwrite: true })).status === 409, 'save never replaces a file the preset extends');

  // Bad requests: 4xx with a message, the server still serving.
  const still = async (what) => {
    const r = await api(url, '/api/state');
    ok(r.status === 200 && r.json.cycle === 7, `still serving after ${what}`);
  };
  for (const p of ['/../../etc/passwd', '/%2e%2e/%2e%2e/etc/passwd', '/%2E%2E%2F%2E%2E%2Fetc%2Fpasswd',
                   '/vendor/three/build/../../../../../../etc/passwd', '/vendor/three/build/%2e%2e%2f%2e%2e%2fpackage.json',
                   '/vendor/three/..%2f..%2f..%2fgoblin.yaml', '/studio.js/../../etc/passwd', '//etc/passwd',
                   '/vendor/three/build/..%252f..%252fpackage.json', '/node_modules/three/package.json', '/index.html/..']) {
    const r = await raw(url, 'GET', p);
    ok(r.status === 404 && !r.body.toString().includes('root:'), `GET ${p} is 404`);
  }
  ok((await raw(url, 'GET', '/vendor/three/build/three.module.js')).status === 200, 'three.js is served');
  ok((await raw(url, 'GET', '/')).body.toString().includes('rockbake studio'), 'the page is served');
  const big = await rawPost(url, '/api/edit', 'x'.repeat(2 * 1024 * 1024));
  ok(big.status === 413 && big.body.includes('at most 1 MiB'), `a 2 MB body gets 413 with a message (${big.status} ${big.body})`);
  await still('a 2 MB body');
  const bad = await raw(url, 'POST', '/api/edit', '{"durability": {"points": [[0, 1], ', { 'Content-Type': 'application/json' });
  ok(bad.status === 400 && JSON.parse(bad.body.toString()).error.includes('not valid JSON'), 'malformed JSON gets 400 with a message');
  const range = await api(url, '/api/edit', { durability: { points: [[0, 1], [0.5, -2], [1, 1]] } });
  ok(range.status === 400 && range.json.error.includes('durability.points.1.1'), `an out-of-range point gets 400 naming it: ${range.json.error}`);
  const order = await api(url, '/api/edit', { durability: { points: [[0, 1], [1.5, 2]] } });
  ok(order.status === 400 && order.json.error.includes('durability.points'), 'an altitude past 1 gets 400');
  const unknown = await api(url, '/api/edit', { grid: { resolution: 200 } });
  ok(unknown.status === 400 && unknown.json.error.includes('grid'), 'editing the grid is refused');
  const huge = await api(url, '/api/edit', { bubbles: [{ up_to: 1, bubble: { sphere: { radius: 1.9 } } }] });
  ok(huge.status === 400 && huge.json.error.includes('margin'), `a bubble larger than the margin is refused: ${huge.json.error}`);
  ok((await api(url, '/api/control', { seek: -1 })).status === 400, 'a negative seek gets 400');
  ok((await api(url, '/api/control', { action: 'fly' })).status === 400, 'an unknown action gets 400');
  ok((await api(url, '/api/save', { name: '../evil' })).status === 400 && !fs.existsSync(path.join(dir, '..', 'evil.yaml')),
    'a save name with a path gets 400 and writes nothing');
  const rainbow = await api(url, '/api/mesh?palette=rainbow');
  ok(rainbow.status === 400 && rainbow.json.error === 'palette: expected natural, debug or curvature',
    'an unknown palette gets 400 naming the preset\'s palettes');
  ok((await api(url, '/api/mesh?palette=durability')).status === 200, 'durability is the debug palette\'s other name');
  await still('the bad requests');

  // Play runs on its own; pause stops it.
  await api(url, '/api/control', { action: 'play' });
  await new Promise((r) => setTimeout(r, 1500));
  s = (await api(url, '/api/control', { action: 'pause' })).json;
  ok(s.cycle > 7 && !s.playing, `play runs cycles in the background (cycle ${s.cycle})`);
  const mesh = await api(url, '/api/mesh?palette=curvature');
  ok(mesh.status === 200 && mesh.body.subarray(0, 4).toString() === 'RBPM' && mesh.body.readUInt32LE(12) > 100,
    'the preview mesh has the rock');

  // Bake final: the normal bake of what is on screen, at the preset's own resolution, with progress.
  const early = await api(url, '/api/final/rock.glb');
  ok(early.status === 404 && early.json.error.startsWith('no final bake has finished'),
    `the final view's GLB before any bake gets 404 saying what to do: ${early.json.error}`);
  const now = (await api(url, '/api/state')).json;
  const started = await api(url, '/api/bake', {});
  ok(started.status === 202 && started.json.asset_dir === path.join(finalOut, 'goblin'), `bake final starts (${started.status})`);
  ok((await api(url, '/api/bake', {})).status === 409, 'a second bake final while one runs gets 409');
  let bake = null;
  const progress = new Set();
  for (const deadline = Date.now() + 240000; Date.now() < deadline;) {
    bake = (await api(url, '/api/state')).json.bake;
    if (bake.state !== 'running') break;
    progress.add(bake.message);
    await new Promise((r) => setTimeout(r, 100));
  }
  ok(bake.state === 'done' && bake.progress === 1, `bake final finishes (${JSON.stringify(bake)})`);
  ok(progress.has('simulate') && progress.has('mesh'), `the page sees the bake's stages (${[...progress]})`);
  const asset = path.join(finalOut, 'goblin');
  for (const f of ['manifest.json', 'asset.json', 'rock.glb', 'rock.vdb', 'render.png'])
    ok(fs.existsSync(path.join(asset, f)), `bake final writes ${f}`);
  // The page's final view reads the finished bake's LOD0 and its maps, and nothing else there.
  for (const f of ['rock.glb', 'textures/goblin_BaseColor.png', 'textures/goblin_History.png']) {
    const served = await api(url, `/api/final/${f}`);
    ok(served.status === 200 && Buffer.compare(served.body, fs.readFileSync(path.join(asset, f))) === 0,
      `GET /api/final/${f} is the bake's file, byte for byte (${served.status})`);
  }
  // (A parent step is refused by the route's pattern before the folder rule is reached.)
  for (const f of ['asset.json', 'rock.vdb', 'textures/goblin_Height.exr', 'textures/..%2Fasset.json', 'textures/missing.png'])
    ok((await api(url, `/api/final/${f}`)).status === 404, `GET /api/final/${f} gets 404`);
  // A link in the folder that leads out of it is not followed.
  fs.symlinkSync(path.join(dir, 'goblin.yaml'), path.join(asset, 'textures', 'outside.png'));
  ok((await api(url, '/api/final/textures/outside.png')).status === 404, 'a link out of the bake\'s folder gets 404');
  const manifest = JSON.parse(fs.readFileSync(path.join(asset, 'stats.json'), 'utf8'));
  ok(manifest.preset.grid.resolution === 96 && manifest.preset.time === now.time,
    `bake final bakes the preset's own resolution at the studio's time (${manifest.preset.grid.resolution}, ${manifest.preset.time})`);
  // The same as the saved preset baked from the command line.
  ok((await api(url, '/api/save', { name: 'goblin-final' })).status === 200, 'save at the bake\'s time');
  // Under the studio's asset name: the GLBs name their maps by it (textures/goblin_BaseColor.png).
  const cli = spawnSync(rockbake, ['bake', path.join(dir, 'goblin-final.yaml'), '--no-render', '--set', 'name=goblin',
    '-o', path.join(dir, 'cli')], { encoding: 'utf8' });
  ok(cli.status === 0, `the saved preset bakes (${cli.stderr})`);
  for (const f of ['rock.vdb', 'rock.glb', 'rock_lod4.glb', 'textures/goblin_BaseColor.png', 'textures/goblin_Normal_LOD4.png'])
    ok(Buffer.compare(fs.readFileSync(path.join(asset, f)), fs.readFileSync(path.join(dir, 'cli', 'goblin', f))) === 0,
      `bake final's ${f} is the saved preset's, byte for byte`);
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
