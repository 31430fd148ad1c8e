// The page's one state object (docs/studio.md, "The page"): what the server last
// said, the editable copy of what is in effect, and what the pointer and the
// panels hold. Every module reads and writes this object; nothing else is kept
// between events.
export const state = {
  server: null,        // the last answer with the state (GET /api/state, docs/studio.md)
  active: null,        // {durability, bubbles, response} in effect now: an editable copy
  dragging: null,      // {kind, index} while a pointer drags; new states leave `active` alone meanwhile
  selectedSegment: 0,  // durability segment whose noise the editor shows
  selectedBand: 0,     // bubble band the editor shows
  timelineHeld: false, // the timeline is being dragged: new states leave its value alone
  durabilityScale: 3,  // durability at the graph's right edge
  problemShown: '',    // the server's `problem` last shown (each is shown once)
  mesh: { version: -1, palette: '', loading: false },  // the preview mesh shown
  // The final bake's view: how many finished bakes the page has seen (one finished before it
  // loaded counts; each reloads the view), the one shown (0: none), and what it holds once loaded.
  final: { done: 0, shown: 0, loading: false, triangles: 0, textured: false, history: false },
  bakeState: 'idle',   // the bake's state last seen, to notice one finishing
};

export function copy(x) { return JSON.parse(JSON.stringify(x)); }

const listeners = [];

// `listener(server)` runs after every new state from the server.
export function onServerState(listener) { listeners.push(listener); }

export function receiveServerState(server) {
  state.server = server;
  if (!state.dragging) state.active = copy(server.active);
  for (const listener of listeners) listener(server);
}
