// The review page (docs/review.md): a baked library's grid with filters and
// sort, failed jobs, an asset view (turntable movie, 3-D view of the GLB, stats,
// the preset), a compare view with cameras in step, and verdicts saved to
// OUT/review.json through POST /api/review.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

const $ = (id) => document.getElementById(id);
const state = { assets: [], selected: new Set(), current: null };
window.reviewState = state;
// For scripts and the browser test: the 3-D views once made.
window.reviewViewers = () => ({ asset: assetViewer, compare: compareViewers });

function message(text) { $('message').textContent = text || ''; }

async function api(path, body) {
  const r = await fetch(path, body === undefined ? {} : {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body),
  });
  const json = await r.json().catch(() => ({}));
  if (!r.ok) throw new Error(json.error || `${path}: HTTP ${r.status}`);
  return json;
}

// ---- the grid ----

const FILTERS = ['preset', 'wedge', 'seed', 'tag', 'status', 'verdict'];

function verdictOf(a) {
  if (!a.review) return 'none';
  return a.review.stale ? 'stale' : a.review.status;
}

function valuesOf(a, key) {
  if (key === 'tag') return a.tags || [];
  if (key === 'verdict') return [verdictOf(a)];
  const v = a[key];
  return v === null || v === undefined ? [] : [String(v)];
}

function fillFilters() {
  for (const key of FILTERS) {
    const select = $(`f-${key}`);
    const keep = select.value;
    const values = new Set();
    for (const a of state.assets) for (const v of valuesOf(a, key)) values.add(v);
    if (key === 'verdict') ['none', 'approved', 'needs-work', 'rejected', 'stale'].forEach((v) => values.add(v));
    select.replaceChildren(new Option('any', ''));
    for (const v of [...values].sort(naturalCompare)) select.add(new Option(v, v));
    select.value = [...values].includes(keep) ? keep : '';
  }
}

function naturalCompare(a, b) { return String(a).localeCompare(String(b), undefined, { numeric: true }); }

function visibleAssets() {
  const chosen = Object.fromEntries(FILTERS.map((k) => [k, $(`f-${k}`).value]));
  const list = state.assets.filter((a) => FILTERS.every((k) => !chosen[k] || valuesOf(a, k).includes(chosen[k])));
  const sort = $('sort').value;
  if (sort === 'name') list.sort((a, b) => naturalCompare(a.name, b.name));
  else list.sort((a, b) => (b[sort] ?? -Infinity) - (a[sort] ?? -Infinity) || naturalCompare(a.name, b.name));
  return list;
}

function badge(a) {
  const span = document.createElement('span');
  span.className = 'badge';
  if (a.review) {
    span.classList.add(a.review.status);
    if (a.review.stale) span.classList.add('stale');
    span.textContent = a.review.status + (a.review.stale ? ' (stale)' : '');
    span.title = a.review.note;
  } else {
    span.textContent = 'unreviewed';
  }
  span.dataset.verdict = verdictOf(a);
  return span;
}

function drawGrid() {
  const grid = $('grid');
  const list = visibleAssets();
  grid.replaceChildren();
  for (const a of list.filter((x) => x.status === 'ok' || x.status === 'skipped-resumed')) {
    const tile = document.createElement('div');
    tile.className = 'tile';
    tile.dataset.name = a.name;
    const img = document.createElement('img');
    img.alt = a.name;
    if (a.files.render) img.src = a.files.render;
    const pick = document.createElement('input');
    pick.type = 'checkbox';
    pick.title = 'compare';
    pick.checked = state.selected.has(a.name);
    pick.addEventListener('click', (e) => {
      e.stopPropagation();
      if (pick.checked) state.selected.add(a.name); else state.selected.delete(a.name);
      $('compare').disabled = state.selected.size !== 2;
    });
    const caption = document.createElement('div');
    caption.className = 'caption';
    const name = document.createElement('span');
    name.textContent = a.name;
    const status = document.createElement('span');
    status.className = 'status';
    status.textContent = a.status === 'ok' ? 'baked' : a.status;
    caption.append(name, status, badge(a));
    tile.append(img, pick, caption);
    tile.addEventListener('click', () => openAsset(a.name));
    grid.append(tile);
  }
  const failed = $('failed');
  failed.replaceChildren();
  const bad = list.filter((x) => x.status === 'failed' || x.status === 'damaged' || x.status === 'unreadable');
  if (bad.length) {
    const h = document.createElement('h3');
    h.textContent = `Failed jobs (${bad.length})`;
    failed.append(h);
    for (const a of bad) {
      const div = document.createElement('div');
      div.className = 'job';
      div.dataset.name = a.name;
      div.textContent = `${a.name} (${a.status}): ${a.message || ''}`;
      failed.append(div);
    }
  }
  $('count').textContent = `${grid.children.length} of ${state.assets.length} assets shown`;
}

async function refresh() {
  const { assets } = await api('/api/assets');
  state.assets = assets;
  fillFilters();
  drawGrid();
}

// ---- the 3-D view ----

// The compressed set's decoders (docs/delivery.md): three's KTX2Loader with the Basis Universal
// transcoder and the meshopt decoder, both from the pinned three.js, imported the first time a
// compressed GLB is shown. One KTX2Loader for the page (it owns a pool of workers).
let compressedDecoders = null;
function decodersFor(renderer) {
  if (!compressedDecoders) {
    compressedDecoders = Promise.all([
      import('three/addons/loaders/KTX2Loader.js'),
      import('three/addons/libs/meshopt_decoder.module.js'),
    ]).then(([{ KTX2Loader }, { MeshoptDecoder }]) => ({
      ktx2: new KTX2Loader().setTranscoderPath('/vendor/three/examples/jsm/libs/basis/').detectSupport(renderer),
      meshopt: MeshoptDecoder,
    }));
    compressedDecoders.catch(() => { compressedDecoders = null; });
  }
  return compressedDecoders;
}

class Viewer {
  constructor(canvas) {
    this.canvas = canvas;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setSize(canvas.width, canvas.height, false);
    this.renderer.setClearColor(0x2e2e2e);
    this.scene = new THREE.Scene();
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x444444, 1.2));
    const key = new THREE.DirectionalLight(0xffffff, 2.0);
    key.position.set(-3, 5, 4);
    this.scene.add(key);
    this.camera = new THREE.PerspectiveCamera(40, canvas.width / canvas.height, 0.01, 1000);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener('change', () => this.draw());
    this.model = null;
    this.history = null;       // the History map of the LOD shown (a texture), or null
    this.textures = new Map(); // History maps by URL: promises of textures
    this.channel = 'lit';
    this.wireframe = false;
    this.framed = false;
  }

  // Shows the GLB at `url`; `history`: the URL of that LOD's History map, or null; `compressed`:
  // a GLB of the compressed set (KTX2 maps, meshopt meshes).
  async load(url, history = null, compressed = false) {
    const loader = new GLTFLoader();
    if (compressed) {
      const { ktx2, meshopt } = await decodersFor(this.renderer);
      loader.setKTX2Loader(ktx2).setMeshoptDecoder(meshopt);
    }
    const [gltf, map] = await Promise.all([
      loader.loadAsync(url),
      history ? this.historyTexture(history).catch((e) => {
        message(`cannot load ${history} (${e.message}): the history channels show the vertex attribute`);
        return null;
      }) : null,
    ]);
    if (this.model) this.scene.remove(this.model);
    this.model = gltf.scene;
    this.history = map;
    this.model.traverse((o) => { if (o.isMesh) o.userData.original = o.material; });
    this.scene.add(this.model);
    if (!this.framed) this.frame();
    this.applyChannel();
    this.canvas.dataset.drawn = url;
    this.canvas.dataset.set = compressed ? 'compressed' : 'full';
  }

  // The History map at `url` as a texture: linear RGBA data, read as stored (not premultiplied, no
  // colour conversion: where A, the dust, is 0 the RGB must survive), glTF's uv origin (no flip).
  historyTexture(url) {
    if (!this.textures.has(url)) {
      const loader = new THREE.ImageBitmapLoader().setOptions({ premultiplyAlpha: 'none', colorSpaceConversion: 'none' });
      const promise = loader.loadAsync(url).then((bitmap) => {
        const texture = new THREE.Texture(bitmap);
        texture.name = url;
        texture.flipY = false;
        texture.needsUpdate = true;
        return texture;
      });
      promise.catch(() => this.textures.delete(url));
      this.textures.set(url, promise);
    }
    return this.textures.get(url);
  }

  frame() {
    const box = new THREE.Box3().setFromObject(this.model);
    const centre = box.getCenter(new THREE.Vector3());
    const radius = box.getSize(new THREE.Vector3()).length() / 2 || 1;
    const distance = radius / Math.sin(THREE.MathUtils.degToRad(this.camera.fov / 2));
    this.camera.position.copy(centre).add(new THREE.Vector3(0.6, 0.45, 0.8).normalize().multiplyScalar(distance));
    this.camera.near = distance / 100;
    this.camera.far = distance * 10;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
    this.framed = true;
  }

  // The material a channel shows: the glTF material's maps when it has them
  // (textures/), else the vertex colours (COLOR_0) and the packed mask (COLOR_1).
  // history / history-dust: the look's History (docs/textures.md) on the meshes
  // that have one (`_HISTORY`), unlit: the LOD's History map through TEXCOORD_0
  // on the rock and colluvium surfaces where the LOD has one, else the
  // `_HISTORY` attribute; RGB (age, stain and varnish, moisture) or A (dust) as
  // grey. Black without a look, as mask without COLOR_1.
  channelMaterial(mesh) {
    const m = mesh.userData.original;
    const geometry = mesh.geometry;
    const wireframe = this.wireframe;
    switch (this.channel) {
      case 'base':
        return new THREE.MeshBasicMaterial({ map: m.map || null, vertexColors: !m.map && !!geometry.attributes.color, wireframe });
      case 'normals':
        return m.normalMap ? new THREE.MeshBasicMaterial({ map: m.normalMap, wireframe })
                           : new THREE.MeshNormalMaterial({ wireframe });
      case 'ao':
        return m.aoMap ? new THREE.MeshBasicMaterial({ map: m.aoMap, wireframe })
                       : new THREE.MeshBasicMaterial({ color: 0xffffff, wireframe });
      case 'mask': {
        const mask = geometry.attributes.color_1;
        if (!mask) return new THREE.MeshBasicMaterial({ color: 0x000000, wireframe });
        if (!geometry.attributes.maskColor) {
          const rgb = new Float32Array(mask.count * 3);
          for (let i = 0; i < mask.count; ++i) {
            rgb[3 * i] = mask.getX(i); rgb[3 * i + 1] = mask.getY(i); rgb[3 * i + 2] = mask.getZ(i);
          }
          geometry.setAttribute('maskColor', new THREE.BufferAttribute(rgb, 3));
        }
        const material = new THREE.MeshBasicMaterial({ vertexColors: true, wireframe });
        material.onBeforeCompile = (shader) => {
          shader.vertexShader = shader.vertexShader
            .replace('#include <common>', '#include <common>\nattribute vec3 maskColor;')
            .replace('#include <color_vertex>', 'vColor = maskColor;');
        };
        return material;
      }
      case 'history':
      case 'history-dust': {
        const swizzle = this.channel === 'history' ? 'rgb' : 'aaa';
        const history = geometry.attributes._history;  // GLTFLoader's name for _HISTORY
        if (!history) return new THREE.MeshBasicMaterial({ color: 0x000000, wireframe });
        // The map is the rock's and the colluvium's (their materials' names end so, after the
        // asset's or the profile's prefix: docs/delivery.md); the stones have their own uvs and
        // their own _HISTORY.
        if (this.history && geometry.attributes.uv && /(^|_)(rock|colluvium)$/.test(m.name)) {
          const material = new THREE.MeshBasicMaterial({ map: this.history, wireframe });
          material.onBeforeCompile = (shader) => {
            shader.fragmentShader = shader.fragmentShader
              .replace('#include <map_fragment>', `diffuseColor.rgb *= texture2D( map, vMapUv ).${swizzle};`);
          };
          material.customProgramCacheKey = () => `history-map-${swizzle}`;
          return material;
        }
        if (!geometry.attributes.historyRgba) geometry.setAttribute('historyRgba', history);
        const material = new THREE.MeshBasicMaterial({ vertexColors: true, wireframe });
        material.onBeforeCompile = (shader) => {
          shader.vertexShader = shader.vertexShader
            .replace('#include <common>', '#include <common>\nattribute vec4 historyRgba;')
            .replace('#include <color_vertex>', `vColor = historyRgba.${swizzle};`);
        };
        material.customProgramCacheKey = () => `history-vertex-${swizzle}`;
        return material;
      }
      default: {
        const material = m.clone();
        material.wireframe = wireframe;
        return material;
      }
    }
  }

  applyChannel() {
    if (!this.model) return;
    this.model.traverse((o) => { if (o.isMesh) o.material = this.channelMaterial(o); });
    this.draw();
  }

  draw() { this.renderer.render(this.scene, this.camera); }

  // The model's bounding box on the canvas, in canvas pixels {x0, y0, x1, y1}.
  screenBox() {
    const box = new THREE.Box3().setFromObject(this.model);
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (let i = 0; i < 8; ++i) {
      const p = new THREE.Vector3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z)
        .project(this.camera);
      const x = (p.x + 1) / 2 * this.canvas.width, y = (1 - p.y) / 2 * this.canvas.height;
      x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
    }
    const clamp = (v, hi) => Math.max(0, Math.min(hi, Math.round(v)));
    return { x0: clamp(x0, this.canvas.width), y0: clamp(y0, this.canvas.height),
             x1: clamp(x1, this.canvas.width), y1: clamp(y1, this.canvas.height) };
  }
}

let assetViewer = null;

// The URL of the History map (asset.json's maps, type history) of the LOD whose GLB is at
// `glb` (a files.lods link), or null: the bake had no look, or no texture set.
function historyMapOf(d, glb) {
  const lod = (d.files?.lods || []).find((l) => l.file === glb);
  const maps = Array.isArray(d.asset?.maps) ? d.asset.maps : [];
  const map = lod && maps.find((m) => m && m.type === 'history' && m.lod === lod.level && typeof m.file === 'string');
  return map ? `/files/${d.name}/${map.file}` : null;
}

// The GLB to show for the LOD and set chosen: a LOD's file in the compressed set is the full set's
// name inside the set's folder (asset.json's sets.compressed.folder).
function chosenGlb() {
  const glb = $('a-lod').value;
  const folder = state.current?.compressedFolder;
  if (!glb || $('a-set').value !== 'compressed' || !folder) return { url: glb, compressed: false };
  return { url: glb.replace(/\/([^/]*)$/, `/${encodeURIComponent(folder)}/$1`), compressed: true };
}

// Shows the chosen LOD of the chosen set. The compressed set's uvs are quantised (with a texture
// transform on the materials' maps), so the History map, read by the vertex uvs, is the full set's alone.
function showChosen() {
  const { url, compressed } = chosenGlb();
  if (!url) return Promise.resolve();
  return assetViewer.load(url, compressed ? null : historyMapOf(state.current, url), compressed)
    .catch((e) => message(`cannot show ${url}: ${e.message}`));
}

// asset.json's "sets" as rows: each set's download and GPU memory, in MB.
function setRows(sets) {
  const mb = (bytes) => (Number(bytes) / 1e6).toFixed(2);
  return Object.entries(sets || {}).filter(([, s]) => s && typeof s === 'object')
    .map(([name, s]) => [`${name} set: download / GPU (MB)`, `${mb(s.download_bytes)} / ${mb(s.gpu_bytes)}`]);
}

function statRows(d) {
  const rows = [['status', d.status], ['preset', d.preset], ['wedge', d.wedge], ['seed', d.seed],
    ['tags', (d.tags || []).join(', ')], ['size (m)', (d.size_m || []).map((x) => x.toFixed(3)).join(' × ')],
    ['texel density', d.texel_density ?? '—'], ['bake time (s)', d.bake_seconds?.toFixed(2)],
    ['input hash', d.input_hash]];
  for (const lod of d.lods || []) rows.push([`LOD${lod.level} triangles`, lod.triangles]);
  for (const [stage, s] of Object.entries(d.stages || {})) rows.push([`${stage} (s)`, Number(s).toFixed(3)]);
  rows.push(...setRows(d.sets));
  return rows;
}

function showVerdict(review) {
  for (const b of $('a-verdict').querySelectorAll('button')) b.classList.toggle('on', review?.status === b.dataset.status);
  $('a-stale').textContent = review?.stale ? 'stale: the asset was baked again with other inputs' : '';
  $('a-note').disabled = !review;
  if (document.activeElement !== $('a-note')) $('a-note').value = review?.note || '';
}

// asset.json's "sets", or null: an asset without a compressed set, or an asset.json that cannot be read.
async function setsOf(d) {
  if (!d.files?.asset) return null;
  try {
    const r = await fetch(d.files.asset);
    if (!r.ok) return null;
    const sets = (await r.json())?.sets;
    return sets && typeof sets === 'object' ? sets : null;
  } catch {
    return null;
  }
}

async function openAsset(name) {
  const d = await api(`/api/assets/${encodeURIComponent(name)}`);
  d.sets = await setsOf(d);
  const folder = d.sets?.compressed?.folder;
  d.compressedFolder = typeof folder === 'string' && /^[\w.-]+$/.test(folder) && folder !== '..' ? folder : null;
  state.current = d;
  $('a-set').value = 'full';
  $('a-set').disabled = !d.compressedFolder;
  $('a-set').title = d.compressedFolder ? 'the full set (PNG maps) or the compressed set (KTX2 maps, meshopt meshes)'
    : 'this asset has no compressed set (delivery.compressed)';
  $('a-name').textContent = d.name;
  $('a-movie').hidden = !d.files.movie;
  if (d.files.movie) $('a-movie').src = d.files.movie; else $('a-movie').removeAttribute('src');
  $('a-stats').replaceChildren(...statRows(d).map(([k, v]) => {
    const tr = document.createElement('tr');
    tr.innerHTML = '<td></td><td></td>';
    tr.cells[0].textContent = k;
    tr.cells[1].textContent = v ?? '—';
    return tr;
  }));
  $('a-preset').textContent = JSON.stringify(d.bake_preset, null, 2);
  const lod = $('a-lod');
  lod.replaceChildren(...d.files.lods.filter((l) => l.file.endsWith('.glb'))
    .map((l) => new Option(`LOD${l.level} (${l.triangles})`, l.file)));
  showVerdict(d.review);
  $('asset-view').showModal();
  if (!assetViewer) assetViewer = new Viewer($('a-canvas'));
  assetViewer.framed = false;
  await showChosen();
}

async function saveVerdict(status, note) {
  const d = state.current;
  try {
    const r = await api('/api/review', { asset: d.name, status, note });
    d.review = r.review;
    const a = state.assets.find((x) => x.name === d.name);
    if (a) a.review = r.review;
    showVerdict(r.review);
    drawGrid();
    message('');
  } catch (e) {
    message(`not saved: ${e.message}`);
  }
}

// ---- compare: two views, one camera ----

let compareViewers = null;

async function openCompare() {
  const [left, right] = [...state.selected];
  $('c-title').textContent = `${left} | ${right}`;
  $('c-left-name').textContent = left;
  $('c-right-name').textContent = right;
  $('compare-view').showModal();
  if (!compareViewers) {
    compareViewers = [new Viewer($('c-left')), new Viewer($('c-right'))];
    const [a, b] = compareViewers;
    let syncing = false;
    const follow = (from, to) => () => {
      if (syncing) return;
      syncing = true;
      to.camera.position.copy(from.camera.position);
      to.camera.quaternion.copy(from.camera.quaternion);
      to.controls.target.copy(from.controls.target);
      to.controls.update();
      to.draw();
      syncing = false;
    };
    a.controls.addEventListener('change', follow(a, b));
    b.controls.addEventListener('change', follow(b, a));
  }
  const detail = await Promise.all([left, right].map((n) => api(`/api/assets/${encodeURIComponent(n)}`)));
  const [a, b] = compareViewers;
  a.framed = false;
  await a.load(detail[0].files.lods[0].file);
  b.framed = true;  // the right view takes the left one's camera
  await b.load(detail[1].files.lods[0].file);
  b.camera.position.copy(a.camera.position);
  b.camera.near = a.camera.near; b.camera.far = a.camera.far;
  b.camera.updateProjectionMatrix();
  b.controls.target.copy(a.controls.target);
  b.controls.update();
  a.draw(); b.draw();
}

// ---- wiring ----

for (const key of FILTERS) $(`f-${key}`).addEventListener('change', drawGrid);
$('sort').addEventListener('change', drawGrid);
$('compare').addEventListener('click', () => openCompare().catch((e) => message(e.message)));
$('a-close').addEventListener('click', () => { $('a-movie').pause(); $('asset-view').close(); });
$('c-close').addEventListener('click', () => $('compare-view').close());
$('a-lod').addEventListener('change', showChosen);
$('a-set').addEventListener('change', showChosen);
$('a-wire').addEventListener('change', () => { assetViewer.wireframe = $('a-wire').checked; assetViewer.applyChannel(); });
$('a-channel').addEventListener('change', () => { assetViewer.channel = $('a-channel').value; assetViewer.applyChannel(); });
for (const b of $('a-verdict').querySelectorAll('button'))
  b.addEventListener('click', () => saveVerdict(b.dataset.status, $('a-note').value));
let noteTimer = null;
$('a-note').addEventListener('input', () => {
  clearTimeout(noteTimer);
  noteTimer = setTimeout(() => { if (state.current?.review) saveVerdict(state.current.review.status, $('a-note').value); }, 300);
});
$('library').textContent = location.host;
refresh().catch((e) => message(e.message));
