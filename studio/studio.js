// rockbake studio page: talks to the server only through the JSON API of
// docs/studio.md. The 3-D view shows the preview mesh (GET /api/mesh); the
// durability and bubble graphs sit beside it with altitude on the same screen
// scale as the rock, so a point dragged to a height edits the rock at that height.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);

// ---------------------------------------------------------------- API
let messageTimer = null;
function showMessage(text, ok = false) {
  const m = $('message');
  m.textContent = text;
  m.className = ok ? 'ok' : '';
  clearTimeout(messageTimer);
  messageTimer = setTimeout(() => { m.textContent = ''; }, ok ? 5000 : 15000);
}

async function api(path, body) {
  const options = body === undefined ? {} :
    { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) };
  let response;
  try {
    response = await fetch(path, options);
  } catch (e) {
    showMessage(`no answer from the studio server (${e.message}); is rockbake studio still running?`);
    throw e;
  }
  const data = await response.json().catch(() => ({}));
  if (!response.ok) {
    showMessage(data.error || `${path}: HTTP ${response.status}`);
    const error = new Error(data.error || response.statusText);
    error.status = response.status;
    throw error;
  }
  return data;
}

// ---------------------------------------------------------------- state
let state = null;        // last GET /api/state
let active = null;       // {durability, bubbles, response} in effect now (editable copy)
let dragging = null;     // what a pointer is dragging; polls leave `active` alone meanwhile
let selectedSegment = 0;
let selectedBand = 0;
let timelineHeld = false;

function copy(x) { return JSON.parse(JSON.stringify(x)); }

function applyState(s) {
  state = s;
  if (!dragging) active = copy(s.active);
  $('preset-name').textContent = `${s.preset.name} · ${s.grid.nx}×${s.grid.ny}×${s.grid.nz} voxels (resolution ${s.resolution})`;
  $('stat-cycle').textContent = s.cycle;
  $('stat-time').textContent = s.time.toFixed(3);
  $('stat-rock').textContent = s.rock;
  $('stat-exposed').textContent = s.exposed;
  $('stat-colluvium').textContent = s.colluvium;
  $('stat-keyframes').textContent = s.preset.durability.keyframes.length;
  $('play').textContent = s.playing ? 'pause' : 'play';
  const timeline = $('timeline');
  timeline.max = s.end_time;
  timeline.step = s.h;
  if (!timelineHeld) timeline.value = s.time;
  $('time-readout').textContent = `t = ${s.time.toFixed(2)} / ${s.end_time.toFixed(2)}${s.finished ? ' (end)' : ''}`;
  if (!$('save-name').value) $('save-name').value = `${s.preset.name}-edited`;
  const bake = s.bake;
  $('bake-progress').value = bake.progress;
  $('bake-status').textContent = bake.state === 'idle' ? '' : `${bake.state}: ${bake.message}`;
  if (document.activeElement?.tagName !== 'INPUT' && document.activeElement?.tagName !== 'SELECT') fillEditors();
  drawVolumePlot();
}

async function refresh() {
  try {
    applyState(await api('/api/state'));
  } catch (e) { /* shown */ }
}

async function control(body) {
  try { applyState(await api('/api/control', body)); } catch (e) { /* shown */ }
}

async function edit(part) {
  try {
    applyState(await api('/api/edit', part));
  } catch (e) {
    await refresh();  // back to what the server has
  }
}

// ---------------------------------------------------------------- 3-D view
const view = $('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
const background = new THREE.Color(0x30343a);
scene.background = background;
const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
camera.up.set(0, 0, 1);
const controls = new OrbitControls(camera, renderer.domElement);
controls.enableDamping = false;
scene.add(new THREE.HemisphereLight(0xdfe8ff, 0x4a4036, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 2.0);
sun.position.set(3, -4, 6);
scene.add(sun);
const groundMaterial = new THREE.MeshStandardMaterial({ color: 0x4d4a45, roughness: 1 });
const ground = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), groundMaterial);
scene.add(ground);
const surfaceMaterial = new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.9, side: THREE.DoubleSide });
const rockMesh = new THREE.Mesh(new THREE.BufferGeometry(), surfaceMaterial);
const colluviumMesh = new THREE.Mesh(new THREE.BufferGeometry(), surfaceMaterial);
scene.add(rockMesh, colluviumMesh);
let framed = false;
let loadedMesh = { version: -1, palette: '' };
let meshLoading = false;

function frameCamera() {
  const g = state.grid;
  const [sx, sy, sz] = state.preset.grid.size;
  const target = new THREE.Vector3(sx / 2, sy / 2, sz / 2);
  controls.target.copy(target);
  const distance = 1.9 * Math.max(sx, sy, sz) / Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)) / 2;
  camera.position.set(target.x + distance * 0.75, target.y - distance * 0.65, target.z + distance * 0.18);
  ground.scale.set(sx * 2.5, sy * 2.5, 1);
  ground.position.set(sx / 2, sy / 2, -0.002 * g.h);
  controls.update();
  framed = true;
}

// Binary preview mesh (docs/studio.md): "RBPM", version, cycle, then rock and
// colluvium: vertex count, triangle count, positions, linear RGB colours, indices.
function readMeshes(buffer) {
  const view32 = new DataView(buffer);
  const magic = String.fromCharCode(...new Uint8Array(buffer, 0, 4));
  if (magic !== 'RBPM') throw new Error('not a preview mesh');
  let offset = 12;
  const meshes = [];
  for (let m = 0; m < 2; ++m) {
    const vertices = view32.getUint32(offset, true);
    const triangles = view32.getUint32(offset + 4, true);
    offset += 8;
    const positions = new Float32Array(buffer.slice(offset, offset + 12 * vertices)); offset += 12 * vertices;
    const colours = new Float32Array(buffer.slice(offset, offset + 12 * vertices)); offset += 12 * vertices;
    const indices = new Uint32Array(buffer.slice(offset, offset + 12 * triangles)); offset += 12 * triangles;
    meshes.push({ positions, colours, indices });
  }
  return meshes;
}

function setGeometry(mesh, data) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(data.positions, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(data.colours, 3));
  geometry.setIndex(new THREE.BufferAttribute(data.indices, 1));
  geometry.computeVertexNormals();
  mesh.geometry.dispose();
  mesh.geometry = geometry;
}

async function updateMesh() {
  if (!state || meshLoading) return;
  const palette = $('palette').value;
  if (loadedMesh.version === state.mesh_version && loadedMesh.palette === palette) return;
  meshLoading = true;
  try {
    const response = await fetch(`/api/mesh?palette=${palette}`);
    if (!response.ok) throw new Error(`GET /api/mesh: HTTP ${response.status}`);
    const version = Number(response.headers.get('X-Mesh-Version'));
    const [rock, colluvium] = readMeshes(await response.arrayBuffer());
    setGeometry(rockMesh, rock);
    setGeometry(colluviumMesh, colluvium);
    loadedMesh = { version, palette };
    window.studio.meshVersion = version;
    window.studio.rockTriangles = rock.indices.length / 3;
  } catch (e) {
    showMessage(e.message);
  } finally {
    meshLoading = false;
  }
}

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(1, h);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);

// Page y (CSS pixels) of altitude a (0 ground, 1 top of grid.size) above the grid's centre.
function altitudeToPageY(a) {
  const [sx, sy, sz] = state.preset.grid.size;
  const p = new THREE.Vector3(sx / 2, sy / 2, a * sz).project(camera);
  const rect = renderer.domElement.getBoundingClientRect();
  return rect.top + (1 - (p.y + 1) / 2) * rect.height;
}

// ---------------------------------------------------------------- graphs
function fitCanvas(canvas) {
  const r = canvas.getBoundingClientRect();
  const dpr = window.devicePixelRatio || 1;
  if (canvas.width !== Math.round(r.width * dpr) || canvas.height !== Math.round(r.height * dpr)) {
    canvas.width = Math.round(r.width * dpr);
    canvas.height = Math.round(r.height * dpr);
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  return { ctx, w: r.width, h: r.height, rect: r };
}

// Canvas-local y of altitudes 0 and 1: the rock's own height scale, kept on the canvas.
function altitudeAxis(rect) {
  let y0 = altitudeToPageY(0) - rect.top, y1 = altitudeToPageY(1) - rect.top;
  if (!(y0 - y1 > 40)) { y0 = rect.height - 12; y1 = 12; }
  return { y0, y1, toY: (a) => y0 + (y1 - y0) * a, toA: (y) => (y - y0) / (y1 - y0) };
}

let durabilityScale = 3;
function durabilityAxis(w) {
  const left = 10, right = w - 10;
  return { toX: (d) => left + (right - left) * d / durabilityScale, toD: (x) => (x - left) / (right - left) * durabilityScale };
}

// Paper Fig. 7: red hues for durable rock, blue for soft.
function durabilityColour(d) {
  const t = Math.max(0, Math.min(1, d / durabilityScale));
  return `hsl(${240 - 240 * t}, 75%, 58%)`;
}

function drawDurability() {
  const canvas = $('durability-graph');
  const { ctx, w, h, rect } = fitCanvas(canvas);
  ctx.clearRect(0, 0, w, h);
  if (!active) return;
  const ax = altitudeAxis(rect), dx = durabilityAxis(w);
  ctx.strokeStyle = '#3b4046';
  ctx.fillStyle = '#8a9096';
  ctx.font = '10px sans-serif';
  for (let d = 0; d <= durabilityScale + 1e-9; d += 0.5) {
    ctx.beginPath(); ctx.moveTo(dx.toX(d), ax.toY(0)); ctx.lineTo(dx.toX(d), ax.toY(1)); ctx.stroke();
    if (Math.abs(d - Math.round(d)) < 1e-9) ctx.fillText(String(d), dx.toX(d) + 2, ax.toY(0) + 11);
  }
  for (const a of [0, 1]) { ctx.beginPath(); ctx.moveTo(0, ax.toY(a)); ctx.lineTo(w, ax.toY(a)); ctx.stroke(); }
  const pts = active.durability.points, noise = active.durability.noise || [];
  for (let i = 0; i + 1 < pts.length; ++i) {
    const n = noise[i];
    const x0 = dx.toX(pts[i][1]), y0 = ax.toY(pts[i][0]), x1 = dx.toX(pts[i + 1][1]), y1 = ax.toY(pts[i + 1][0]);
    if (n) {  // a band showing the noise's amplitude
      ctx.fillStyle = 'rgba(224,160,96,0.18)';
      const a = dx.toX(n.amplitude) - dx.toX(0);
      ctx.beginPath(); ctx.moveTo(x0 - a, y0); ctx.lineTo(x1 - a, y1); ctx.lineTo(x1 + a, y1); ctx.lineTo(x0 + a, y0); ctx.fill();
    }
    const gradient = ctx.createLinearGradient(x0, y0, x1, y1);
    gradient.addColorStop(0, durabilityColour(pts[i][1]));
    gradient.addColorStop(1, durabilityColour(pts[i + 1][1]));
    ctx.strokeStyle = gradient;
    ctx.lineWidth = i === selectedSegment ? 4 : 2;
    ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1); ctx.stroke();
  }
  ctx.lineWidth = 1;
  for (let i = 0; i < pts.length; ++i) {
    ctx.fillStyle = dragging?.kind === 'durability' && dragging.index === i ? '#fff' : durabilityColour(pts[i][1]);
    ctx.beginPath(); ctx.arc(dx.toX(pts[i][1]), ax.toY(pts[i][0]), 5, 0, 2 * Math.PI); ctx.fill();
    ctx.strokeStyle = '#111'; ctx.stroke();
  }
}

function drawBubbles() {
  const canvas = $('bubble-graph');
  const { ctx, w, h, rect } = fitCanvas(canvas);
  ctx.clearRect(0, 0, w, h);
  if (!active) return;
  const ax = altitudeAxis(rect);
  const pixelsPerUnit = (ax.y0 - ax.y1) / state.preset.grid.size[2];
  let below = 0;
  active.bubbles.forEach((band, b) => {
    const yTop = ax.toY(band.up_to), yBottom = ax.toY(below);
    ctx.fillStyle = b === selectedBand ? 'rgba(224,160,96,0.20)' : (b % 2 ? 'rgba(255,255,255,0.05)' : 'rgba(255,255,255,0.09)');
    ctx.fillRect(0, yTop, w, yBottom - yTop);
    const kind = Object.keys(band.bubble)[0];
    const r = kind === 'sphere' ? band.bubble.sphere.radius : null;
    const cy = (yTop + yBottom) / 2;
    ctx.strokeStyle = '#d9dcdf';
    if (r !== null) { ctx.beginPath(); ctx.arc(w * 0.3, cy, Math.max(1.5, r * pixelsPerUnit), 0, 2 * Math.PI); ctx.stroke(); }
    ctx.fillStyle = '#d9dcdf';
    ctx.font = '10px sans-serif';
    ctx.fillText(r !== null ? `r ${r.toFixed(2)}` : kind, w * 0.55, cy - 6);
    ctx.fillText(`s ${band.spheroidal.toFixed(2)} c ${band.cavernous.toFixed(2)}`, w * 0.55, cy + 8);
    ctx.strokeStyle = '#e0a060';
    ctx.lineWidth = b + 1 < active.bubbles.length ? 2 : 1;
    ctx.beginPath(); ctx.moveTo(0, yTop); ctx.lineTo(w, yTop); ctx.stroke();
    ctx.lineWidth = 1;
    below = band.up_to;
  });
}

function responseAt(r, x) {
  if ('power' in r) return Math.pow(x, r.power);
  if ('threshold' in r) return Math.max(0, (x - r.threshold) / (1 - r.threshold));
  const c = r.curve;
  if (x <= c[0][0]) return c[0][1];
  for (let i = 1; i < c.length; ++i)
    if (x <= c[i][0]) return c[i - 1][1] + (x - c[i - 1][0]) / (c[i][0] - c[i - 1][0]) * (c[i][1] - c[i - 1][1]);
  return c[c.length - 1][1];
}

function responseAxes(w, h) {
  const m = 8;
  return { toX: (x) => m + x * (w - 2 * m), toY: (y) => h - m - y * (h - 2 * m),
           fromX: (px) => (px - m) / (w - 2 * m), fromY: (py) => (h - m - py) / (h - 2 * m) };
}

function drawResponse() {
  const canvas = $('response-graph');
  const { ctx, w, h } = fitCanvas(canvas);
  ctx.clearRect(0, 0, w, h);
  if (!active) return;
  const a = responseAxes(w, h);
  ctx.strokeStyle = '#3b4046';
  ctx.strokeRect(a.toX(0), a.toY(1), a.toX(1) - a.toX(0), a.toY(0) - a.toY(1));
  ctx.strokeStyle = '#e0a060';
  ctx.lineWidth = 2;
  ctx.beginPath();
  for (let i = 0; i <= 100; ++i) {
    const x = i / 100, y = responseAt(active.response, x);
    if (i === 0) ctx.moveTo(a.toX(x), a.toY(y)); else ctx.lineTo(a.toX(x), a.toY(y));
  }
  ctx.stroke();
  ctx.lineWidth = 1;
  if ('curve' in active.response)
    for (const [x, y] of active.response.curve) {
      ctx.fillStyle = '#fff';
      ctx.beginPath(); ctx.arc(a.toX(x), a.toY(y), 4, 0, 2 * Math.PI); ctx.fill();
    }
}

function drawVolumePlot() {
  const canvas = $('volume-plot');
  const { ctx, w, h } = fitCanvas(canvas);
  ctx.clearRect(0, 0, w, h);
  if (!state) return;
  const history = state.history;
  const tMax = Math.max(state.end_time, 1e-6), vMax = Math.max(state.initial_rock, 1);
  const X = (t) => 6 + (w - 12) * t / tMax, Y = (v) => h - 6 - (h - 12) * v / vMax;
  ctx.strokeStyle = '#3b4046';
  ctx.strokeRect(6, 6, w - 12, h - 12);
  ctx.strokeStyle = '#e0a060';
  ctx.beginPath();
  ctx.moveTo(X(0), Y(state.initial_rock));
  for (const [t, v] of history) ctx.lineTo(X(t), Y(v));
  ctx.stroke();
  ctx.strokeStyle = '#8fd18f';
  ctx.beginPath(); ctx.moveTo(X(state.time), 6); ctx.lineTo(X(state.time), h - 6); ctx.stroke();
  ctx.fillStyle = '#8a9096';
  ctx.font = '10px sans-serif';
  ctx.fillText(`rock volume ${(100 * state.rock / vMax).toFixed(1)}%`, 10, 17);
  for (const t of state.checkpoints) { ctx.fillRect(X(t) - 0.5, h - 10, 1, 4); }
}

// ---------------------------------------------------------------- editing
function pointerPos(canvas, event) {
  const r = canvas.getBoundingClientRect();
  return { x: event.clientX - r.left, y: event.clientY - r.top, rect: r };
}

function commitDurability() {
  edit({ durability: { points: active.durability.points, noise: active.durability.noise } });
}

function nearestSegment(pts, dx, ax, p) {
  let best = -1, bestDistance = 1e9;
  for (let i = 0; i + 1 < pts.length; ++i) {
    const x0 = dx.toX(pts[i][1]), y0 = ax.toY(pts[i][0]), x1 = dx.toX(pts[i + 1][1]), y1 = ax.toY(pts[i + 1][0]);
    const t = Math.max(0, Math.min(1, ((p.x - x0) * (x1 - x0) + (p.y - y0) * (y1 - y0)) / ((x1 - x0) ** 2 + (y1 - y0) ** 2 || 1)));
    const d = Math.hypot(p.x - (x0 + t * (x1 - x0)), p.y - (y0 + t * (y1 - y0)));
    if (d < bestDistance) { bestDistance = d; best = i; }
  }
  return { index: best, distance: bestDistance };
}

function setupDurabilityGraph() {
  const canvas = $('durability-graph');
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (event) => {
    if (!active) return;
    const p = pointerPos(canvas, event);
    const ax = altitudeAxis(p.rect), dx = durabilityAxis(p.rect.width);
    const pts = active.durability.points;
    const hit = pts.findIndex(([a, d]) => Math.hypot(dx.toX(d) - p.x, ax.toY(a) - p.y) < 9);
    if (hit >= 0 && event.button === 2) {  // remove a point; its two segments merge (the lower keeps its noise)
      if (pts.length <= 2) { showMessage('the durability graph needs at least two points'); return; }
      pts.splice(hit, 1);
      if (active.durability.noise?.length) active.durability.noise.splice(Math.min(hit, active.durability.noise.length - 1), 1);
      commitDurability();
      return;
    }
    if (hit >= 0 && event.button === 0) {
      dragging = { kind: 'durability', index: hit };
      canvas.setPointerCapture(event.pointerId);
      return;
    }
    const segment = nearestSegment(pts, dx, ax, p);
    if (segment.index >= 0 && segment.distance < 10) { selectedSegment = segment.index; fillEditors(); }
  });
  canvas.addEventListener('dblclick', (event) => {  // add a point on a segment
    const p = pointerPos(canvas, event);
    const ax = altitudeAxis(p.rect), dx = durabilityAxis(p.rect.width);
    const pts = active.durability.points;
    const a = ax.toA(p.y);
    const i = pts.findIndex((q) => q[0] > a);
    if (i <= 0) return;
    pts.splice(i, 0, [Number(a.toFixed(4)), Number(Math.max(0.05, dx.toD(p.x)).toFixed(4))]);
    const noise = active.durability.noise;
    if (noise?.length) noise.splice(i - 1, 0, noise[i - 1] ? copy(noise[i - 1]) : null);
    commitDurability();
  });
  canvas.addEventListener('pointermove', (event) => {
    if (dragging?.kind !== 'durability') return;
    const p = pointerPos(canvas, event);
    const ax = altitudeAxis(p.rect), dx = durabilityAxis(p.rect.width);
    const pts = active.durability.points, i = dragging.index;
    pts[i][1] = Number(Math.min(50, Math.max(0.05, dx.toD(p.x))).toFixed(4));
    if (i > 0 && i + 1 < pts.length) {  // inner points move in altitude too, between their neighbours
      const lo = pts[i - 1][0] + 0.005, hi = pts[i + 1][0] - 0.005;
      pts[i][0] = Number(Math.min(hi, Math.max(lo, ax.toA(p.y))).toFixed(4));
    }
  });
  const release = () => {
    if (dragging?.kind !== 'durability') return;
    dragging = null;
    commitDurability();
  };
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);
}

function commitBubbles() { edit({ bubbles: active.bubbles }); }

function setupBubbleGraph() {
  const canvas = $('bubble-graph');
  canvas.addEventListener('pointerdown', (event) => {
    if (!active) return;
    const p = pointerPos(canvas, event);
    const ax = altitudeAxis(p.rect);
    const bands = active.bubbles;
    const boundary = bands.findIndex((b, i) => i + 1 < bands.length && Math.abs(ax.toY(b.up_to) - p.y) < 6);
    if (boundary >= 0) {
      dragging = { kind: 'band', index: boundary };
      canvas.setPointerCapture(event.pointerId);
      return;
    }
    const a = ax.toA(p.y);
    const band = bands.findIndex((b) => a <= b.up_to);
    selectedBand = band >= 0 ? band : bands.length - 1;
    fillEditors();
  });
  canvas.addEventListener('pointermove', (event) => {
    if (dragging?.kind !== 'band') return;
    const p = pointerPos(canvas, event);
    const ax = altitudeAxis(p.rect);
    const bands = active.bubbles, i = dragging.index;
    const lo = (i > 0 ? bands[i - 1].up_to : 0) + 0.01, hi = bands[i + 1].up_to - 0.01;
    bands[i].up_to = Number(Math.min(hi, Math.max(lo, ax.toA(p.y))).toFixed(4));
  });
  const release = () => {
    if (dragging?.kind !== 'band') return;
    dragging = null;
    commitBubbles();
  };
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);
  $('band-split').addEventListener('click', () => {
    const bands = active.bubbles, i = selectedBand;
    const below = i > 0 ? bands[i - 1].up_to : 0;
    const half = copy(bands[i]);
    half.up_to = Number(((below + bands[i].up_to) / 2).toFixed(4));
    bands.splice(i, 0, half);
    commitBubbles();
  });
  $('band-remove').addEventListener('click', () => {
    const bands = active.bubbles;
    if (bands.length <= 1) { showMessage('the bubble graph needs at least one band'); return; }
    const i = selectedBand;
    if (i + 1 === bands.length) bands[i - 1].up_to = 1; // the top band always reaches altitude 1
    bands.splice(i, 1);
    selectedBand = Math.min(i, bands.length - 1);
    commitBubbles();
  });
  const bandField = (id, set) => $(id).addEventListener('change', (e) => {
    const value = Number(e.target.value);
    set(active.bubbles[selectedBand], value);
    commitBubbles();
  });
  bandField('band-radius', (b, v) => { b.bubble = { sphere: { radius: v } }; });
  bandField('band-spheroidal', (b, v) => { b.spheroidal = v; });
  bandField('band-cavernous', (b, v) => { b.cavernous = v; });
}

function setupNoiseEditor() {
  const field = (id, key) => $(id).addEventListener('change', (e) => {
    const pts = active.durability.points;
    const noise = active.durability.noise?.length ? active.durability.noise : new Array(pts.length - 1).fill(null);
    const n = noise[selectedSegment] || { amplitude: 0.2, period: 0.8, octaves: 2 };
    n[key] = Number(e.target.value);
    noise[selectedSegment] = n;
    active.durability.noise = noise;
    commitDurability();
  });
  field('noise-amplitude', 'amplitude');
  field('noise-period', 'period');
  field('noise-octaves', 'octaves');
  $('noise-clear').addEventListener('click', () => {
    if (!active.durability.noise?.length) return;
    active.durability.noise[selectedSegment] = null;
    commitDurability();
  });
}

function setupResponseEditor() {
  const canvas = $('response-graph');
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  $('response-kind').addEventListener('change', (e) => {
    const kind = e.target.value;
    active.response = kind === 'power' ? { power: 1 } : kind === 'threshold' ? { threshold: 0.5 } : { curve: [[0, 0], [0.5, 0.2], [1, 1]] };
    edit({ response: active.response });
  });
  $('response-value').addEventListener('change', (e) => {
    const kind = Object.keys(active.response)[0];
    if (kind === 'curve') return;
    active.response = { [kind]: Number(e.target.value) };
    edit({ response: active.response });
  });
  canvas.addEventListener('pointerdown', (event) => {
    if (!active || !('curve' in active.response)) return;
    const p = pointerPos(canvas, event);
    const a = responseAxes(p.rect.width, p.rect.height);
    const c = active.response.curve;
    const hit = c.findIndex(([x, y]) => Math.hypot(a.toX(x) - p.x, a.toY(y) - p.y) < 8);
    if (hit >= 0 && event.button === 2) {
      if (hit === 0 || hit === c.length - 1) return;  // the curve runs from x = 0 to x = 1
      c.splice(hit, 1);
      edit({ response: active.response });
    } else if (hit >= 0) {
      dragging = { kind: 'response', index: hit };
      canvas.setPointerCapture(event.pointerId);
    }
  });
  canvas.addEventListener('dblclick', (event) => {
    if (!('curve' in active.response)) return;
    const p = pointerPos(canvas, event);
    const a = responseAxes(p.rect.width, p.rect.height);
    const x = a.fromX(p.x), c = active.response.curve;
    const i = c.findIndex((q) => q[0] > x);
    if (i <= 0) return;
    c.splice(i, 0, [Number(x.toFixed(4)), Number(Math.min(1, Math.max(0, a.fromY(p.y))).toFixed(4))]);
    edit({ response: active.response });
  });
  canvas.addEventListener('pointermove', (event) => {
    if (dragging?.kind !== 'response') return;
    const p = pointerPos(canvas, event);
    const a = responseAxes(p.rect.width, p.rect.height);
    const c = active.response.curve, i = dragging.index;
    if (i > 0 && i + 1 < c.length) c[i][0] = Number(Math.min(c[i + 1][0] - 0.01, Math.max(c[i - 1][0] + 0.01, a.fromX(p.x))).toFixed(4));
    c[i][1] = Number(Math.min(1, Math.max(0, a.fromY(p.y))).toFixed(4));
  });
  const release = () => {
    if (dragging?.kind !== 'response') return;
    dragging = null;
    edit({ response: active.response });
  };
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);
}

function fillEditors() {
  if (!active) return;
  const pts = active.durability.points;
  selectedSegment = Math.min(selectedSegment, pts.length - 2);
  const n = active.durability.noise?.[selectedSegment];
  $('noise-segment').textContent = `${selectedSegment + 1} (altitude ${pts[selectedSegment][0]}–${pts[selectedSegment + 1][0]})`;
  $('noise-amplitude').value = n ? n.amplitude : '';
  $('noise-period').value = n ? n.period : '';
  $('noise-octaves').value = n ? n.octaves : '';
  selectedBand = Math.min(selectedBand, active.bubbles.length - 1);
  const band = active.bubbles[selectedBand];
  const sphere = band.bubble.sphere;
  $('band-radius').value = sphere ? sphere.radius : '';
  $('band-radius').placeholder = sphere ? '' : Object.keys(band.bubble)[0];
  $('band-spheroidal').value = band.spheroidal;
  $('band-cavernous').value = band.cavernous;
  const kind = Object.keys(active.response)[0];
  $('response-kind').value = kind;
  $('response-value-label').style.display = kind === 'curve' ? 'none' : '';
  if (kind !== 'curve') $('response-value').value = active.response[kind];
}

// ---------------------------------------------------------------- transport, save, bake
function setupTransport() {
  $('play').addEventListener('click', () =>
    control(state?.playing ? { action: 'pause' } : { action: 'play', rate: Number($('rate').value) }));
  $('rate').addEventListener('change', () => { if (state?.playing) control({ action: 'play', rate: Number($('rate').value) }); });
  $('step').addEventListener('click', () => control({ action: 'step' }));
  $('reset').addEventListener('click', () => control({ action: 'reset' }));
  const timeline = $('timeline');
  timeline.addEventListener('pointerdown', () => { timelineHeld = true; });
  timeline.addEventListener('change', async () => {
    await control({ seek: Number(timeline.value) });
    timelineHeld = false;
  });
  $('run-until-go').addEventListener('click', () => control({ run_until: Number($('run-until').value) }));
  $('save').addEventListener('click', async () => {
    try {
      const saved = await api('/api/save', { name: $('save-name').value, overwrite: $('save-overwrite').checked });
      showMessage(`saved ${saved.path} (time ${saved.time})`, true);
    } catch (e) { /* shown */ }
  });
  $('bake').addEventListener('click', async () => {
    try {
      const started = await api('/api/bake', {});
      showMessage(`baking into ${started.asset_dir}`, true);
    } catch (e) { /* shown */ }
  });
  $('palette').addEventListener('change', updateMesh);
  $('show-colluvium').addEventListener('change', (e) => { colluviumMesh.visible = e.target.checked; });
}

// ---------------------------------------------------------------- main loop
window.studio = { ready: false, meshVersion: -1, rockTriangles: 0,
  // Page coordinates of durability point i (for scripted tests and tools).
  durabilityPointPage(i) {
    const canvas = $('durability-graph'), rect = canvas.getBoundingClientRect();
    const ax = altitudeAxis(rect), dx = durabilityAxis(rect.width);
    const [a, d] = active.durability.points[i];
    return { x: rect.left + dx.toX(d), y: rect.top + ax.toY(a) };
  },
  durabilityScale: () => durabilityScale,
  // Page rectangle the rock's bounds cover in the 3-D view.
  rockScreenBox() {
    rockMesh.geometry.computeBoundingBox();
    const box = rockMesh.geometry.boundingBox, rect = renderer.domElement.getBoundingClientRect();
    let x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
    for (let i = 0; i < 8; ++i) {
      const p = new THREE.Vector3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z).project(camera);
      const x = rect.left + (p.x + 1) / 2 * rect.width, y = rect.top + (1 - (p.y + 1) / 2) * rect.height;
      x0 = Math.min(x0, x); y0 = Math.min(y0, y); x1 = Math.max(x1, x); y1 = Math.max(y1, y);
    }
    return { x0, y0, x1, y1, background: '#' + background.getHexString() };
  },
};

function animate() {
  requestAnimationFrame(animate);
  if (!state) return;
  if (!framed) { resize(); frameCamera(); }
  controls.update();
  renderer.render(scene, camera);
  drawDurability();
  drawBubbles();
  drawResponse();
}

async function start() {
  setupDurabilityGraph();
  setupBubbleGraph();
  setupNoiseEditor();
  setupResponseEditor();
  setupTransport();
  await refresh();
  if (state) {
    const maxPoint = Math.max(...state.active.durability.points.map((p) => p[1]));
    durabilityScale = Math.max(2, Math.ceil(maxPoint * 1.5));
  }
  animate();
  await updateMesh();
  window.studio.ready = true;
  setInterval(async () => { await refresh(); updateMesh(); }, 200);
}
start();
