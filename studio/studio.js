// rockbake studio page (docs/studio.md): talks to the server only through the
// JSON API (js/api.js). The 3-D view (js/view.js) shows the preview mesh; the
// durability and bubble graphs (js/graphs.js, js/editors.js) sit beside it with
// altitude on the same screen scale as the rock, so a point dragged to a height
// edits the rock at that height. All the page holds is one object (js/state.js).
import { refresh } from './js/api.js';
import { $ } from './js/dom.js';
import { onServerState, state } from './js/state.js';
import { setupBubbleGraph, setupDurabilityGraph, setupNoiseEditor, setupResponseEditor } from './js/editors.js';
import { altitudeAxis, drawBubbles, drawDurability, drawResponse, durabilityAxis } from './js/graphs.js';
import { setupTransport, showServerState } from './js/panels.js';
import { renderView, rockScreenBox, updateMesh } from './js/view.js';

// For scripted tests and tools (tests/studio/browser_test.mjs).
window.studio = {
  ready: false,
  get meshVersion() { return state.mesh.version; },
  get rockTriangles() { return state.mesh.triangles ?? 0; },
  // The final bake's view once loaded: {shown, triangles, textured, history} (shown 0: none yet).
  get finalView() { const f = state.final; return { shown: f.shown, triangles: f.triangles, textured: f.textured, history: f.history }; },
  // Page coordinates of durability point i.
  durabilityPointPage(i) {
    const rect = $('durability-graph').getBoundingClientRect();
    const ax = altitudeAxis(rect), dx = durabilityAxis(rect.width);
    const [a, d] = state.active.durability.points[i];
    return { x: rect.left + dx.toX(d), y: rect.top + ax.toY(a) };
  },
  durabilityScale: () => state.durabilityScale,
  rockScreenBox,
};

function animate() {
  requestAnimationFrame(animate);
  if (!state.server) return;
  renderView();
  drawDurability();
  drawBubbles();
  drawResponse();
}

async function start() {
  onServerState(showServerState);
  setupDurabilityGraph();
  setupBubbleGraph();
  setupNoiseEditor();
  setupResponseEditor();
  setupTransport();
  await refresh();
  if (state.server) {
    const maxPoint = Math.max(...state.server.active.durability.points.map((p) => p[1]));
    state.durabilityScale = Math.max(2, Math.ceil(maxPoint * 1.5));
  }
  animate();
  await updateMesh();
  window.studio.ready = true;
  setInterval(async () => { await refresh(); updateMesh(); }, 200);
}
start();
