// The graphs beside the view (docs/studio.md, "The page"): durability and bubble
// bands on the rock's own altitude scale, the response f as the server samples
// it (the page never evaluates f itself), and the rock volume over time.
import { $ } from './dom.js';
import { state } from './state.js';
import { altitudeToPageY } from './view.js';

export function fitCanvas(canvas) {
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
export function altitudeAxis(rect) {
  let y0 = altitudeToPageY(0) - rect.top, y1 = altitudeToPageY(1) - rect.top;
  if (!(y0 - y1 > 40)) { y0 = rect.height - 12; y1 = 12; }
  return { y0, y1, toY: (a) => y0 + (y1 - y0) * a, toA: (y) => (y - y0) / (y1 - y0) };
}

export function durabilityAxis(w) {
  const left = 10, right = w - 10, scale = state.durabilityScale;
  return { toX: (d) => left + (right - left) * d / scale, toD: (x) => (x - left) / (right - left) * scale };
}

export function responseAxes(w, h) {
  const m = 8;
  return { toX: (x) => m + x * (w - 2 * m), toY: (y) => h - m - y * (h - 2 * m),
           fromX: (px) => (px - m) / (w - 2 * m), fromY: (py) => (h - m - py) / (h - 2 * m) };
}

// Paper Fig. 7: red hues for durable rock, blue for soft.
function durabilityColour(d) {
  const t = Math.max(0, Math.min(1, d / state.durabilityScale));
  return `hsl(${240 - 240 * t}, 75%, 58%)`;
}

export function drawDurability() {
  const { ctx, w, h, rect } = fitCanvas($('durability-graph'));
  ctx.clearRect(0, 0, w, h);
  if (!state.active) return;
  const ax = altitudeAxis(rect), dx = durabilityAxis(w);
  ctx.strokeStyle = '#3b4046';
  ctx.fillStyle = '#8a9096';
  ctx.font = '10px sans-serif';
  for (let d = 0; d <= state.durabilityScale + 1e-9; d += 0.5) {
    ctx.beginPath(); ctx.moveTo(dx.toX(d), ax.toY(0)); ctx.lineTo(dx.toX(d), ax.toY(1)); ctx.stroke();
    if (Math.abs(d - Math.round(d)) < 1e-9) ctx.fillText(String(d), dx.toX(d) + 2, ax.toY(0) + 11);
  }
  for (const a of [0, 1]) { ctx.beginPath(); ctx.moveTo(0, ax.toY(a)); ctx.lineTo(w, ax.toY(a)); ctx.stroke(); }
  const pts = state.active.durability.points, noise = state.active.durability.noise || [];
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
    ctx.lineWidth = i === state.selectedSegment ? 4 : 2;
    ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1); ctx.stroke();
  }
  ctx.lineWidth = 1;
  for (let i = 0; i < pts.length; ++i) {
    const held = state.dragging?.kind === 'durability' && state.dragging.index === i;
    ctx.fillStyle = held ? '#fff' : durabilityColour(pts[i][1]);
    ctx.beginPath(); ctx.arc(dx.toX(pts[i][1]), ax.toY(pts[i][0]), 5, 0, 2 * Math.PI); ctx.fill();
    ctx.strokeStyle = '#111'; ctx.stroke();
  }
}

export function drawBubbles() {
  const { ctx, w, h, rect } = fitCanvas($('bubble-graph'));
  ctx.clearRect(0, 0, w, h);
  if (!state.active) return;
  const ax = altitudeAxis(rect);
  const pixelsPerUnit = (ax.y0 - ax.y1) / state.server.preset.grid.size[2];
  const bands = state.active.bubbles;
  let below = 0;
  bands.forEach((band, b) => {
    const yTop = ax.toY(band.up_to), yBottom = ax.toY(below);
    ctx.fillStyle = b === state.selectedBand ? 'rgba(224,160,96,0.20)' : (b % 2 ? 'rgba(255,255,255,0.05)' : 'rgba(255,255,255,0.09)');
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
    ctx.lineWidth = b + 1 < bands.length ? 2 : 1;
    ctx.beginPath(); ctx.moveTo(0, yTop); ctx.lineTo(w, yTop); ctx.stroke();
    ctx.lineWidth = 1;
    below = band.up_to;
  });
}

// f as the server sampled it (`response_curve` in the state); a curve's points on top.
export function drawResponse() {
  const { ctx, w, h } = fitCanvas($('response-graph'));
  ctx.clearRect(0, 0, w, h);
  if (!state.active) return;
  const a = responseAxes(w, h);
  ctx.strokeStyle = '#3b4046';
  ctx.strokeRect(a.toX(0), a.toY(1), a.toX(1) - a.toX(0), a.toY(0) - a.toY(1));
  ctx.strokeStyle = '#e0a060';
  ctx.lineWidth = 2;
  ctx.beginPath();
  state.server.response_curve.forEach(([x, y], i) => {
    if (i === 0) ctx.moveTo(a.toX(x), a.toY(y)); else ctx.lineTo(a.toX(x), a.toY(y));
  });
  ctx.stroke();
  ctx.lineWidth = 1;
  if ('curve' in state.active.response)
    for (const [x, y] of state.active.response.curve) {
      ctx.fillStyle = '#fff';
      ctx.beginPath(); ctx.arc(a.toX(x), a.toY(y), 4, 0, 2 * Math.PI); ctx.fill();
    }
}

export function drawVolumePlot() {
  const { ctx, w, h } = fitCanvas($('volume-plot'));
  ctx.clearRect(0, 0, w, h);
  const s = state.server;
  if (!s) return;
  const tMax = Math.max(s.end_time, 1e-6), vMax = Math.max(s.initial_rock, 1);
  const X = (t) => 6 + (w - 12) * t / tMax, Y = (v) => h - 6 - (h - 12) * v / vMax;
  ctx.strokeStyle = '#3b4046';
  ctx.strokeRect(6, 6, w - 12, h - 12);
  ctx.strokeStyle = '#e0a060';
  ctx.beginPath();
  ctx.moveTo(X(0), Y(s.initial_rock));
  for (const [t, v] of s.history) ctx.lineTo(X(t), Y(v));
  ctx.stroke();
  ctx.strokeStyle = '#8fd18f';
  ctx.beginPath(); ctx.moveTo(X(s.time), 6); ctx.lineTo(X(s.time), h - 6); ctx.stroke();
  ctx.fillStyle = '#8a9096';
  ctx.font = '10px sans-serif';
  ctx.fillText(`rock volume ${(100 * s.rock / vMax).toFixed(1)}%`, 10, 17);
  for (const t of s.checkpoints) { ctx.fillRect(X(t) - 0.5, h - 10, 1, 4); }
}
