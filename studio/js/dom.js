// The page's elements by id, and the message line at the top right (docs/studio.md,
// "The page": every refusal the server sends back appears there).
export const $ = (id) => document.getElementById(id);

let messageTimer = null;

export function showMessage(text, ok = false) {
  const m = $('message');
  m.textContent = text;
  m.className = ok ? 'ok' : '';
  clearTimeout(messageTimer);
  messageTimer = setTimeout(() => { m.textContent = ''; }, ok ? 5000 : 15000);
}
