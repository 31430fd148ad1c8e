// Validates .glb files with the Khronos glTF validator.
// Usage: node scripts/gltf-validator/validate.mjs FILE.glb...
// Images and buffers a file names by relative URI (a texture set's maps) are
// read from beside it and validated with it; one that is missing is an error.
// Prints one line per file (errors, warnings, infos) and every error message;
// exits 1 if any file has an error or cannot be read, 2 on no arguments.
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node validate.mjs FILE.glb...');
  process.exit(2);
}
let failed = false;
for (const file of files) {
  try {
    const bytes = new Uint8Array(await readFile(file));
    const report = await validator.validateBytes(bytes, {
      maxIssues: 50,
      uri: file,
      externalResourceFunction: async (uri) =>
        new Uint8Array(await readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)))),
    });
    const { numErrors, numWarnings, numInfos } = report.issues;
    console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos`);
    for (const m of report.issues.messages)
      if (m.severity === 0) console.log(`  error ${m.code} at ${m.pointer ?? '?'}: ${m.message}`);
    if (numErrors > 0) failed = true;
  } catch (error) {
    console.log(`${file}: not validated: ${error}`);
    failed = true;
  }
}
process.exit(failed ? 1 : 0);
