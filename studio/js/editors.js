// Editing the durability graph, the bubble bands, the noise of a segment and the
// response (docs/studio.md, "The page"). Pointer work changes `state.active`;
// each finished gesture is one edit sent to the server, whose answer wins.
import { edit } from './api.js';
import { $, showMessage } from './dom.js';
import { copy, state } from './state.js';
import { altitudeAxis, durabilityAxis, responseAxes } from './graphs.js';

function pointerPos(canvas, event) {
  const r = canvas.getBoundingClientRect();
  return { x: event.clientX - r.left, y: event.clientY - r.top, rect: r };
}

// Ends a drag of `kind` (pointerup or pointercancel) with `commit`.
function releaseDrag(canvas, kind, commit) {
  const release = () => {
    if (state.dragging?.kind !== kind) return;
    state.dragging = null;
    commit();
  };
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);
}

function commitDurability() {
  const { points, noise } = state.active.durability;
  edit({ durability: { points, noise } });
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

function durabilityPointerDown(canvas, event) {
  if (!state.active) return;
  const p = pointerPos(canvas, event);
  const ax = altitudeAxis(p.rect), dx = durabilityAxis(p.rect.width);
  const { durability } = state.active, pts = durability.points;
  const hit = pts.findIndex(([a, d]) => Math.hypot(dx.toX(d) - p.x, ax.toY(a) - p.y) < 9);
  if (hit >= 0 && event.button === 2) {  // remove a point; its two segments merge (the lower keeps its noise)
    if (pts.length <= 2) { showMessage('the durability graph needs at least two points'); return; }
    pts.splice(hit, 1);
    if (durability.noise?.length) durability.noise.splice(Math.min(hit, durability.noise.length - 1), 1);
    commitDurability();
    return;
  }
  if (hit >= 0 && event.button === 0) {
    state.dragging = { kind: 'durability', index: hit };
    canvas.setPointerCapture(event.pointerId);
    return;
  }
  const segment = nearestSegment(pts, dx, ax, p);
  if (segment.index >= 0 && segment.distance < 10) { state.selectedSegment = segment.index; fillEditors(); }
}

export function setupDurabilityGraph() {
  const canvas = $('durability-graph');
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (event) => durabilityPointerDown(canvas, event));
  canvas.addEventListener('dblclick', (event) => {  // add a point on a segment
    const p = pointerPos(canvas, event);
    const ax = altitudeAxis(p.rect), dx = durabilityAxis(p.rect.width);
    const { durability } = state.active, pts = durability.points;
    const a = ax.toA(p.y);
    const i = pts.findIndex((q) => q[0] > a);
    if (i <= 0) return;
    pts.splice(i, 0, [Number(a.toFixed(4)), Number(Math.max(0.05, dx.toD(p.x)).toFixed(4))]);
    const noise = durability.noise;
    if (noise?.length) noise.splice(i - 1, 0, noise[i - 1] ? copy(noise[i - 1]) : null);
    commitDurability();
  });
  canvas.addEventListener('pointermove', (event) => {
    if (state.dragging?.kind !== 'durability') return;
    const p = pointerPos(canvas, event);
    const ax = altitudeAxis(p.rect), dx = durabilityAxis(p.rect.width);
    const pts = state.active.durability.points, i = state.dragging.index;
    pts[i][1] = Number(Math.min(50, Math.max(0.05, dx.toD(p.x))).toFixed(4));
    if (i > 0 && i + 1 < pts.length) {  // inner points move in altitude too, between their neighbours
      const lo = pts[i - 1][0] + 0.005, hi = pts[i + 1][0] - 0.005;
      pts[i][0] = Number(Math.min(hi, Math.max(lo, ax.toA(p.y))).toFixed(4));
    }
  });
  releaseDrag(canvas, 'durability', commitDurability);
}

function commitBubbles() { edit({ bubbles: state.active.bubbles }); }

function setupBandButtons() {
  $('band-split').addEventListener('click', () => {
    const bands = state.active.bubbles, i = state.selectedBand;
    const below = i > 0 ? bands[i - 1].up_to : 0;
    const half = copy(bands[i]);
    half.up_to = Number(((below + bands[i].up_to) / 2).toFixed(4));
    bands.splice(i, 0, half);
    commitBubbles();
  });
  $('band-remove').addEventListener('click', () => {
    const bands = state.active.bubbles;
    if (bands.length <= 1) { showMessage('the bubble graph needs at least one band'); return; }
    const i = state.selectedBand;
    if (i + 1 === bands.length) bands[i - 1].up_to = 1;  // the top band always reaches altitude 1
    bands.splice(i, 1);
    state.selectedBand = Math.min(i, bands.length - 1);
    commitBubbles();
  });
  const bandField = (id, set) => $(id).addEventListener('change', (e) => {
    set(state.active.bubbles[state.selectedBand], Number(e.target.value));
    commitBubbles();
  });
  bandField('band-radius', (b, v) => { b.bubble = { sphere: { radius: v } }; });
  bandField('band-spheroidal', (b, v) => { b.spheroidal = v; });
  bandField('band-cavernous', (b, v) => { b.cavernous = v; });
}

export function setupBubbleGraph() {
  const canvas = $('bubble-graph');
  canvas.addEventListener('pointerdown', (event) => {
    if (!state.active) return;
    const p = pointerPos(canvas, event);
    const ax = altitudeAxis(p.rect);
    const bands = state.active.bubbles;
    const boundary = bands.findIndex((b, i) => i + 1 < bands.length && Math.abs(ax.toY(b.up_to) - p.y) < 6);
    if (boundary >= 0) {
      state.dragging = { kind: 'band', index: boundary };
      canvas.setPointerCapture(event.pointerId);
      return;
    }
    const a = ax.toA(p.y);
    const band = bands.findIndex((b) => a <= b.up_to);
    state.selectedBand = band >= 0 ? band : bands.length - 1;
    fillEditors();
  });
  canvas.addEventListener('pointermove', (event) => {
    if (state.dragging?.kind !== 'band') return;
    const p = pointerPos(canvas, event);
    const ax = altitudeAxis(p.rect);
    const bands = state.active.bubbles, i = state.dragging.index;
    const lo = (i > 0 ? bands[i - 1].up_to : 0) + 0.01, hi = bands[i + 1].up_to - 0.01;
    bands[i].up_to = Number(Math.min(hi, Math.max(lo, ax.toA(p.y))).toFixed(4));
  });
  releaseDrag(canvas, 'band', commitBubbles);
  setupBandButtons();
}

export function setupNoiseEditor() {
  const field = (id, key) => $(id).addEventListener('change', (e) => {
    const { durability } = state.active;
    const noise = durability.noise?.length ? durability.noise : new Array(durability.points.length - 1).fill(null);
    const n = noise[state.selectedSegment] || { amplitude: 0.2, period: 0.8, octaves: 2 };
    n[key] = Number(e.target.value);
    noise[state.selectedSegment] = n;
    durability.noise = noise;
    commitDurability();
  });
  field('noise-amplitude', 'amplitude');
  field('noise-period', 'period');
  field('noise-octaves', 'octaves');
  $('noise-clear').addEventListener('click', () => {
    if (!state.active.durability.noise?.length) return;
    state.active.durability.noise[state.selectedSegment] = null;
    commitDurability();
  });
}

function commitResponse() { edit({ response: state.active.response }); }

function responseCurvePointer(canvas) {
  canvas.addEventListener('pointerdown', (event) => {
    if (!state.active || !('curve' in state.active.response)) return;
    const p = pointerPos(canvas, event);
    const a = responseAxes(p.rect.width, p.rect.height);
    const c = state.active.response.curve;
    const hit = c.findIndex(([x, y]) => Math.hypot(a.toX(x) - p.x, a.toY(y) - p.y) < 8);
    if (hit >= 0 && event.button === 2) {
      if (hit === 0 || hit === c.length - 1) return;  // the curve runs from x = 0 to x = 1
      c.splice(hit, 1);
      commitResponse();
    } else if (hit >= 0) {
      state.dragging = { kind: 'response', index: hit };
      canvas.setPointerCapture(event.pointerId);
    }
  });
  canvas.addEventListener('dblclick', (event) => {
    if (!('curve' in state.active.response)) return;
    const p = pointerPos(canvas, event);
    const a = responseAxes(p.rect.width, p.rect.height);
    const x = a.fromX(p.x), c = state.active.response.curve;
    const i = c.findIndex((q) => q[0] > x);
    if (i <= 0) return;
    c.splice(i, 0, [Number(x.toFixed(4)), Number(Math.min(1, Math.max(0, a.fromY(p.y))).toFixed(4))]);
    commitResponse();
  });
  canvas.addEventListener('pointermove', (event) => {
    if (state.dragging?.kind !== 'response') return;
    const p = pointerPos(canvas, event);
    const a = responseAxes(p.rect.width, p.rect.height);
    const c = state.active.response.curve, i = state.dragging.index;
    if (i > 0 && i + 1 < c.length) c[i][0] = Number(Math.min(c[i + 1][0] - 0.01, Math.max(c[i - 1][0] + 0.01, a.fromX(p.x))).toFixed(4));
    c[i][1] = Number(Math.min(1, Math.max(0, a.fromY(p.y))).toFixed(4));
  });
  releaseDrag(canvas, 'response', commitResponse);
}

export function setupResponseEditor() {
  const canvas = $('response-graph');
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  $('response-kind').addEventListener('change', (e) => {
    const kind = e.target.value;
    state.active.response = kind === 'power' ? { power: 1 } : kind === 'threshold' ? { threshold: 0.5 } : { curve: [[0, 0], [0.5, 0.2], [1, 1]] };
    commitResponse();
  });
  $('response-value').addEventListener('change', (e) => {
    const kind = Object.keys(state.active.response)[0];
    if (kind === 'curve') return;
    state.active.response = { [kind]: Number(e.target.value) };
    commitResponse();
  });
  responseCurvePointer(canvas);
}

// The editors' fields from `state.active` (the selected segment and band).
export function fillEditors() {
  const { active } = state;
  if (!active) return;
  const pts = active.durability.points;
  state.selectedSegment = Math.min(state.selectedSegment, pts.length - 2);
  const s = state.selectedSegment, n = active.durability.noise?.[s];
  $('noise-segment').textContent = `${s + 1} (altitude ${pts[s][0]}–${pts[s + 1][0]})`;
  $('noise-amplitude').value = n ? n.amplitude : '';
  $('noise-period').value = n ? n.period : '';
  $('noise-octaves').value = n ? n.octaves : '';
  state.selectedBand = Math.min(state.selectedBand, active.bubbles.length - 1);
  const band = active.bubbles[state.selectedBand];
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
