// The studio's JSON API (docs/studio.md, "JSON API"): the one place the page
// sends a request and reads its answer. A refusal's message is shown and thrown.
import { showMessage } from './dom.js';
import { receiveServerState } from './state.js';

// GET `path`, or POST `body` as JSON; resolves with the answer's JSON.
export async function api(path, body) {
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

export async function refresh() {
  try { receiveServerState(await api('/api/state')); } catch (e) { /* shown */ }
}

export async function control(body) {
  try { receiveServerState(await api('/api/control', body)); } catch (e) { /* shown */ }
}

// An edit (docs/studio.md, "How edits become keyframes"); refused, the page goes
// back to what the server has.
export async function edit(part) {
  try {
    receiveServerState(await api('/api/edit', part));
  } catch (e) {
    await refresh();
  }
}
