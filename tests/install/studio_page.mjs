// The studio page as an installed rockbake serves it: the page, and every module it
// loads, followed import by import (through the page's import map) over HTTP, so a
// three.js file the install rules leave out (cmake/Install.cmake) is a failure here.
// The review page (`--review OUT`, a baked library) is checked the same way.
// Usage: node studio_page.mjs ROCKBAKE PRESET [MARKER]
//        node studio_page.mjs ROCKBAKE --review OUT
//   MARKER: text the page must contain (a page from ROCKBAKE_DATA_DIR's copy).
import { check, raw, startStudio, stopStudio } from '../studio/harness.mjs';
import { startReview, stopReview } from '../review/library.mjs';

const [rockbake, preset, third] = process.argv.slice(2);
const review = preset === '--review';
const marker = review ? undefined : third;

// Module specifiers of static imports and re-exports, and of dynamic imports of a literal.
function importsOf(source) {
  const found = new Set();
  const patterns = [
    /\bimport\s+(?:[\w*{}\s,$]+?\s+from\s+)?['"]([^'"]+)['"]/g,
    /\bexport\s+(?:\*|\{[^}]*\})(?:\s+as\s+\w+)?\s+from\s+['"]([^'"]+)['"]/g,
    /\bimport\(\s*['"]([^'"]+)['"]\s*\)/g,
  ];
  for (const pattern of patterns) for (const m of source.matchAll(pattern)) found.add(m[1]);
  return [...found];
}

// A specifier to a URL, as a browser resolves it: relative and absolute paths against the
// importing module, bare names through the import map (exact keys, then the longest prefix
// key ending in '/').
function resolve(specifier, base, importMap) {
  if (/^(\/|\.\/|\.\.\/)/.test(specifier)) return new URL(specifier, base).href;
  if (importMap[specifier]) return new URL(importMap[specifier], base).href;
  const prefix = Object.keys(importMap)
    .filter((key) => key.endsWith('/') && specifier.startsWith(key))
    .sort((a, b) => b.length - a.length)[0];
  if (!prefix) throw new Error(`FAILED: '${specifier}' (imported by ${base}) is not in the page's import map`);
  return new URL(importMap[prefix] + specifier.slice(prefix.length), base).href;
}

async function get(url) {
  const u = new URL(url);
  const response = await raw(url, 'GET', u.pathname);
  check(response.status === 200, `GET ${u.pathname}: ${response.status}`);
  return response;
}

const studio = review ? await startReview(rockbake, third) : await startStudio(rockbake, [preset, '--resolution', '16']);
try {
  const page = (await get(studio.url)).body.toString();
  if (marker) check(page.includes(marker), `the page is the one in ROCKBAKE_DATA_DIR (it holds '${marker}')`);
  const mapText = page.match(/<script type="importmap">([\s\S]*?)<\/script>/);
  check(mapText !== null, 'the page has an import map');
  const importMap = JSON.parse(mapText[1]).imports;
  const pending = [...page.matchAll(/<script type="module" src="([^"]+)"/g)].map((m) => new URL(m[1], studio.url).href);
  check(pending.length > 0, 'the page loads a module');
  const fetched = new Set();
  while (pending.length > 0) {
    const url = pending.pop();
    if (fetched.has(url)) continue;
    fetched.add(url);
    const response = await get(url);
    check(/javascript/.test(response.headers['content-type'] ?? ''), `${new URL(url).pathname} is served as JavaScript`);
    for (const specifier of importsOf(response.body.toString())) pending.push(resolve(specifier, url, importMap));
  }
  const three = [...fetched].filter((url) => new URL(url).pathname.startsWith('/vendor/three/'));
  check(three.some((url) => url.endsWith('/build/three.module.js')), 'three.module.js is among the modules');
  console.log(`ok: ${fetched.size} modules fetched, ${three.length} of them three.js`);
} finally {
  const code = review ? await stopReview(studio) : await stopStudio(studio);
  check(code === 0, `the server stops on Ctrl-C with exit status 0 (got ${code})`);
}
