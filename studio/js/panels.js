// The transport, the stats, Save and Bake final (docs/studio.md, "The page"):
// what the page shows of each new state, and the buttons that drive the server.
import { api, control } from './api.js';
import { $, showMessage } from './dom.js';
import { state } from './state.js';
import { fillEditors } from './editors.js';
import { drawVolumePlot } from './graphs.js';
import { showColluvium, showFinal, showFinalBake, updateMesh } from './view.js';

// The panels from a new state (`server`: the state as the server sent it).
export function showServerState(server) {
  $('preset-name').textContent =
    `${server.preset.name} · ${server.grid.nx}×${server.grid.ny}×${server.grid.nz} voxels (resolution ${server.resolution})`;
  $('stat-cycle').textContent = server.cycle;
  $('stat-time').textContent = server.time.toFixed(3);
  $('stat-rock').textContent = server.rock;
  $('stat-exposed').textContent = server.exposed;
  $('stat-colluvium').textContent = server.colluvium;
  $('stat-keyframes').textContent = server.preset.durability.keyframes.length;
  $('play').textContent = server.playing ? 'pause' : 'play';
  const timeline = $('timeline');
  timeline.max = server.end_time;
  timeline.step = server.h;
  if (!state.timelineHeld) timeline.value = server.time;
  $('time-readout').textContent =
    `t = ${server.time.toFixed(2)} / ${server.end_time.toFixed(2)}${server.finished ? ' (end)' : ''}`;
  if (!$('save-name').value) $('save-name').value = `${server.preset.name}-edited`;
  $('bake-progress').value = server.bake.progress;
  $('bake-status').textContent = server.bake.state === 'idle' ? '' : `${server.bake.state}: ${server.bake.message}`;
  noticeFinishedBake(server.bake.state);
  if (server.problem && server.problem !== state.problemShown) showMessage(server.problem);  // why playing stopped
  state.problemShown = server.problem;
  const focus = document.activeElement?.tagName;
  if (focus !== 'INPUT' && focus !== 'SELECT') fillEditors();
  drawVolumePlot();
}

// A bake that finishes makes the final view available, and reloads it when it is the one shown.
function noticeFinishedBake(bakeState) {
  const finished = bakeState === 'done' && state.bakeState !== 'done';
  state.bakeState = bakeState;
  if (!finished) return;
  state.final.done += 1;
  $('view-mode').querySelector('option[value="final"]').disabled = false;
  if ($('view-mode').value === 'final') showFinalBake(state.final.done);
}

function setupSaveAndBake() {
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
}

// The default pace plays the preset's whole run in this many seconds, whatever the preview
// resolution (a finer one runs more, shorter cycles): time to see the rock change and to
// drag a point while it does, so an edit lands as a keyframe mid-run (docs/studio.md).
const kSteerSeconds = 30;

// Cycles per second for the rate menu's choice: a number, or the steering pace from the run's
// length in cycles (end_time / h), at least half a cycle a second.
export function playRate(choice, server) {
  if (choice !== 'steer') return Number(choice);
  const cycles = server && server.h > 0 ? Math.round(server.end_time / server.h) : kSteerSeconds;
  return Math.max(0.5, Math.round((100 * cycles) / kSteerSeconds) / 100);
}

export function setupTransport() {
  const rate = () => playRate($('rate').value, state.server);
  $('play').addEventListener('click', () =>
    control(state.server?.playing ? { action: 'pause' } : { action: 'play', rate: rate() }));
  $('rate').addEventListener('change', () => { if (state.server?.playing) control({ action: 'play', rate: rate() }); });
  $('step').addEventListener('click', () => control({ action: 'step' }));
  $('reset').addEventListener('click', () => control({ action: 'reset' }));
  const timeline = $('timeline');
  timeline.addEventListener('pointerdown', () => { state.timelineHeld = true; });
  timeline.addEventListener('change', async () => {
    await control({ seek: Number(timeline.value) });
    state.timelineHeld = false;
  });
  $('run-until-go').addEventListener('click', () => control({ run_until: Number($('run-until').value) }));
  $('palette').addEventListener('change', updateMesh);
  $('show-colluvium').addEventListener('change', (e) => showColluvium(e.target.checked));
  $('view-mode').addEventListener('change', (e) => {
    const final = e.target.value === 'final';
    if (final && state.final.shown !== state.final.done) showFinalBake(state.final.done);
    else showFinal(final);
  });
  setupSaveAndBake();
}
